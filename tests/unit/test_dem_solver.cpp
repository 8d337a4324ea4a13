// The DEM solver against closed forms: two-sphere impact, a sphere rolling down an
// incline (a = 5/7 g sin theta), rolling resistance stopping a sphere (stopping
// distance v0^2 / (2 * 5/7 k_max g)); momentum conservation; thread independence.
#include "dem_closed_form.hpp"

#include "surge/dem/dem_solver.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

using namespace surge;
using namespace surge::dem;

namespace {
const Vec3 lo{-1, -1, -1}, hi{1, 1, 1};
Material grains(Real e) { return test::grains(1e6f, 0.2f, e); }
} // namespace

TEST(DemSolver, HeadOnImpactMatchesTheClippedOscillator) {
  for (Real e : {0.5f, 0.9f}) {
    DemSolver s({grains(e)}, {}, Vec3{}, lo, hi);
    const Real r = 0.01f;
    s.set_spheres({{{-r, 0, 0}, {0.5f, 0, 0}, {}, r, 0}, {{r, 0, 0}, {-0.5f, 0, 0}, {}, r, 0}});
    const Real dt = s.critical_dt(0.01f);
    double t = 0, t_on = -1, t_off = -1;
    for (int k = 0; k < 200000 && t_off < 0; ++k) {
      s.step(dt);
      t += dt;
      const auto sp = s.spheres();
      const bool touching = sp[1].pos.x - sp[0].pos.x < 2 * r;
      if (touching && t_on < 0) t_on = t;
      if (!touching && t_on >= 0) t_off = t;
    }
    const auto sp = s.spheres();
    const test::Impact cf = test::closed_form(e, 1.0);
    const double e_sim = (sp[1].vel.x - sp[0].vel.x) / 1.0;
    // Tolerance 2 % (the issue's); float state and a step of 1 % of sqrt(m/k_n).
    EXPECT_NEAR(e_sim, cf.restitution, 0.02 * cf.restitution) << "e = " << e;
    EXPECT_NEAR(t_off - t_on, cf.duration, 0.02 * cf.duration) << "e = " << e;
    EXPECT_NEAR(sp[0].vel.x + sp[1].vel.x, 0.0f, 1e-6f); // equal masses: momentum stays zero
  }
}

TEST(DemSolver, MomentumConservedInACollidingCloud) {
  // 343 touching spheres with random velocities, no gravity, no walls: every contact
  // force is applied with opposite signs to its two spheres, so momentum changes only
  // by round-off (float, relative 1e-5 of sum |m v|).
  DemSolver s({grains(0.5f)}, {}, Vec3{}, lo, hi);
  std::vector<Sphere> sp;
  std::mt19937 rng(3);
  std::normal_distribution<float> nd(0, 0.3f);
  for (int k = 0; k < 7; ++k)
    for (int j = 0; j < 7; ++j)
      for (int i = 0; i < 7; ++i)
        sp.push_back({{0.0199f * static_cast<Real>(i), 0.0199f * static_cast<Real>(j), 0.0199f * static_cast<Real>(k)},
                      {nd(rng), nd(rng), nd(rng)},
                      {nd(rng) * 10, nd(rng) * 10, nd(rng) * 10},
                      0.01f,
                      0});
  s.set_spheres(sp);
  auto momentum = [&] {
    Vec3d p{};
    double scale = 0;
    for (const auto& x : s.spheres()) {
      p += Vec3d(x.vel);
      scale += norm(Vec3d(x.vel));
    }
    return std::make_pair(p, scale);
  };
  const auto [p0, scale] = momentum();
  const Real dt = s.critical_dt(0.1f);
  for (int k = 0; k < 300; ++k) s.step(dt);
  const auto [p1, unused] = momentum();
  EXPECT_LT(norm(p1 - p0) / scale, 1e-5);
  EXPECT_GT(norm(Vec3d(s.spheres()[0].vel) - Vec3d(sp[0].vel)), 1e-3); // they did collide
}

TEST(DemSolver, SameResultOnOneAndTwoThreads) {
  auto run = [](int threads) {
    par::set_threads(threads);
    DemSolver s({grains(0.5f)}, {{{0, 0, -0.2f}, {0, 0, 1}, 0}}, Vec3{0, 0, -9.81f}, lo, hi);
    std::vector<Sphere> sp;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-0.001f, 0.001f);
    for (int k = 0; k < 6; ++k)
      for (int j = 0; j < 6; ++j)
        for (int i = 0; i < 6; ++i)
          sp.push_back({{0.02f * static_cast<Real>(i) + u(rng), 0.02f * static_cast<Real>(j) + u(rng),
                         -0.19f + 0.02f * static_cast<Real>(k)},
                        {},
                        {},
                        0.01f,
                        0});
    s.set_spheres(sp);
    const Real dt = s.critical_dt(0.1f);
    for (int k = 0; k < 500; ++k) s.step(dt);
    return s.spheres();
  };
  const auto a = run(1), b = run(2);
  par::set_threads(2);
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].pos.x, b[i].pos.x) << i;
    ASSERT_EQ(a[i].pos.z, b[i].pos.z) << i;
    ASSERT_EQ(a[i].omega.y, b[i].omega.y) << i;
  }
}

TEST(DemSolver, SphereRollsDownAnInclineAtFiveSeventhsGSinTheta) {
  const Real theta = Real(20 * pi / 180), g = 9.81f, r = 0.01f;
  const Vec3 n{-std::sin(theta), 0, std::cos(theta)}; // plane z = x tan(theta) through the origin
  DemSolver s({grains(0.5f)}, {{{0, 0, 0}, n, 0}}, Vec3{0, 0, -g}, lo, hi);
  s.set_spheres({{n * r, {}, {}, r, 0}});
  const Real dt = s.critical_dt(0.05f);
  const Vec3 down{-std::cos(theta), 0, -std::sin(theta)}; // downhill is -x
  double t = 0, v1 = 0, t1 = 0;
  for (int k = 0; t < 0.3; ++k) {
    s.step(dt);
    t += dt;
    if (t1 == 0 && t >= 0.1) {
      t1 = t;
      v1 = dot(Vec3d(s.spheres()[0].vel), Vec3d(down));
    }
  }
  const double v2 = dot(Vec3d(s.spheres()[0].vel), Vec3d(down));
  const double a = (v2 - v1) / (t - t1);
  const double expected = 5.0 / 7.0 * g * std::sin(theta);
  EXPECT_NEAR(a, expected, 0.02 * expected); // 2 %, the tolerance
  // Rolling without slip: w r = v.
  EXPECT_NEAR(std::fabs(s.spheres()[0].omega.y) * r, v2, 0.02 * v2);
}

TEST(DemSolver, RollingResistanceStopsASphereAtTheClosedFormDistance) {
  // On a flat plane, a rolling sphere with rolling resistance at its cap decelerates at
  // a = M_max / (r (m + I/r^2)) = 5/7 k_max g; it stops after v0^2 / (2 a).
  Material m = grains(0.5f);
  m.k_roll = 1.0f;
  m.k_roll_max = 0.05f;
  const Real g = 9.81f, r = 0.01f, v0 = 0.2f;
  DemSolver s({m}, {{{0, 0, 0}, {0, 0, 1}, 0}}, Vec3{0, 0, -g}, lo, hi);
  s.set_spheres({{{0, 0, r - 2.05e-5f}, {v0, 0, 0}, {0, v0 / r, 0}, r, 0}}); // resting overlap m g / k_n
  const Real dt = s.critical_dt(0.05f);
  for (int k = 0; k < 200000; ++k) {
    s.step(dt);
    if (std::fabs(s.spheres()[0].vel.x) < 1e-4f && k > 100) break;
  }
  const double expected = v0 * v0 / (2 * 5.0 / 7.0 * m.k_roll_max * g);
  EXPECT_NEAR(s.spheres()[0].pos.x, expected, 0.05 * expected); // 5 %: the spring phase at start and end
  EXPECT_LT(std::fabs(s.spheres()[0].vel.x), 1e-3f);
}

namespace {
// A bonded pair of touching spheres (r = 1 cm, no damping) flung apart at 0.6 m/s (along x) or
// sheared (along y) at 2 m/s (the spheres also spin up, which slows the shear), enough
// for the bond spring to exceed its strength; the step (0.2 % of sqrt(m/k_n)) makes the
// force grow by < 0.7 % of the limit per step. Returns the largest bond force before it broke and the number of broken
// bonds.
struct BondTest {
  double max_force = 0;
  long broken = 0;
  long bonds = 0;
};
BondTest load_bond(bool shear) {
  Material m = grains(1.0f);
  m.bonded = true;
  m.bond_cn = 2e4f; // C_n r'^2 = 2 N
  m.bond_cs = 1e4f; // C_s r'^2 = 1 N
  const Real r = 0.01f, v = shear ? 1.0f : 0.3f;
  DemSolver s({m}, {}, Vec3{}, lo, hi);
  const Vec3 dv = shear ? Vec3{0, v, 0} : Vec3{v, 0, 0};
  s.set_spheres({{{-r, 0, 0}, dv * -1.0f, {}, r, 0}, {{r, 0, 0}, dv, {}, r, 0}});
  BondTest out;
  out.bonds = s.bond_touching(1e-6f);
  const Real dt = s.critical_dt(0.002f);
  for (int k = 0; k < 20000 && s.broken_bonds() == 0; ++k) {
    s.step(dt);
    const Vec3 f = s.forces()[1];
    if (s.broken_bonds() > 0) break; // the force of the breaking step is already frictional
    const auto sp = s.spheres();
    const Vec3 n = (sp[1].pos - sp[0].pos) * (1 / norm(sp[1].pos - sp[0].pos));
    const double fn = dot(f, n); // > 0: tension on sphere 1
    const double fs = norm(f - n * static_cast<Real>(fn));
    // Shear: the load relative to the limit |F_n| tan(phi) + C_s r'^2 (the sheared pair also
    // stretches a little, so |F_n| is not zero). Tension: the normal force.
    out.max_force = std::max(out.max_force, shear ? fs / (std::fabs(fn) * static_cast<double>(m.tan_phi) + 1.0) : -fn);
  }
  out.broken = s.broken_bonds();
  return out;
}
} // namespace

TEST(DemSolver, BondBreaksInTensionAtCnR2) {
  const BondTest b = load_bond(false);
  EXPECT_EQ(b.bonds, 1);
  EXPECT_EQ(b.broken, 1);
  EXPECT_NEAR(b.max_force, 2.0, 0.01 * 2.0); // 1 %, the tolerance
}

TEST(DemSolver, BondBreaksInShearAtItsShearLimit) {
  // max_force here is the largest |F_s| / (|F_n| tan(phi) + C_s r'^2): it must reach 1
  // (within 1 %) and never exceed it.
  const BondTest b = load_bond(true);
  EXPECT_EQ(b.broken, 1);
  EXPECT_NEAR(b.max_force, 1.0, 0.01 * 1.0);
}

namespace {
// Runs a sphere (r = 1 cm) on a flat triangle mesh in the plane z = 0 and returns
// the largest deviation of the contact force's z-component from m g over the run.
double worst_normal_force_error(const std::vector<WallTriangle>& tris, Vec3 start, Vec3 vel, int steps) {
  const Real g = 9.81f, r = 0.01f;
  DemSolver s({grains(0.5f)}, {}, Vec3{0, 0, -g}, lo, hi);
  s.set_wall_triangles(tris);
  const Real mass = 2500 * Real(4.0 / 3.0 * pi) * r * r * r;
  const Real kn = normal_stiffness(1e6f, r, 1e6f, r);
  start.z = r - mass * g / kn;                                         // resting overlap m g / k_n: no bounce
  s.set_spheres({{start, vel, Vec3{-vel.y / r, vel.x / r, 0}, r, 0}}); // rolling without slip
  const Real dt = s.critical_dt(0.05f);
  double worst = 0;
  for (int k = 0; k < steps; ++k) {
    s.step(dt);
    worst = std::max(worst, std::fabs(static_cast<double>(s.forces()[0].z) / (mass * g) - 1.0));
  }
  return worst;
}
} // namespace

TEST(DemSolver, SphereRollingAcrossASharedEdgeFeelsOneContinuousNormalForce) {
  // A square split along its diagonal; the sphere rolls across the diagonal edge. Two
  // contacts there would double the normal force; the tolerance (2 % of m g) allows the
  // small spring oscillation only.
  const std::vector<WallTriangle> quad = {{{-0.1f, -0.1f, 0}, {0.1f, -0.1f, 0}, {0.1f, 0.1f, 0}, 0, 0},
                                          {{-0.1f, -0.1f, 0}, {0.1f, 0.1f, 0}, {-0.1f, 0.1f, 0}, 0, 0}};
  // 0.3 m/s along x from x = -0.03, y = 0.01: crosses the diagonal x = y at x = 0.01 m.
  EXPECT_LT(worst_normal_force_error(quad, {-0.03f, 0.01f, 0}, {0.3f, 0, 0}, 2000), 0.02);
}

TEST(DemSolver, SphereOnAMeshVertexIsHeldOnce) {
  // Six triangles meeting at the origin, the sphere resting right above the shared vertex.
  std::vector<WallTriangle> fan;
  for (int k = 0; k < 6; ++k) {
    const Real a0 = Real(k * pi / 3), a1 = Real((k + 1) * pi / 3);
    fan.push_back({{0, 0, 0},
                   {0.05f * std::cos(a0), 0.05f * std::sin(a0), 0},
                   {0.05f * std::cos(a1), 0.05f * std::sin(a1), 0},
                   0,
                   0});
  }
  EXPECT_LT(worst_normal_force_error(fan, {0, 0, 0}, {0, 0, 0}, 1000), 0.02);
}

namespace {
// A bonded 3 x 3 x 2 block of spheres (r = 1 cm, phi = 30 deg) resting on a plane tilted
// by theta; returns how far its centre moved along the slope from 0.15 s to 0.3 s.
double bonded_block_slide(double theta_deg) {
  const Real theta = static_cast<Real>(theta_deg * pi / 180), r = 0.01f, g = 9.81f;
  Material m = grains(0.5f);
  m.bonded = true;
  m.bond_cn = 1e6f;
  m.bond_cs = 1e6f;
  m.k_roll = 0.5f;
  m.k_roll_max = 0.1f;
  const Vec3 n{-std::sin(theta), 0, std::cos(theta)}, along{std::cos(theta), 0, std::sin(theta)};
  const Vec3 across{0, 1, 0};
  DemSolver s({m}, {{{0, 0, 0}, n, 0}}, Vec3{0, 0, -g}, lo, hi);
  // Without rolling resistance (k_roll above) the bottom spheres roll on the plane and
  // the block creeps down a 20 deg slope at about 4 mm/s, with or without local damping
  // (measured; see docs/validation.md). Local damping settles the start.
  s.set_local_damping(0.7f);
  std::vector<Sphere> sp;
  const Real rest = r - 2.0e-5f; // about the resting overlap
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i)
        sp.push_back({along * (2 * r * static_cast<Real>(i)) + across * (2 * r * static_cast<Real>(j)) +
                          n * (rest + 2 * r * static_cast<Real>(k)),
                      {},
                      {},
                      r,
                      0});
  s.set_spheres(sp);
  EXPECT_GT(s.bond_touching(1e-5f), 20);
  auto centre = [&] {
    Vec3d c{};
    for (const auto& x : s.spheres()) c += Vec3d(x.pos);
    return c * (1.0 / 18);
  };
  const Real dt = s.critical_dt(0.05f);
  for (double t = 0; t < 0.15; t += static_cast<double>(dt)) s.step(dt); // settle onto the contact springs
  const Vec3d c0 = centre();
  for (double t = 0; t < 0.15; t += static_cast<double>(dt)) s.step(dt);
  EXPECT_EQ(s.broken_bonds(), 0);
  return std::fabs(dot(centre() - c0, Vec3d(along)));
}
} // namespace

TEST(DemSolver, BondedBlockStaysBelowTheFrictionAngleAndSlidesAbove) {
  // Below phi = 30 deg the settled block moves less than 0.1 mm in 0.15 s; above it, it
  // slides: at 40 deg undamped (sin - cos tan phi) g gives 6 cm in that window, local
  // damping 0.7 leaves 30 % of the driving force.
  EXPECT_LT(bonded_block_slide(20), 1e-4);
  EXPECT_GT(bonded_block_slide(40), 0.01);
}

// Wall gauges: a column of three spheres at rest on a floor presses on it with its
// weight, F_z = -3 m g, and the moment about the origin is r x F of that load, with r the
// column's position: M = (x, y, 0) x (0, 0, -W) = (-y W, x W, 0) (relative 1e-3: the column settles
// with local damping; float). The same on a floor made of two triangles of one mesh.
TEST(DemSolver, WallGaugeReadsTheWeightOfARestingColumn) {
  const Real r = 0.01f, g = 9.81f;
  const Vec3 x0{0.3f, -0.2f, 0};
  for (bool mesh : {false, true}) {
    std::vector<Plane> planes;
    if (!mesh) planes.push_back({{0, 0, 0}, {0, 0, 1}, 0});
    DemSolver s({grains(0.5f)}, planes, Vec3{0, 0, -g}, lo, hi);
    if (mesh)
      s.set_wall_triangles({{{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, 0, 0}, {{-1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, 0, 0}});
    std::vector<Sphere> sp;
    for (int k = 0; k < 3; ++k) sp.push_back({x0 + Vec3{0, 0, r * static_cast<Real>(1 + 2 * k)}, {}, {}, r, 0});
    s.set_spheres(sp);
    s.set_local_damping(0.7f);
    const Real dt = s.critical_dt(0.1f);
    for (int k = 0; k < 4000; ++k) s.step(dt);
    const double m = 2500.0 * 4.0 / 3.0 * pi * r * r * r, w = 3 * m * g;
    const WallLoad l = mesh ? s.wall_load(-1, 0, Vec3{}) : s.wall_load(0, -1, Vec3{});
    EXPECT_NEAR(l.force.z, -w, 1e-3 * w) << (mesh ? "mesh" : "plane");
    EXPECT_NEAR(l.force.x, 0.0, 1e-3 * w);
    EXPECT_NEAR(l.moment.y, x0.x * w, 1e-3 * w * 0.3);
    EXPECT_NEAR(l.moment.x, -x0.y * w, 1e-3 * w * 0.3); // (y e_y) x (-w e_z) = -y w e_x
    // Another wall (or mesh) reads nothing.
    const WallLoad none = mesh ? s.wall_load(-1, 1, Vec3{}) : s.wall_load(1, -1, Vec3{});
    EXPECT_EQ(none.force.z, 0.0f);
  }
}

namespace {
// A sphere of radius 0.1 m with 26 spheres of 0.01 m touching it all round: more partners
// than a sphere can list.
TEST(DemSolver, MoreNeighboursThanAListHoldsIsAnErrorNotAMissedContact) {
  DemSolver s({grains(0.5f)}, {}, Vec3{}, Vec3{-1, -1, -1}, Vec3{1, 1, 1});
  std::vector<Sphere> sp{{{0, 0, 0}, {}, {}, 0.1f, 0}};
  const int n = 26;
  for (int k = 0; k < n; ++k) { // a Fibonacci lattice on the sphere of radius 0.109
    const double z = 1 - (2 * k + 1.0) / n, rho = std::sqrt(1 - z * z), phi = 2.399963229728653 * k;
    sp.push_back({Vec3(Vec3d{rho * std::cos(phi), rho * std::sin(phi), z} * 0.109), {}, {}, 0.01f, 0});
  }
  s.set_spheres(sp);
  EXPECT_THROW(s.step(1e-6f), std::runtime_error);
  // With 12 around it (fewer than the 16 a list holds) the step goes ahead.
  sp.resize(13);
  s.set_spheres(sp);
  EXPECT_NO_THROW(s.step(1e-6f));
}
} // namespace

TEST(DemSolver, RestoredStateContinuesBitwiseWithWallContacts) {
  // Spheres created in shuffled order (ids unrelated to the sorted order) settle on a
  // floor; the state saved half way and restored into a new solver continues exactly as
  // the straight run: the wall histories (rows by id, saved in sorted order) come back to
  // their spheres.
  Material m = grains(0.5f);
  m.k_roll = 0.2f;
  m.k_roll_max = 0.05f;
  auto make = [&] { return DemSolver({m}, {{{0, 0, -0.2f}, {0, 0, 1}, 0}}, Vec3{0, 0, -9.81f}, lo, hi); };
  std::vector<Sphere> sp;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-0.002f, 0.002f);
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 6; ++i)
        sp.push_back({{0.021f * static_cast<Real>(i) + u(rng), 0.021f * static_cast<Real>(j) + u(rng),
                       -0.189f + 0.021f * static_cast<Real>(k)},
                      {u(rng) * 100, u(rng) * 100, 0},
                      {},
                      0.01f,
                      0});
  std::shuffle(sp.begin(), sp.end(), rng);
  DemSolver a = make();
  a.set_spheres(sp);
  const Real dt = a.critical_dt(0.1f);
  for (int k = 0; k < 400; ++k) a.step(dt);
  const std::string saved = a.save();
  for (int k = 0; k < 400; ++k) a.step(dt);
  DemSolver b = make();
  b.set_spheres(sp);
  b.restore(saved);
  for (int k = 0; k < 400; ++k) b.step(dt);
  const auto x = a.spheres(), y = b.spheres();
  int on_floor = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    ASSERT_EQ(x[i].pos.x, y[i].pos.x) << i;
    ASSERT_EQ(x[i].pos.z, y[i].pos.z) << i;
    ASSERT_EQ(x[i].omega.y, y[i].omega.y) << i;
    on_floor += x[i].pos.z < -0.185f ? 1 : 0;
  }
  EXPECT_GT(on_floor, 30); // the wall histories were in play
  const WallLoad la = a.wall_load(0, -1, Vec3{}), lb = b.wall_load(0, -1, Vec3{});
  EXPECT_EQ(la.force.z, lb.force.z);
  EXPECT_EQ(la.moment.x, lb.moment.x);
}
