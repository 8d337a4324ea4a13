// DEM walls that move (issue 34): the spheres feel a moving wall's velocity at the contact
// (a sphere on a moving belt ends rolling at 2/7 of the belt's speed, whatever the
// friction), and a free body hit by spheres takes exactly the negatives of their contact
// forces (linear and angular momentum of body and spheres conserved to round-off).
#include "dem_closed_form.hpp"

#include "surge/dem/dem_solver.hpp"
#include "surge/geometry/mass_properties.hpp"
#include "surge/motion/free_body.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

using namespace surge;
using namespace surge::dem;

namespace {
const Vec3 lo{-1, -1, -1}, hi{1, 1, 1};

// The 12 triangles of the box [a, b], wound outwards.
std::vector<geometry::Triangle> box_triangles(const Vec3d& a, const Vec3d& b) {
  const Vec3d c[8] = {{a.x, a.y, a.z}, {b.x, a.y, a.z}, {b.x, b.y, a.z}, {a.x, b.y, a.z},
                      {a.x, a.y, b.z}, {b.x, a.y, b.z}, {b.x, b.y, b.z}, {a.x, b.y, b.z}};
  const int f[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                        {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  std::vector<geometry::Triangle> out;
  for (const auto& t : f) out.push_back({c[t[0]], c[t[1]], c[t[2]]});
  return out;
}

RigidState state_at(const Vec3& pos, const Vec3& vel) {
  RigidState s;
  s.pos = pos;
  s.vel = vel;
  return s;
}
} // namespace

// A sphere at rest on a plane that moves along x at V: friction accelerates it and spins
// it backwards until its contact point moves with the plane, at v = 2/7 V (v grows as
// mu g t, the contact point's speed as 7/2 mu g t). A still plane (the broken variant:
// the wall's velocity left out) leaves it at rest.
TEST(DemMovingWalls, ASphereOnAMovingBeltEndsRollingAtTwoSeventhsOfItsSpeed) {
  for (Real mu : {0.3f, 0.6f}) {
    Material m = test::grains(1e6f, 0.2f, 0.5f);
    m.tan_phi = mu;
    Plane belt;
    belt.body = 0;
    DemSolver s({m}, {belt}, Vec3{0, 0, -9.81f}, lo, hi);
    const Real r = 0.01f;
    s.set_spheres({{{0, 0, r}, {}, {}, r, 0}});
    const Real V = 0.5f;
    s.set_wall_bodies({state_at({0, 0, 0}, {})});
    const Real dt = s.critical_dt(0.05f);
    // settle on the still belt, then run it
    for (int k = 0; k < 2000; ++k) s.step(dt);
    s.move_walls({state_at({0, 0, 0}, {V, 0, 0})});
    const double t_roll = 2 * V / (7 * mu * 9.81); // sliding ends
    double t = 0, v = 0, contact = 0;
    int n = 0;
    float belt_x = 0;
    while (t < 3 * t_roll + 0.1) {
      s.step(dt);
      t += dt;
      belt_x += V * dt;
      s.move_walls({state_at({belt_x, 0, 0}, {V, 0, 0})});
      if (t < 3 * t_roll) continue;
      // the last 0.1 s, averaged over the tangential spring's small rocking
      const Sphere sp = s.spheres()[0];
      v += sp.vel.x;
      contact += sp.vel.x - sp.omega.y * r; // the contact point's speed
      ++n;
    }
    EXPECT_NEAR(v / n, 2 * V / 7, 0.01 * V) << "mu " << mu;
    EXPECT_NEAR(contact / n, V, 0.01 * V) << "mu " << mu; // rolling on the belt
    EXPECT_NEAR(s.spheres()[0].pos.z, r, 5e-3 * r);       // resting on it (overlap m g / k_n = 0.002 r)
  }
}

// A free cube (10 cm, 500 kg/m^3) thrown off-centre into a cluster of spheres, without
// gravity or still walls: what the spheres gain the body loses, so the total linear and
// angular momentum (about the origin) stay as they were, to float round-off.
TEST(DemMovingWalls, AFreeBodyHittingSpheresConservesMomentum) {
  const Material m = test::grains(1e6f, 0.2f, 0.5f);
  const double a = 0.05;
  const auto tris = box_triangles({-a, -a, -a}, {a, a, a});
  geometry::Mesh mesh;
  mesh.tris = tris;
  const geometry::MassProperties mp = geometry::mesh_mass_properties(mesh);
  BodySpec spec;
  spec.free = true;
  spec.velocity = {1.0, 0, 0};
  spec.spin = {0, 0, 2.0};
  const double mass = 500 * mp.volume;
  motion::Matrix3 inertia{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) inertia[i][j] = mp.inertia[i][j] * 500;
  motion::FreeBody body(spec, mass, mp.centroid, inertia, {0, 0, 0});

  DemSolver s({m}, {}, Vec3{}, lo, hi);
  std::vector<WallTriangle> wt;
  for (const auto& t : tris) wt.push_back({Vec3(t.a), Vec3(t.b), Vec3(t.c), 0, 0, 0});
  s.set_wall_triangles(wt);
  const Real r = 0.01f;
  std::vector<Sphere> sp;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 2; ++i)
        sp.push_back({{0.075f + 0.0201f * static_cast<Real>(i), -0.01f + 0.0201f * static_cast<Real>(j),
                       -0.02f + 0.0201f * static_cast<Real>(k)},
                      {},
                      {},
                      r,
                      0});
  s.set_spheres(sp);
  const auto pose_state = [&] { return motion::rigid_state(body.pose(), mp.centroid); };
  s.set_wall_bodies({motion::rigid_state(motion::Pose{}, mp.centroid)});
  s.move_walls({pose_state()});
  const double rho = m.density;
  auto totals = [&](Vec3d& p, Vec3d& l) {
    p = body.momentum();
    l = cross(body.centre(), body.momentum()) + body.angular_momentum();
    for (const auto& x : s.spheres()) {
      const double ms = rho * 4.0 / 3.0 * M_PI * std::pow(static_cast<double>(x.radius), 3);
      p += Vec3d(x.vel) * ms;
      l += cross(Vec3d(x.pos), Vec3d(x.vel) * ms) + Vec3d(x.omega) * (0.4 * ms * x.radius * x.radius);
    }
  };
  Vec3d p0, l0;
  totals(p0, l0);
  // Until the collision is over (no contact for 500 steps): in free flight afterwards the
  // float positions' rounding alone moves the spheres' x m v by about 1e-8 per 1,000 steps.
  const Real dt = s.critical_dt(0.05f);
  int free_steps = 0, k = 0;
  for (; k < 100000 && free_steps < 500; ++k) {
    s.step(dt);
    const WallLoadD ld = s.body_loads()[0];
    body.advance(ld.force, ld.moment, dt);
    s.move_walls({pose_state()});
    free_steps = norm(ld.force) > 0 ? 0 : free_steps + 1;
  }
  ASSERT_LT(k, 100000);
  Vec3d p1, l1;
  totals(p1, l1);
  const double p_scale = norm(p0), l_scale = norm(l0) + a * norm(p0);
  std::printf("after %d steps: momentum change %.3g, angular momentum change %.3g (relative)\n", k,
              norm(p1 - p0) / p_scale, norm(l1 - l0) / l_scale);
  EXPECT_LT(norm(p1 - p0) / p_scale, 1e-5) << p1.x << " " << p1.y << " " << p1.z;
  EXPECT_LT(norm(l1 - l0) / l_scale, 1e-5) << l1.x << " " << l1.y << " " << l1.z;
  // The collision happened: the body lost a good part of its momentum to the spheres.
  EXPECT_LT(body.momentum().x, 0.9 * p0.x);
  double sphere_px = 0;
  for (const auto& x : s.spheres()) sphere_px += x.vel.x;
  EXPECT_GT(sphere_px, 0.1);
}
