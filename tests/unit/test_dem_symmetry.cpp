// DEM spheres at symmetry faces (DemSolver::set_symmetry): half of a symmetric pack, cut
// at its mirror plane, moves as the whole: bonded spheres on the plane keep their bonds
// to their own and their neighbours' mirror images, a sphere thrown at the plane bounces
// off its image, and a restart continues bit for bit.
#include "dem_closed_form.hpp"

#include "surge/dem/dem_solver.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

using namespace surge;
using namespace surge::dem;

namespace {
constexpr Real r = 0.005f, plane_y = 0.05f;
const Vec3 lo{0, 0, 0}, hi_whole{0.1f, 2 * plane_y, 0.1f}, hi_half{0.1f, plane_y, 0.1f};

Material bonded_grains() {
  Material m = test::grains(1e6f, 0.2f, 0.5f);
  m.bonded = true;
  m.bond_cn = 1e9f; // never breaks: the test follows the bonds, not their strength
  m.bond_cs = 1e9f;
  m.k_roll = 0.1f; // rolling resistance: mirrored spins must load it as the whole does
  return m;
}

// The half (y < 0.05): a bonded row of three spheres touching the plane (each bonded to
// its own image), one bonded behind it, a loose sphere thrown
// at the plane with spin, and one falling with spin away from it. Each has its own
// velocity and spin, so that every bond and contact is loaded.
std::vector<Sphere> half() {
  const Real d = 2 * r, y0 = plane_y - r;
  return {{{0.04f, y0, 0.03f}, {0.1f, 0.02f, 0}, {0, 0, 3}, r, 0},
          {{0.04f + d, y0, 0.03f}, {0.12f, -0.01f, 0.01f}, {1, 0, 0}, r, 0},
          {{0.04f + 2 * d, y0, 0.03f}, {0.1f, 0, -0.02f}, {0, 2, 0}, r, 0},
          {{0.04f + d, y0 - d, 0.03f}, {0.1f, 0.01f, 0}, {0, 0, -1}, r, 0},
          {{0.02f, plane_y - 3 * r, 0.05f}, {0, 0.4f, 0}, {2, -1, 5}, r, 0},
          {{0.08f, 0.02f, 0.06f}, {-0.1f, 0, 0}, {0, 3, 0}, r, 0}};
}

// The mirror image of a sphere in y = plane_y: position 2 y_plane - y (as the solver
// mirrors), the normal velocity reversed, the spin as a pseudovector (det R R w).
Sphere mirrored(Sphere s) {
  s.pos.y = 2 * plane_y - s.pos.y;
  s.vel.y = -s.vel.y;
  s.omega = Vec3{-s.omega.x, s.omega.y, -s.omega.z};
  return s;
}

// The whole: the half and its image, moved along x by dx (a translation changes the
// positions' bits and nothing else: what the whole then differs by is round-off).
std::vector<Sphere> whole(Real dx) {
  std::vector<Sphere> a = half(), b;
  for (const auto& s : a) b.push_back(mirrored(s));
  a.insert(a.end(), b.begin(), b.end());
  for (auto& s : a) s.pos.x += dx;
  return a;
}

struct Pack {
  DemSolver solver;
  long bonds = 0;
  Pack(const Vec3& hi, bool symmetry, const std::vector<Sphere>& spheres)
      : solver({bonded_grains()}, {Plane{{0, 0, 0}, {0, 0, 1}, 0}}, Vec3{0, 0, -9.81f}, lo, hi) {
    if (symmetry) solver.set_symmetry({false, false, false, true, false, false});
    solver.set_spheres(spheres);
    bonds = solver.bond_touching(r * 0.01f);
  }
};

// The largest difference between the half's spheres and the same spheres of a whole run
// (moved by dx): positions over r, velocities over 0.5 m/s, spins times r over
// 0.5 m/s.
double deviation(const std::vector<Sphere>& h, const std::vector<Sphere>& w, Real dx = 0) {
  double d = 0;
  for (std::size_t k = 0; k < h.size(); ++k) {
    const Sphere& b = w[k];
    d = std::max(d, static_cast<double>(norm(h[k].pos + Vec3{dx, 0, 0} - b.pos)) / r);
    d = std::max(d, static_cast<double>(norm(h[k].vel - b.vel)) / 0.5);
    d = std::max(d, static_cast<double>(norm(h[k].omega - b.omega)) * r / 0.5);
  }
  return d;
}
} // namespace

TEST(DemSymmetry, HalfAPackMovesAsTheWhole) {
  constexpr Real dx1 = 0.01f, dx2 = 0.015f;
  Pack h(hi_half, true, half()), w(hi_whole, false, whole(0)), w1(hi_whole, false, whole(dx1)),
      w2(hi_whole, false, whole(dx2));
  Pack cut(hi_half, false, half()); // the broken variant: the plane without its images
  // Bonds: the whole's bonds within each half, twice, and those across the plane, one per
  // mirror bond the half's spheres hold (the row's three, each to its own image).
  const long half_list = cut.bonds;
  EXPECT_EQ(half_list, 3); // the row's two and the one behind it
  EXPECT_EQ(h.bonds, half_list + 3);
  EXPECT_EQ(w.bonds, 2 * half_list + 3);
  const Real dt = h.solver.critical_dt(0.1f);
  for (int k = 0; k < static_cast<int>(0.1f / dt); ++k)
    for (Pack* run : {&h, &w, &w1, &w2, &cut}) run->solver.step(dt);
  const auto a = h.solver.spheres();
  const double dev = deviation(a, w.solver.spheres());
  // Round-off alone: the whole moved along x against the whole.
  const double scale = std::max(deviation(w.solver.spheres(), w1.solver.spheres(), dx1),
                                deviation(w.solver.spheres(), w2.solver.spheres(), dx2));
  const double broken = deviation(cut.solver.spheres(), w.solver.spheres());
  std::printf("half against whole: %.3g; whole against whole moved along x: %.3g; half without its images: %.3g\n", dev,
              scale, broken);
  EXPECT_LT(dev, 4 * scale + 1e-6);
  EXPECT_GT(broken, 100 * (4 * scale + 1e-6)); // the comparison tells the physics apart
  // The thrown sphere came back from its image.
  EXPECT_LT(a[4].vel.y, 0);
  EXPECT_LT(a[4].pos.y, plane_y - r * 0.9f);
  for (const auto& s : a) EXPECT_LE(s.pos.y, plane_y - r * 0.9f);
  // Contact counts (images included) as the whole's, and no bond broken.
  const auto ch = h.solver.contact_counts(), cw = w.solver.contact_counts();
  EXPECT_TRUE(std::equal(ch.begin(), ch.end(), cw.begin()));
  EXPECT_EQ(h.solver.broken_bonds(), 0);
}

TEST(DemSymmetry, ARestartContinuesBitForBit) {
  Pack straight(hi_half, true, half()), first(hi_half, true, half());
  const Real dt = straight.solver.critical_dt(0.1f);
  const int steps = static_cast<int>(0.05f / dt);
  for (int k = 0; k < steps; ++k) {
    straight.solver.step(dt);
    first.solver.step(dt);
  }
  Pack restored(hi_half, true, half());
  restored.solver.restore(first.solver.save());
  for (int k = 0; k < steps; ++k) {
    straight.solver.step(dt);
    restored.solver.step(dt);
  }
  const auto a = straight.solver.spheres(), b = restored.solver.spheres();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(std::memcmp(&a[k].pos, &b[k].pos, sizeof(Vec3)), 0) << k;
    EXPECT_EQ(std::memcmp(&a[k].omega, &b[k].omega, sizeof(Vec3)), 0) << k;
  }
  EXPECT_EQ(straight.solver.save(), restored.solver.save());
}

TEST(DemSymmetry, ASphereAcrossTheFaceIsRefused) {
  DemSolver s({bonded_grains()}, {}, Vec3{}, lo, hi_half);
  s.set_symmetry({false, false, false, true, false, false});
  std::vector<Sphere> sp = half();
  sp[2].pos.y = plane_y - 0.5f * r;
  EXPECT_THROW(s.set_spheres(sp), std::invalid_argument);
}
