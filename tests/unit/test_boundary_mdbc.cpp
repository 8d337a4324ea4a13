// The modified dynamic boundary (mDBC): ghost nodes from the wall geometry, the
// first-order interpolation against a linear density field (exact up to float round-off),
// and a hydrostatic tank against rho g (H - z).
#include "test_helpers.hpp"

#include "surge/geometry/particle_generators.hpp"
#include "surge/io/case_schema.hpp"
#include "surge/sph/boundary/mdbc_density.hpp"
#include "surge/sph/gauges.hpp"
#include "surge/sph/wcsph_solver.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace surge;

namespace {

// mdbc_density for one boundary particle, evaluated in the execution space.
Real density_at(const sph::WcsphParams& prm, const neighbour::GridView& g, const particles::ParticleView& v, Vec3 xb,
                Vec3 xg) {
  par::Buffer<Real> out(1);
  Real* o = out.data();
  par::parallel_for(
      1, SURGE_LAMBDA(int) { o[0] = sph::mdbc_density(prm, g, v, xb, xg, Real(-1)); });
  return par::download(out)[0];
}

} // namespace

// Tank walls mirror through the closest point of the box (a corner particle diagonally),
// solid boxes through their nearest face.
TEST(Mdbc, GhostPointsMirrorThroughTheWallSurface) {
  WallSpec tank;
  tank.box = {{0, 0, 0}, {1, 1, 1}};
  auto near = [](Vec3d a, Vec3d b) { return norm(a - b) < 1e-12; };
  EXPECT_TRUE(near(geometry::ghost_point(tank, nullptr, {0.5, 0.5, -0.015}), {0.5, 0.5, 0.015}));
  EXPECT_TRUE(near(geometry::ghost_point(tank, nullptr, {-0.005, 0.5, -0.025}), {0.005, 0.5, 0.025}));
  EXPECT_TRUE(near(geometry::ghost_point(tank, nullptr, {1.005, 0.3, 0.5}), {0.995, 0.3, 0.5}));
  WallSpec block = tank;
  block.solid = true;
  EXPECT_TRUE(near(geometry::ghost_point(block, nullptr, {0.5, 0.985, 0.5}), {0.5, 1.015, 0.5}));
}

// Fluid particles on a lattice above a floor at z = 0 with density rho = a + b.x (a
// linear field): the corrected interpolation is exact for linear fields, so a boundary
// particle at z = -1.5 dp with its ghost at +1.5 dp gets a + b.x_b to float round-off
// (tolerance 1e-5 relative), although x_b lies outside the fluid.
TEST(Mdbc, LinearDensityFieldIsExtrapolatedExactly) {
  const Real dp = 0.01f;
  const Real a = 1000;
  const Vec3 b{3, -2, -50}; // kg/m^4: a hydrostatic-like gradient plus a tilt
  particles::HostParticles h;
  std::uint32_t id = 0;
  for (int k = 0; k < 8; ++k)
    for (int j = 0; j < 12; ++j)
      for (int i = 0; i < 12; ++i) {
        const Vec3 x{(static_cast<Real>(i) + 0.5f) * dp, (static_cast<Real>(j) + 0.5f) * dp,
                     (static_cast<Real>(k) + 0.5f) * dp};
        h.push(x, Vec3{}, a + dot(b, x), Kind::Fluid, id++);
      }
  particles::ParticleStore store;
  store.upload(h);
  neighbour::UniformGrid grid;
  sph::WcsphParams prm;
  prm.kernel = sph::WendlandC2(1.2f * dp);
  prm.mass = 1000 * dp * dp * dp;
  grid.set_spec(neighbour::make_grid({-0.05f, -0.05f, -0.05f}, {0.17f, 0.17f, 0.13f}, prm.kernel.support(), 2));
  ASSERT_EQ(store.sort(grid), 0);
  const auto v = store.view();
  const Vec3 xb{0.06f, 0.06f, -1.5f * dp}, xg{0.06f, 0.06f, 1.5f * dp};
  const Real got = density_at(prm, grid.view(v.pos, v.kind), v, xb, xg);
  const Real want = a + dot(b, xb);
  EXPECT_NEAR(got, want, 1e-5 * want) << "got " << got << ", want " << want;
  // A ghost with no fluid around keeps the current value (-1 here).
  EXPECT_EQ(density_at(prm, grid.view(v.pos, v.kind), v, Vec3{0.06f, 0.06f, 0.5f}, Vec3{0.06f, 0.06f, 0.5f}), Real(-1));
}

// Still water 0.2 m deep in a 0.1 x 0.1 m tank at dp = 0.01: the pressure 2 cm above the
// floor, averaged over 0.3-0.6 s (several acoustic periods), is rho g (H - z) within 2 %
// with mDBC. The same average with the dynamic boundary is printed for comparison.
double mean_bottom_pressure(const std::string& boundary) {
  const Case c = io::read_case_text(test::hydrostatic_tank_case(boundary), "hydro.yaml");
  const auto init = sph::build_initial_state(c);
  sph::WcsphSolver s(sph::solver_config(c), init);
  sph::Gauges g(c, init);
  double t = 0, sum = 0;
  int n = 0;
  while (t < 0.6) {
    t += s.step(1.0).dt;
    if (t >= 0.3 && s.step_count() % 10 == 0) {
      sum += g.sample(s)[0];
      ++n;
    }
  }
  return sum / n;
}

TEST(Mdbc, HydrostaticPressureWithinTwoPercent) {
  const double expected = 1000 * 9.81 * (0.2 - 0.02);
  const double mdbc = mean_bottom_pressure("mdbc");
  std::printf("bottom pressure, mean over 0.3-0.6 s: mdbc %.1f Pa (%+.2f %%), expected %.1f Pa\n", mdbc,
              100 * (mdbc / expected - 1), expected);
  EXPECT_NEAR(mdbc, expected, 0.02 * expected);
}

// The wall models a case may name (the schema's choices for sph.boundary) are the models
// the solver knows (sph/boundary/boundary_model.cpp), in the same order; an unknown name
// is rejected with the list of known ones.
TEST(BoundaryModels, TheSchemaListsEveryRegisteredModel) {
  std::vector<std::string> schema, registry;
  for (const auto& f : io::sph_fields())
    if (std::string(f.key) == "boundary") schema = f.choices;
  for (const auto& m : sph::boundary_models()) registry.emplace_back(m.name);
  EXPECT_EQ(schema, registry);
  for (const auto& name : registry) EXPECT_EQ(std::string(sph::boundary_model(name).name), name);
  try {
    (void)sph::boundary_model("slip");
    FAIL() << "an unknown model was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("known: dynamic, mdbc"), std::string::npos) << e.what();
  }
}

// A case's words become the solver's typed configuration once (sph/solver_config.cpp).
TEST(BoundaryModels, SolverConfigTypesTheCaseOnce) {
  const Case c = io::read_case_text(test::tank_case(0.01, 0.0, test::paper_scheme), "t.yaml");
  Case m = c;
  m.sph.boundary = "mdbc";
  m.sph.integrator = "symplectic";
  m.sph.no_penetration = false;
  const auto a = sph::solver_config(c), b = sph::solver_config(m);
  EXPECT_STREQ(a.boundary->name, "dynamic");
  EXPECT_STREQ(b.boundary->name, "mdbc");
  EXPECT_EQ(a.integrator, sph::Integrator::Verlet);
  EXPECT_EQ(b.integrator, sph::Integrator::Symplectic);
  EXPECT_TRUE(a.no_penetration);
  EXPECT_FALSE(b.no_penetration);
  EXPECT_FLOAT_EQ(a.rho_min, 700.0f);
  EXPECT_FLOAT_EQ(a.rho_max, 1300.0f);
  EXPECT_FLOAT_EQ(a.prm.mass, 1000.0f * 1e-6f);
}
