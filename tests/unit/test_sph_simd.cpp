// The batched pair loop (wcsph_rates_batched.inc, 8 pairs at a time) against the scalar one
// (wcsph_rates): on every particle of a few cases after some steps (fluid, wall, body,
// mDBC and Fourtakas), isolated particles, a crowded cell and a domain one cell thick.
// The sums are reordered (lane k sums pairs k, k + 8, ...), so each rate may differ by the
// rounding of a reordered float sum: 1e-5 of the sum of the magnitudes of its pair terms
// (60 terms at 6e-8 each, with margin). The wall plane each fluid particle picks and the
// signal speed (a maximum) are exact. Every instruction set gives the same bits. With
// laminar_sps the strain rate too (each component against the sum of |S| over the pairs).
#include "test_helpers.hpp"

#include "surge/sph/boundary/mdbc_density.hpp"
#include "surge/sph/initial_state.hpp"
#include "surge/sph/wcsph_rates_simd.hpp"
#include "surge/sph/wcsph_solver.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

using namespace surge;

namespace {

// The sum of the magnitudes of particle i's pair terms, per rate: the scale of a reordered
// sum's rounding.
struct TermScale {
  Real acc = 0, drho = 0, grad_c = 0, div_r = 0, strain = 0;
};

// |S| of a strain rate's components (Frobenius).
Real magnitude(const SymTensor& s) {
  return std::sqrt(s.xx * s.xx + s.yy * s.yy + s.zz * s.zz + 2 * (s.xy * s.xy + s.xz * s.xz + s.yz * s.yz));
}

TermScale term_scale(const sph::WcsphParams& prm, const neighbour::GridView& g, const particles::ParticleView& p,
                     int i) {
  const auto fluid = static_cast<std::uint8_t>(Kind::Fluid);
  const bool fluid_i = p.kind[i] == fluid;
  const sph::PairSide<Real> a{p.vel[i], p.rho[i], p.press[i]};
  TermScale t;
  neighbour::for_each_neighbour(
      g, p.pos[i], prm.kernel.support() * prm.kernel.support(), [&](int j, const Vec3& rij, Real r2) {
        if (j == i || (!fluid_i && p.kind[j] != fluid)) return;
        sph::PairSums<Real> one;
        const bool fluid_pair = fluid_i && p.kind[j] == fluid;
        sph::add_pair_terms(prm, rij, r2, std::sqrt(r2), a, sph::PairSide<Real>{p.vel[j], p.rho[j], p.press[j]},
                            fluid_pair, one);
        t.acc += norm(one.acc);
        t.drho += std::fabs(one.drho) + std::fabs(prm.delta * prm.kernel.h * prm.eos.c0 * one.diff);
        t.grad_c += norm(one.grad_c);
        t.div_r += std::fabs(one.div_r);
        if (p.sps) { // the SPS terms alone: the pair's terms with them less those without
          sph::SpsSums<Real> sps;
          sph::PairSums<Real> with;
          const SymTensor ti = sph::stress_over_rho(p.sps[i], a.rho);
          const sph::SpsPair<Real> sp{ti, p.sps[j], sps};
          sph::add_pair_terms(prm, rij, r2, std::sqrt(r2), a, sph::PairSide<Real>{p.vel[j], p.rho[j], p.press[j]},
                              fluid_pair, with, &sp);
          t.acc += norm(with.acc - one.acc);
          if (fluid_i) t.strain += magnitude(sph::strain_rate(sps.strain));
        }
      });
  return t;
}

bool same_bits(const sph::Rates& a, const sph::Rates& b) {
  return std::memcmp(&a.acc, &b.acc, sizeof a.acc) == 0 && std::memcmp(&a.drho, &b.drho, sizeof a.drho) == 0 &&
         std::memcmp(&a.vsig, &b.vsig, sizeof a.vsig) == 0 && std::memcmp(&a.wall, &b.wall, sizeof a.wall) == 0 &&
         std::memcmp(&a.shift, &b.shift, sizeof a.shift) == 0 &&
         std::memcmp(&a.strain, &b.strain, sizeof a.strain) == 0;
}

// The rates a batched copy stores for every particle (the blocks the solver hands it).
std::vector<sph::Rates> batched_all(sph::RatesFn f, const sph::WcsphSolver& s, const neighbour::GridView& g,
                                    const particles::ParticleView& p) {
  std::vector<sph::WallChoice> faces(static_cast<std::size_t>(p.n));
  std::vector<sph::ShiftSums> shift(static_cast<std::size_t>(p.n));
  std::vector<SymTensor> strain(static_cast<std::size_t>(p.n));
  const sph::RatesOut out{faces.data(), s.params().shift.on() ? shift.data() : nullptr,
                          p.sps ? strain.data() : nullptr};
  for (int b = 0; b < p.n; b += sph::rates_block)
    f(s.params(), g, p, s.hold_view(), out, b, std::min(p.n, b + sph::rates_block));
  std::vector<sph::Rates> rates(static_cast<std::size_t>(p.n));
  for (int i = 0; i < p.n; ++i) rates[i] = sph::Rates{p.acc[i], p.drho[i], p.vsig[i], faces[i], shift[i], strain[i]};
  return rates;
}

// Compares every particle's rates; returns how many particles had each batch tail (pairs
// mod 8), so that a test can check it covered them.
std::array<int, 8> compare_rates(sph::WcsphSolver& s, const std::string& what) {
  s.refresh();
  // Reads and runs the loops on the host: a CPU-only test (SIMD builds are never CUDA
  // builds), so the device check's protection is lifted for it.
  const par::devcheck::Open access;
  const auto p = s.view();
  const auto g = s.grid_view();
  const auto gh = s.hold_view();
  const auto& prm = s.params();
  const sph::RatesFn sse2 = sph::batched_rates("sse2");
  const sph::RatesFn avx2 = sph::batched_rates("avx2"); // null on a CPU without AVX2
  EXPECT_NE(sse2, nullptr);
  const auto got_all = batched_all(sse2, s, g, p);
  const auto avx2_all = avx2 ? batched_all(avx2, s, g, p) : got_all;
  std::array<int, 8> tails{};
  for (int i = 0; i < p.n; ++i) {
    const sph::Rates ref = sph::wcsph_rates(prm, g, p, i, gh);
    const sph::Rates& got = got_all[i];
    EXPECT_TRUE(same_bits(got, avx2_all[i])) << what << ": particle " << i;
    const TermScale t = term_scale(prm, g, p, i);
    EXPECT_LE(norm(got.acc - ref.acc), 1e-5f * t.acc) << what << ": particle " << i;
    EXPECT_LE(std::fabs(got.drho - ref.drho), 1e-5f * t.drho) << what << ": particle " << i;
    EXPECT_EQ(got.vsig, ref.vsig) << what << ": particle " << i;
    if (prm.shift.on()) {
      EXPECT_LE(norm(got.shift.grad_c - ref.shift.grad_c), 1e-5f * t.grad_c) << what << ": particle " << i;
      EXPECT_LE(std::fabs(got.shift.div_r - ref.shift.div_r), 1e-5f * t.div_r) << what << ": particle " << i;
    }
    if (p.sps) {
      const SymTensor& a = got.strain;
      const SymTensor& b = ref.strain;
      const SymTensor d{a.xx - b.xx, a.yy - b.yy, a.zz - b.zz, a.xy - b.xy, a.xz - b.xz, a.yz - b.yz};
      EXPECT_LE(magnitude(d), 1e-5f * t.strain) << what << ": particle " << i;
    }
    EXPECT_EQ(std::memcmp(&got.wall, &ref.wall, sizeof ref.wall), 0) << what << ": particle " << i;
    int pairs = 0;
    neighbour::for_each_neighbour(
        g, p.pos[i], prm.kernel.support() * prm.kernel.support(),
        [&](int j, const Vec3&, Real) { pairs += j != i && (p.kind[i] == 0 || p.kind[j] == 0) ? 1 : 0; });
    ++tails[pairs % 8];
  }
  return tails;
}

sph::WcsphSolver advanced(const std::string& text, int steps) {
  const Case c = io::read_case_text(text, "simd.yaml");
  sph::WcsphSolver s(sph::solver_config(c), sph::build_initial_state(c));
  for (int k = 0; k < steps; ++k) s.step(1.0);
  return s;
}

} // namespace

// A dam break in a tank after 40 steps: fluid, walls with the no-penetration condition
// (the wall plane is chosen in the batched loop too), a domain edge, every tail length.
TEST(SphSimd, DynamicBoundaryDamBreakMatchesScalar) {
  auto s = advanced(test::tank_case(0.01), 40);
  const auto tails = compare_rates(s, "dynamic");
  for (int k = 0; k < 8; ++k) EXPECT_GT(tails[k], 0) << "no particle with " << k << " pairs mod 8";
}

TEST(SphSimd, MdbcAndFourtakasMatchScalar) {
  auto s = advanced(test::tank_case(0.01, 0.0, "sph: {boundary: mdbc, diffusion: fourtakas}\n"), 40);
  compare_rates(s, "mdbc + fourtakas");
}

// The laminar viscosity's term and the shifting sums (grad C, div r), on both wall models.
TEST(SphSimd, LaminarViscosityAndShiftingMatchScalar) {
  auto s = advanced(test::tank_case(0.01, 0.0, "sph: {viscosity: laminar, nu: 1.0e-4, shifting: fickian}\n"), 40);
  ASSERT_TRUE(s.params().shift.on());
  compare_rates(s, "laminar + shifting");
  auto m = advanced(
      test::tank_case(0.01, 0.0,
                      "sph: {boundary: mdbc, viscosity: laminar, shifting: delta_plus, integrator: symplectic}\n"),
      40);
  compare_rates(m, "mdbc + laminar + delta_plus shifting");
}

// laminar_sps: the strain rate summed in the pair loop and the stress's momentum term read
// from the stresses the particles carry (40 steps in: every fluid particle carries one).
TEST(SphSimd, SpsStressTermsMatchScalar) {
  auto s = advanced(test::tank_case(0.01, 0.0, "sph: {viscosity: laminar_sps, shifting: fickian}\n"), 40);
  ASSERT_NE(s.view().sps, nullptr);
  compare_rates(s, "laminar_sps");
}

// mDBC's boundary densities with the ghost sums 8 neighbours at a time (mdbc_range) against
// mdbc_density, one neighbour at a time, on every boundary particle of a dam break after 40
// steps (walls near water and far from it, the domain's edges). The sums are reordered:
// each density may differ by the rounding of the 4x4 solve, within the 1e-5 relative
// (the largest difference here is 2.1e-3 kg/m^3, 2e-6 relative, 34 float roundings of a
// density); where |det A| lies within a factor 2 of the threshold that picks the Shepard
// average instead, the rounding may pick the other formula, so those (rare) particles are
// skipped. Both instruction sets give the same bits.
TEST(SphSimd, MdbcGhostDensitiesMatchScalar) {
  auto s = advanced(test::tank_case(0.01, 0.0, "sph: {boundary: mdbc}\n"), 40);
  s.refresh();
  const par::devcheck::Open access; // host reads and runs, as in compare_rates
  const auto p = s.view();
  const auto g = s.grid_view();
  const auto gh = s.hold_view();
  const auto& prm = s.params();
  ASSERT_NE(gh.offset, nullptr);
  const std::vector<Real> before(p.rho, p.rho + p.n);
  std::vector<std::vector<Real>> got;
  for (const char* isa : {"sse2", "avx2"}) {
    const sph::MdbcFn f = sph::batched_mdbc(isa);
    if (!f) continue;
    std::copy(before.begin(), before.end(), p.rho);
    for (int b = 0; b < p.n; b += sph::rates_block)
      f(prm, g, p, gh.offset, gh.first_id, b, std::min(p.n, b + sph::rates_block));
    got.emplace_back(p.rho, p.rho + p.n);
  }
  ASSERT_FALSE(got.empty());
  std::copy(before.begin(), before.end(), p.rho);
  const Real r2max = prm.kernel.support() * prm.kernel.support();
  int compared = 0, linear = 0;
  Real worst = 0;
  for (int i = 0; i < p.n; ++i) {
    if (p.kind[i] == static_cast<std::uint8_t>(Kind::Fluid)) continue;
    for (const auto& other : got) EXPECT_EQ(std::memcmp(&other[i], &got[0][i], sizeof(Real)), 0) << "particle " << i;
    const Vec3 xb = p.pos[i], xg = xb + gh.offset[p.id[i] - gh.first_id];
    sph::GhostSums<Real> sums;
    neighbour::for_each_fluid_neighbour(g, xg, r2max, [&](int j, const Vec3& d, Real r2) {
      sph::add_ghost_terms(prm, d, std::sqrt(r2), p.rho[j], prm.mass / p.rho[j], sums);
    });
    sph::GhostSums<Real> solved = sums;
    const Real det = std::fabs(sph::solve4(solved.a, solved.b));
    if (sums.a[0][0] > 0 && det > Real(0.5e-3) && det < Real(2e-3)) continue;
    const Real want = sph::boundary_density(sph::mdbc_density(prm, g, p, xb, xg, before[i]), prm.eos.rho0);
    EXPECT_NEAR(got[0][i], want, 1e-5F * want) << "particle " << i;
    worst = std::max(worst, std::fabs(got[0][i] - want));
    ++compared;
    linear += sums.a[0][0] > 0 && det >= Real(2e-3);
  }
  EXPECT_GT(compared, 1000);
  EXPECT_GT(linear, 100); // not vacuous: the linear (not Shepard) extrapolation is compared
  EXPECT_GT(worst, 0.0F); // nor the same sums: the order did change
  std::printf("mDBC batched vs scalar: %d densities compared (%d linear), largest difference %.3g kg/m^3\n", compared,
              linear, static_cast<double>(worst));
}

// Body particles are boundary particles that are not walls (no wall plane from them).
TEST(SphSimd, BodyParticlesMatchScalar) {
  auto s = advanced(test::tank_case(0.01), 20);
  s.refresh();
  const auto p = s.view();
  par::parallel_for(
      p.n, SURGE_LAMBDA(int i) {
        if (p.kind[i] == static_cast<std::uint8_t>(Kind::Wall) && i % 3 == 0)
          p.kind[i] = static_cast<std::uint8_t>(Kind::Body);
      });
  compare_rates(s, "bodies");
}

// A domain one cell thick (a slice of water) and a particle alone in the domain: its
// rates are gravity alone, exactly.
TEST(SphSimd, ThinDomainAndLoneParticle) {
  auto s = advanced("name: thin\ndp: 0.01\ndomain: {min: [0,0,0], max: [0.3,0.01,0.3]}\n"
                    "fluid: [{box: {min: [0,0,0], max: [0.1,0.01,0.1]}}, {box: {min: [0.25,0,0.25], max: "
                    "[0.26,0.01,0.26]}}]\n",
                    5);
  compare_rates(s, "thin");
  const par::devcheck::Open access; // host reads, as in compare_rates
  const auto p = s.view();
  const auto g = s.grid_view();
  int lone = -1;
  for (int i = 0; i < p.n; ++i)
    if (p.pos[i].x > 0.2f) lone = i;
  ASSERT_GE(lone, 0);
  for (const char* isa : {"sse2", "avx2"}) {
    const sph::RatesFn f = sph::batched_rates(isa);
    if (!f) continue;
    const sph::Rates r = batched_all(f, s, g, p)[lone];
    EXPECT_EQ(r.acc.z, s.params().gravity.z) << isa;
    EXPECT_EQ(r.drho, 0.0f) << isa;
    EXPECT_EQ(r.vsig, 0.0f) << isa;
  }
}

// 400 particles in one cell of h (far more than the 256 hits a particle buffers before
// summing them): the buffer is summed in several parts.
TEST(SphSimd, CrowdedCellMatchesScalar) {
  auto s = advanced("name: crowd\ndp: 0.01\ngravity: [0, 0, 0]\ndomain: {min: [0,0,0], max: [0.2,0.2,0.2]}\n"
                    "sph: {c0: 20, hydrostatic_init: false}\n"
                    "fluid: [{box: {min: [0.05,0.05,0.05], max: [0.12,0.13,0.13]}}]\n",
                    0);
  s.refresh();
  auto p = s.view();
  const Real h = s.params().kernel.h;
  par::parallel_for(
      p.n, SURGE_LAMBDA(int i) {
        // squeeze the block into a cube of h / 2 (a grid-point hash keeps it deterministic)
        const Vec3 x = p.pos[i];
        p.pos[i] = Vec3{Real(0.1), Real(0.1), Real(0.1)} +
                   (x - Vec3{Real(0.05), Real(0.05), Real(0.05)}) * (h / 2 / Real(0.08));
      });
  ASSERT_GT(p.n, 400);
  s.invalidate();
  compare_rates(s, "crowded");
}
