// The DEM's batched passes (dem_batched.inc: touching pairs, and spheres, 8 or 4 at a
// time) against the scalar ones (detail::pair_pass and integrate, the ones CUDA runs):
// each pair and sphere is computed alone, lane by lane with the scalar operations, so
// every sphere's state, force, torque and bond must be bitwise equal after a run that
// crosses every branch of the contact law: bonds that break in tension and in shear,
// contacts that slip, rolling and twisting springs at their caps, one or two materials,
// fixed spheres, a floor, both laws, and batch tails of every length (the number of
// touching pairs per flush varies from block to block).
#include "dem_closed_form.hpp"

#include "surge/dem/dem_solver.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

using namespace surge;
using namespace surge::dem;

namespace {

struct Outcome {
  std::vector<Sphere> spheres;
  std::vector<Vec3> forces, torques;
  std::vector<Real> quats;
  std::vector<std::uint32_t> bonds, contacts;
  long bonds_at_start = 0, broken = 0;
};

// A block of 8 x 8 x 6 spheres of two materials (the lower half bonded, with rolling
// and twisting resistance; or all of the first, `one_material`) thrown onto a floor with
// random velocities and spins, a few of them fixed.
Outcome run(const char* pass, int law, bool one_material = false) {
  Material a = test::grains(1e6f, 0.2f, 0.5f), b = test::grains(2e6f, 0.3f, 0.8f);
  a.tan_phi = 0.4f;
  b.tan_phi = 0.7f;
  if (law == 0) { // bonds and the caps belong to the linear spring
    a.bonded = true;
    a.bond_cn = 2e4f;
    a.bond_cs = 1e4f;
    a.k_roll = 0.3f;
    a.k_roll_max = 0.05f;
    a.k_twist = 0.2f;
    a.k_twist_max = 0.05f;
  } else {
    a.nu = b.nu = 0.3f;
  }
  DemSolver s({a, b}, {{{0, 0, -0.05f}, {0, 0, 1}, 1}}, Vec3{0, 0, -9.81f}, Vec3{-1, -1, -1}, Vec3{1, 1, 1}, law);
  EXPECT_TRUE(s.set_pair_pass(pass));
  std::vector<Sphere> sp;
  std::mt19937 rng(11);
  std::normal_distribution<float> nd(0, 0.2f);
  std::uniform_real_distribution<float> jitter(-2e-5f, 2e-5f);
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i) {
        const Vec3 x{0.0199f * static_cast<Real>(i) + jitter(rng), 0.0199f * static_cast<Real>(j) + jitter(rng),
                     -0.039f + 0.0199f * static_cast<Real>(k)};
        sp.push_back({x,
                      {nd(rng), nd(rng), nd(rng)},
                      {nd(rng) * 20, nd(rng) * 20, nd(rng) * 20},
                      0.01f,
                      k < 3 || one_material ? 0 : 1,
                      (i + j + k) % 17 == 0});
      }
  s.set_spheres(sp);
  Outcome o;
  if (law == 0) o.bonds_at_start = s.bond_touching(1e-4f);
  const Real dt = s.critical_dt(0.1f);
  for (int k = 0; k < 400; ++k) s.step(dt);
  o.spheres = s.spheres();
  o.forces = s.forces();
  o.torques = s.torques();
  o.quats = s.quaternions();
  o.bonds = s.intact_bonds();
  o.contacts = s.contact_counts();
  o.broken = s.broken_bonds();
  return o;
}

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

bool same_bits(const Vec3& a, const Vec3& b) {
  for (int k = 0; k < 3; ++k)
    if (std::bit_cast<std::uint32_t>(a[k]) != std::bit_cast<std::uint32_t>(b[k])) return false;
  return true;
}

void expect_same(const Outcome& a, const Outcome& b) {
  ASSERT_EQ(a.spheres.size(), b.spheres.size());
  for (std::size_t i = 0; i < a.spheres.size(); ++i) {
    const Sphere &x = a.spheres[i], &y = b.spheres[i];
    ASSERT_TRUE(same_bits(x.pos, y.pos)) << "sphere " << i;
    ASSERT_TRUE(same_bits(x.vel, y.vel)) << "sphere " << i;
    ASSERT_TRUE(same_bits(x.omega, y.omega)) << "sphere " << i;
  }
  EXPECT_TRUE(same_bytes(a.forces, b.forces));
  EXPECT_TRUE(same_bytes(a.torques, b.torques));
  EXPECT_TRUE(same_bytes(a.quats, b.quats));
  EXPECT_TRUE(same_bytes(a.bonds, b.bonds));
  EXPECT_TRUE(same_bytes(a.contacts, b.contacts));
  EXPECT_EQ(a.broken, b.broken);
}

void compare_passes(int law, bool one_material = false) {
  const Outcome scalar = run("off", law, one_material);
  int compared = 0;
  for (const char* isa : {"sse2", "avx2"}) {
    DemSolver probe({test::grains(1e6f, 0.3f, 0.5f)}, {}, Vec3{}, Vec3{-1, -1, -1}, Vec3{1, 1, 1}, law);
    if (!probe.set_pair_pass(isa)) continue; // not built, or not on this CPU
    SCOPED_TRACE(isa);
    expect_same(run(isa, law, one_material), scalar);
    ++compared;
  }
  if (compared == 0) GTEST_SKIP() << "no batched pair pass in this build";
  if (law == 0) { // the bond branches were crossed: some bonds broke, not all
    EXPECT_GT(scalar.broken, 0);
    EXPECT_GT(scalar.bonds.size() / 2, 0U);
    EXPECT_GT(scalar.bonds_at_start, 200);
  }
}

} // namespace

TEST(DemBatched, LinearSpringWithBondsRollingAndTwistingGivesTheScalarBits) { compare_passes(0); }

TEST(DemBatched, HertzMindlinGivesTheScalarBits) { compare_passes(1); }

// One material: the batched pass takes the material pair from the table once.
TEST(DemBatched, OneBondedMaterialGivesTheScalarBits) { compare_passes(0, true); }

TEST(DemBatched, UnknownPassIsRefusedAndChangesNothing) {
  DemSolver s({test::grains(1e6f, 0.2f, 0.5f)}, {}, Vec3{}, Vec3{-1, -1, -1}, Vec3{1, 1, 1});
  const std::string before = s.pair_pass();
  EXPECT_FALSE(s.set_pair_pass("avx512"));
  EXPECT_EQ(before, s.pair_pass());
  EXPECT_TRUE(s.set_pair_pass("off"));
  EXPECT_STREQ(s.pair_pass(), "off");
}
