// DEM spheres across periodic faces (domain/periodic.hpp): a bonded cluster that crosses
// a face moves bit for bit as the same cluster in a wider box without the face, keeps its
// contacts and bonds when its spheres are moved back by a period, and bonds across a face
// at the start as it would away from one.
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
constexpr Real r = 0.005f, period = 0.1f;
const Vec3 lo{0, -0.05f, -0.05f}, hi_periodic{period, 0.05f, 0.05f}, hi_wide{0.5f, 0.05f, 0.05f};

Material bonded_grains() {
  Material m = test::grains(1e6f, 0.2f, 0.5f);
  m.bonded = true;
  m.bond_cn = 1e9f; // never breaks: the test follows the bonds, not their strength
  m.bond_cs = 1e9f;
  return m;
}

// Four spheres in a touching square (x, y) plus one above its middle, moving along +x at
// 0.5 m/s, each with its own small velocity and spin so that every bond is loaded.
std::vector<Sphere> cluster(Real x0) {
  const Real d = 2 * r;
  std::vector<Sphere> s = {{{x0, 0, 0}, {0.5f, 0.02f, 0}, {0, 0, 3}, r, 0},
                           {{x0 + d, 0, 0}, {0.5f, -0.01f, 0.01f}, {1, 0, 0}, r, 0},
                           {{x0, d, 0}, {0.51f, 0, -0.02f}, {0, 2, 0}, r, 0},
                           {{x0 + d, d, 0}, {0.49f, 0.01f, 0}, {0, 0, -1}, r, 0},
                           {{x0 + r, r, d * 0.70710678f}, {0.5f, 0, 0.01f}, {0, 0, 0}, r, 0}};
  return s;
}

struct Tank {
  DemSolver solver;
  long bonds = 0;
  Tank(const Vec3& hi, bool periodic, const std::vector<Sphere>& spheres)
      : solver({bonded_grains()}, {}, Vec3{}, lo, hi) {
    if (periodic) {
      domain::PeriodicAxes p;
      p.on[0] = 1;
      p.lo = lo;
      p.hi = hi;
      p.len = Vec3{period, 0, 0};
      solver.set_periodic(p);
    }
    solver.set_spheres(spheres);
    bonds = solver.bond_touching(r * 0.01f);
  }
};

// The whole state, bit for bit.
bool same_bits(const std::vector<Sphere>& a, const std::vector<Sphere>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k)
    for (const auto& [u, v] : {std::pair{a[k].pos, b[k].pos}, {a[k].vel, b[k].vel}, {a[k].omega, b[k].omega}})
      if (std::memcmp(&u, &v, sizeof u) != 0) return false;
  return true;
}

// x modulo the period, in [0, period).
double wrapped(double x) { return x - period * std::floor(x / period); }
} // namespace

TEST(DemPeriodic, ClusterCrossingAFaceMovesBitwiseAsInAWiderBox) {
  Tank per(hi_periodic, true, cluster(0.08f)), wide(hi_wide, false, cluster(0.08f));
  ASSERT_EQ(per.bonds, wide.bonds);
  ASSERT_EQ(per.bonds, 8); // the square's four sides and the top sphere's four
  const Real dt = per.solver.critical_dt(0.1f);
  // 0.1 s: the cluster's spheres are 0.03-0.04 m past the face, none half a period
  // beyond it (where a sphere is moved back).
  const int steps = static_cast<int>(0.1f / dt);
  double min_x = 1;
  for (int k = 0; k < steps; ++k) {
    per.solver.step(dt);
    wide.solver.step(dt);
  }
  const auto a = per.solver.spheres(), b = wide.solver.spheres();
  for (const auto& s : a) min_x = std::min(min_x, static_cast<double>(s.pos.x));
  EXPECT_GT(min_x - r, period); // all across
  EXPECT_TRUE(same_bits(a, b));
  EXPECT_EQ(per.solver.intact_bonds(), wide.solver.intact_bonds());
  EXPECT_EQ(per.solver.contact_counts(), wide.solver.contact_counts());
  EXPECT_EQ(per.solver.broken_bonds(), 0);
  EXPECT_EQ(std::memcmp(per.solver.quaternions().data(), wide.solver.quaternions().data(), 4 * a.size() * sizeof(Real)),
            0);
}

namespace {
// Once moved back by a period, a sphere's position rounds in other bits than in the wide
// box, and the cluster's stiff bonds carry that round-off into its velocities and spins.
// The scale of that difference is measured, not assumed: the same cluster started one or
// two periods further along in a wider box differs from the first by round-off alone;
// the periodic run must stay within a few times the larger of those differences.
double deviation(const std::vector<Sphere>& a, const std::vector<Sphere>& b) {
  double d = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    d = std::max(d, std::fabs(wrapped(a[k].pos.x) - wrapped(b[k].pos.x)) / r);
    d = std::max(d, static_cast<double>(std::fabs(a[k].pos.y - b[k].pos.y) + std::fabs(a[k].pos.z - b[k].pos.z)) / r);
    d = std::max(d, static_cast<double>(norm(a[k].vel - b[k].vel)) / 0.5);
    d = std::max(d, static_cast<double>(norm(a[k].omega - b[k].omega)) * r / 0.5);
  }
  return d;
}
// The bonds as a set (the list's order follows the spheres' sort, which differs).
std::vector<std::pair<std::uint32_t, std::uint32_t>> bond_set(const DemSolver& s) {
  const auto f = s.intact_bonds();
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  for (std::size_t k = 0; k + 1 < f.size(); k += 2) out.emplace_back(f[k], f[k + 1]);
  std::sort(out.begin(), out.end());
  return out;
}

struct Compared {
  double periodic = 0, translated = 0; // deviations from the wide box (relative to r and 0.5 m/s)
  int mixed = 0;                       // samples with the cluster on both sides of the move back
  bool same_bonds = false, same_contacts = false;
  long broken = 0;
};
Compared compare(const std::vector<Sphere>& periodic_start, Real x0, Real t) {
  Tank per(hi_periodic, true, periodic_start), wide(hi_wide, false, cluster(x0));
  Tank one(hi_wide, false, cluster(x0 + period)), two(hi_wide, false, cluster(x0 + 2 * period));
  const Real dt = per.solver.critical_dt(0.1f);
  Compared c;
  for (int k = 0; k < static_cast<int>(t / dt); ++k) {
    for (Tank* tank : {&per, &wide, &one, &two}) tank->solver.step(dt);
    if (k % 50 == 0) {
      bool lo_side = false, hi_side = false;
      for (const auto& q : per.solver.spheres()) (q.pos.x < hi_periodic.x ? lo_side : hi_side) = true;
      c.mixed += lo_side && hi_side ? 1 : 0;
    }
  }
  const auto w = wide.solver.spheres();
  c.periodic = deviation(per.solver.spheres(), w);
  c.translated = std::max(deviation(one.solver.spheres(), w), deviation(two.solver.spheres(), w));
  c.same_bonds = bond_set(per.solver) == bond_set(wide.solver) && per.bonds == wide.bonds;
  auto sorted_counts = [](const DemSolver& s) { return s.contact_counts(); }; // by id: comparable as they are
  c.same_contacts = sorted_counts(per.solver) == sorted_counts(wide.solver);
  c.broken = per.solver.broken_bonds();
  for (const auto& q : per.solver.spheres()) EXPECT_LT(q.pos.x, hi_periodic.x + period / 2);
  return c;
}
} // namespace

TEST(DemPeriodic, ContactsAndBondsSurviveTheMoveBackByAPeriod) {
  // 0.3 s: the cluster travels 0.15 m; its spheres are moved back one by one (half a
  // period beyond the face) while bonded to spheres not yet moved.
  const Compared c = compare(cluster(0.08f), 0.08f, 0.3f);
  std::printf("deviation from the wide box: periodic %.3g, translated by one or two periods %.3g\n", c.periodic,
              c.translated);
  EXPECT_GT(c.mixed, 0);
  EXPECT_TRUE(c.same_bonds);
  EXPECT_TRUE(c.same_contacts);
  EXPECT_EQ(c.broken, 0);
  EXPECT_LT(c.periodic, 4 * c.translated + 1e-7);
}

TEST(DemPeriodic, SpheresBondAcrossAFaceAtTheStart) {
  // The cluster straddles the face at t = 0: given in the periodic box with its spheres
  // beyond the face a period back, it bonds and moves as in the wider box.
  std::vector<Sphere> straddling = cluster(0.095f);
  for (auto& s : straddling)
    if (s.pos.x >= period) s.pos.x -= period;
  const Compared c = compare(straddling, 0.095f, 0.1f);
  std::printf("deviation from the wide box: periodic %.3g, translated by one or two periods %.3g\n", c.periodic,
              c.translated);
  EXPECT_TRUE(c.same_bonds);
  EXPECT_TRUE(c.same_contacts);
  EXPECT_EQ(c.broken, 0);
  EXPECT_LT(c.periodic, 4 * c.translated + 1e-7);
}

TEST(DemPeriodic, APeriodTooShortForTheSpheresIsRefused) {
  DemSolver s({bonded_grains()}, {}, Vec3{}, lo, Vec3{0.02f, 0.05f, 0.05f});
  domain::PeriodicAxes p;
  p.on[0] = 1;
  p.lo = lo;
  p.hi = Vec3{0.02f, 0.05f, 0.05f};
  p.len = Vec3{0.02f, 0, 0};
  s.set_periodic(p);
  EXPECT_THROW(s.set_spheres(cluster(0.0f)), std::invalid_argument);
}
