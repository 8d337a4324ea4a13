// SPH-DEM coupling (SPEC §4): body-particle layout, exact rigid motion, momentum of
// water plus spheres, thread independence.
#include "surge/coupling/body_particles.hpp"
#include "surge/coupling/sph_dem_coupling.hpp"
#include "surge/dem/rigid_state.hpp"
#include "surge/io/case_reader.hpp"
#include "surge/sim/dem_setup.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace surge;

namespace {

// A blob of water with a sphere inside moving through it; no gravity, no walls.
std::string blob_case(const std::string& integrator, const std::string& boundary = "dynamic") {
  return "name: blob\ndp: 0.01\ngravity: [0, 0, 0]\ndomain: {min: [0, 0, 0], max: [0.3, 0.3, 0.3]}\n"
         "sph: {c0: 10, hmax: 0.2, integrator: " +
         integrator + ", boundary: " + boundary +
         "}\n"
         "fluid:\n  - box: {min: [0.05, 0.05, 0.05], max: [0.25, 0.25, 0.25]}\n"
         "dem:\n  materials: [{name: s, density: 2500, E: 1.0e7}]\n"
         "  packs:\n    - box: {min: [0.12, 0.12, 0.12], max: [0.18, 0.18, 0.18]}\n"
         "      radius: 0.03\n      material: s\n      velocity: [0.5, 0.2, -0.3]\n";
}

struct Coupled {
  Case c;
  sph::InitialState init;
  sim::CoupledParts parts;
  sph::WcsphSolver sph;
  explicit Coupled(const std::string& text)
      : c(io::read_case_text(text, "blob.yaml")), init(sph::build_initial_state(c)), parts(c, init),
        sph(sph::solver_config(c), init) {}
  void step() {
    const auto s = sph.step(1e9);
    parts.coupling->after_fluid_step(sph, *parts.dem, s.dt);
  }
  // Total momentum of water and spheres, in double.
  [[nodiscard]] Vec3d momentum(double* scale) const {
    particles::HostParticles h;
    sph.download(h);
    Vec3d p{};
    double sc = 0;
    const double m = c.sph.rho0 * c.dp * c.dp * c.dp;
    for (std::size_t i = 0; i < h.size(); ++i)
      if (h.kind[i] == static_cast<std::uint8_t>(Kind::Fluid)) {
        p += Vec3d(h.vel[i]) * m;
        sc += m * norm(Vec3d(h.vel[i]));
      }
    for (const auto& s : parts.dem->spheres()) {
      const double r = s.radius;
      const double ms = c.dem.materials[0].density * 4.0 / 3.0 * dem::pi * r * r * r;
      p += Vec3d(s.vel) * ms;
      sc += ms * norm(Vec3d(s.vel));
    }
    if (scale) *scale = sc;
    return p;
  }
};

// n entries of an execution-space array, copied to the host by a loop.
std::vector<Vec3> read_back(const Vec3* src, int n) {
  par::Buffer<Vec3> b(static_cast<std::size_t>(n));
  Vec3* dst = b.data();
  par::parallel_for(
      n, SURGE_LAMBDA(int i) { dst[i] = src[i]; });
  return par::download(b);
}

} // namespace

// Layer k sits at r - (k + 1/2) dp with about 4 pi r_k^2 / dp^2 particles; a sphere
// smaller than the layers is closed by a centre particle (exact radii: 1e-12 relative).
TEST(BodyParticles, LayersSitAtTheirRadiiAndSmallSpheresAreFilled) {
  const double r = 0.03, dp = 0.005;
  const auto o = coupling::body_offsets(r, dp, 3);
  int counts[3] = {0, 0, 0};
  for (const auto& x : o) {
    const double d = norm(x);
    int k = -1;
    for (int l = 0; l < 3; ++l)
      if (std::abs(d - (r - (l + 0.5) * dp)) < 1e-12 * r) k = l;
    ASSERT_GE(k, 0) << "offset at radius " << d << " belongs to no layer";
    ++counts[k];
  }
  for (int l = 0; l < 3; ++l) {
    const double rk = r - (l + 0.5) * dp;
    EXPECT_EQ(counts[l], std::lround(4 * dem::pi * rk * rk / (dp * dp)));
  }
  // r = 2 dp: one shell at 1.5 dp, then the centre (r_1 = dp/2).
  const auto small = coupling::body_offsets(0.03, 0.015, 3);
  EXPECT_EQ(std::count_if(small.begin(), small.end(), [](const Vec3d& x) { return norm(x) == 0.0; }), 1);
  EXPECT_EQ(small.size(), static_cast<std::size_t>(std::lround(4 * dem::pi * 1.5 * 1.5)) + 1);
  EXPECT_EQ(coupling::default_layers(1.2 * dp, dp), 3); // ceil(2.4)
  EXPECT_EQ(coupling::default_layers(1.0 * dp, dp), 2);
}

// Quasi-uniform shells: nearest-neighbour spacing on the outer shell is dp within 15 %
// on average and never below 0.6 dp (Fibonacci lattice).
TEST(BodyParticles, OuterShellSpacingIsAboutDp) {
  const double r = 0.05, dp = 0.005;
  std::vector<Vec3d> shell;
  for (const auto& x : coupling::body_offsets(r, dp, 1)) shell.push_back(x);
  double sum = 0, mn = 1e9;
  for (std::size_t i = 0; i < shell.size(); ++i) {
    double best = 1e9;
    for (std::size_t j = 0; j < shell.size(); ++j)
      if (i != j) best = std::min(best, norm(shell[i] - shell[j]));
    sum += best;
    mn = std::min(mn, best);
  }
  const double mean = sum / static_cast<double>(shell.size());
  EXPECT_NEAR(mean / dp, 1.0, 0.15);
  EXPECT_GT(mn / dp, 0.6);
}

// q v q* against the rotation matrix of the same unit quaternion (1e-6, float), and the
// rigid velocity w x arm.
TEST(RigidMotion, QuaternionRotationMatchesTheMatrix) {
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0, 1);
  for (int t = 0; t < 50; ++t) {
    double q[4] = {n(rng), n(rng), n(rng), n(rng)};
    const double l = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (double& x : q) x /= l;
    const double w = q[0], x = q[1], y = q[2], z = q[3];
    const double R[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                            {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                            {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
    const Vec3 v(static_cast<Real>(n(rng)), static_cast<Real>(n(rng)), static_cast<Real>(n(rng)));
    dem::RigidState s;
    for (int k = 0; k < 4; ++k) s.q[k] = static_cast<Real>(q[k]);
    s.pos = {1, 2, 3};
    s.vel = {0.1f, 0, 0};
    s.omega = {0, 0, 2};
    const dem::RigidPoint p = dem::rigid_point(s, v);
    for (int i = 0; i < 3; ++i) {
      const double expect = R[i][0] * v.x + R[i][1] * v.y + R[i][2] * v.z;
      EXPECT_NEAR(p.pos[i] - s.pos[i], expect, 1e-5);
    }
    const Vec3 vel = s.vel + cross(s.omega, p.pos - s.pos);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(p.vel[i], vel[i], 1e-5);
  }
}

// Without gravity and walls, water plus spheres conserve momentum: fluid-body pair
// forces are antisymmetric and the sphere receives exactly minus what its body
// particles give the water. With the symplectic scheme fluid and spheres see the same
// force over the same dt. Tolerance: 1e-5 of sum |m v| (float sums, 40 steps).
TEST(Coupling, MomentumOfWaterAndSpheresIsConserved) {
  Coupled s(blob_case("symplectic"));
  double scale = 0;
  const Vec3d p0 = s.momentum(&scale);
  for (int k = 0; k < 40; ++k) s.step();
  double scale1 = 0;
  const Vec3d p1 = s.momentum(&scale1);
  // The sphere really pushed the water: a good share of its momentum moved to the fluid.
  const auto sp = s.parts.dem->spheres();
  EXPECT_LT(norm(Vec3d(sp[0].vel)), 0.98 * norm(Vec3d{0.5, 0.2, -0.3}));
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(p1[k], p0[k], 1e-5 * scale) << "component " << k;
}

// Body particles sit where the rigid transform of their sphere puts them, and keep
// their distance to the centre, after the sphere has moved and turned. Tolerance 1e-6 m
// (a few float ulps: this file and the library may contract multiply-adds differently).
TEST(Coupling, BodyParticlesFollowTheirSphereRigidly) {
  Coupled s(blob_case("verlet", "mdbc"));
  for (int k = 0; k < 20; ++k) s.step();
  particles::HostParticles h;
  s.sph.download(h);
  const auto sp = s.parts.dem->spheres();
  const auto q = s.parts.dem->quaternions();
  dem::RigidState st;
  st.pos = sp[0].pos;
  st.vel = sp[0].vel;
  st.omega = sp[0].omega;
  for (int k = 0; k < 4; ++k) st.q[k] = q[static_cast<std::size_t>(k)];
  const auto offsets = coupling::body_offsets(0.03, 0.01, s.parts.layers);
  std::uint32_t first = 0xFFFFFFFFU;
  for (std::size_t i = 0; i < h.size(); ++i)
    if (h.kind[i] == static_cast<std::uint8_t>(Kind::Body)) first = std::min(first, h.id[i]);
  int n_body = 0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    if (h.kind[i] != static_cast<std::uint8_t>(Kind::Body)) continue;
    ++n_body;
    const Vec3 off(offsets[h.id[i] - first]);
    const dem::RigidPoint p = dem::rigid_point(st, off);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(h.pos[i][k], p.pos[k], 1e-6);
      EXPECT_NEAR(h.vel[i][k], p.vel[k], 1e-6);
    }
    EXPECT_NEAR(norm(h.pos[i] - st.pos), norm(off), 1e-6);
  }
  EXPECT_EQ(n_body, static_cast<int>(offsets.size()));
  // mDBC ghost nodes of the body particles, as the coupling left them after moving the
  // sphere: each is its particle mirrored through the sphere's surface, |x_g - c| =
  // 2R - |x_b - c| on the same ray (the centre particle is its own ghost).
  const std::uint32_t fb = s.sph.first_boundary_id();
  std::uint32_t last = fb;
  for (auto id : h.id) last = std::max(last, id);
  const auto ghost = read_back(s.sph.ghost_offsets(), static_cast<int>(last - fb + 1));
  for (std::size_t i = 0; i < h.size(); ++i) {
    if (h.kind[i] != static_cast<std::uint8_t>(Kind::Body)) continue;
    const Vec3 rb = h.pos[i] - st.pos, rg = h.pos[i] + ghost[h.id[i] - fb] - st.pos;
    if (norm(rb) < 1e-6f) continue;
    EXPECT_NEAR(norm(rg), 2 * 0.03 - norm(rb), 2e-6);
    EXPECT_NEAR(dot(rg, rb), norm(rg) * norm(rb), 1e-8);
  }
}

// Per-sphere sums in a fixed order, per-particle writes only: identical states on 1 and
// 2 threads.
TEST(Coupling, SameResultOnOneAndTwoThreads) {
  auto run = [](int threads) {
    par::set_threads(threads);
    Coupled s(blob_case("verlet"));
    for (int k = 0; k < 15; ++k) s.step();
    return std::make_pair(s.parts.dem->spheres()[0], s.parts.dem->external_forces()[0]);
  };
  const auto a = run(1), b = run(2);
  par::set_threads(2);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(a.first.pos[k], b.first.pos[k]);
    EXPECT_EQ(a.first.vel[k], b.first.vel[k]);
    EXPECT_EQ(a.first.omega[k], b.first.omega[k]);
    EXPECT_EQ(a.second[k], b.second[k]);
  }
}
