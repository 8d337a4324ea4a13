// Wave gauges (column reading): the water standing on the bed, whatever flies above it.
// Each case is read at its initial state, where the answer is known from the lattice: the
// 0.5 level of the kernel-smoothed filled fraction lies within dp/2 of a lattice box's
// top, and a dry bed's face reads within dp/2 of the face.
#include "test_helpers.hpp"

#include "surge/coupling/body_particles.hpp"
#include "surge/sph/gauges.hpp"
#include "surge/sph/wcsph_solver.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <utility>

using namespace surge;

namespace {

std::vector<double> read_gauges(const std::string& text) {
  const Case c = io::read_case_text(text, "gauges.yaml");
  const auto init = sph::build_initial_state(c);
  sph::WcsphSolver s(sph::solver_config(c), init);
  sph::Gauges g(c, init);
  return g.sample(s);
}

// Height gauges at n points along x from x0 in steps of dx (not a multiple of dp, so the
// lines fall at every offset from the wall lattice), at y = 0.05.
std::string lines(int n, double x0, double dx, const std::string& extra = "") {
  std::string s = "gauges: [";
  for (int k = 0; k < n; ++k)
    s += std::string(k ? ", " : "") + "{name: H" + std::to_string(k) +
         ", type: height, x: " + std::to_string(x0 + k * dx) + ", y: 0.05" + extra + "}";
  return s + "]\n";
}

// The start of a case in the 0.3 x 0.1 x 0.3 m tank at dp = 0.01 with h = h_over_dp dp.
std::string head(const std::string& h_over_dp) {
  return "name: g\ndp: 0.01\nsph: {h_over_dp: " + h_over_dp + "}\ndomain: {min: [0,0,0], max: [0.3,0.1,0.3]}\n";
}

const std::string tank = "walls: [{name: tank, box: {min: [0,0,0], max: [0.3,0.1,0.3]}, open: [zmax]}";

} // namespace

// Height gauges over still water 0.1 m deep with a sheet of spray (two layers) at 0.2 m:
// the default `column` reading is the top of the water standing on the bed, the
// `highest` reading the top of the spray. A dry line reads the bed (the floor, z = 0).
TEST(Gauges, ColumnReadingIgnoresSprayAboveAnAirGap) {
  const double dp = 0.01;
  const auto v =
      read_gauges("name: spray\ndp: 0.01\ndomain: {min: [0,0,0], max: [0.3,0.1,0.3]}\n"
                  "fluid: [{box: {min: [0,0,0], max: [0.2,0.1,0.1]}}, {box: {min: [0,0,0.2], max: [0.2,0.1,0.22]}}]\n" +
                  tank + "]\n" +
                  "gauges: [{name: col, type: height, x: 0.1, y: 0.05}, {name: top, type: height, x: 0.1, y: 0.05, "
                  "surface: highest}, {name: dry, type: height, x: 0.26, y: 0.05}]\n");
  EXPECT_NEAR(v[0], 0.10, dp / 2);
  EXPECT_NEAR(v[1], 0.22, dp / 2);
  EXPECT_NEAR(v[2], 0.0, dp / 2);
}

// A dry floor under a sheet of water (a jet thrown over an obstacle): every line reads the
// floor, at every offset from the wall lattice and for coarse and fine kernels (the filled
// fraction at the face comes out between about 0.45 and 0.55); `highest` reads the sheet.
TEST(Gauges, DryBedUnderASheetReadsTheBed) {
  const double dp = 0.01;
  for (const char* h : {"1.0", "1.2", "1.5"}) {
    const std::string sheet = "fluid: [{box: {min: [0,0,0.15], max: [0.3,0.1,0.17]}}]\n" + tank + "]\n";
    const auto v = read_gauges(head(h) + sheet + lines(9, 0.1, 0.00123));
    for (std::size_t k = 0; k < v.size(); ++k) EXPECT_NEAR(v[k], 0.0, dp / 2) << "h/dp " << h << ", line " << k;
    const auto top = read_gauges(head(h) + sheet + lines(3, 0.1, 0.00123, ", surface: highest"));
    for (double t : top) EXPECT_NEAR(t, 0.17, dp / 2) << "h/dp " << h;
  }
}

// A sloping mesh bed (z = 0.02 + 0.25 x, a 14-degree solid slope in the tank): dry under a
// sheet at 0.2 m it reads the slope's height under each line; under still water 0.12 m
// deep it reads the water's top.
TEST(Gauges, SlopingMeshBedReadsTheSlopeOrTheWaterOnIt) {
  const double dp = 0.01;
  const std::string slope = test::write_slope(0.02, 0.25);
  const std::string walls = tank + ", {name: slope, mesh: " + slope + ", solid: true}]\n";
  const std::string start = head("1.2");
  const int n = 13;
  const double x0 = 0.04, dx = 0.0173;
  const auto dry =
      read_gauges(start + "fluid: [{box: {min: [0,0,0.2], max: [0.3,0.1,0.22]}}]\n" + walls + lines(n, x0, dx));
  for (int k = 0; k < n; ++k) EXPECT_NEAR(dry[k], 0.02 + 0.25 * (x0 + k * dx), dp / 2) << "line " << k;
  const auto wet =
      read_gauges(start + "fluid: [{box: {min: [0,0,0], max: [0.3,0.1,0.12]}}]\n" + walls + lines(n, x0, dx));
  for (int k = 0; k < n; ++k) EXPECT_NEAR(wet[k], 0.12, dp / 2) << "line " << k;
  std::filesystem::remove(slope);
}

// A line that starts below the tank (the domain reaches 0.1 m under its floor): water
// 0.1 m deep reads 0.1, the dry part of the floor under a sheet reads the floor, not the
// domain's bottom or the sheet (the scan starts at the floor's face, not in the void or
// the wall layers under it).
TEST(Gauges, LineStartingBelowTheTankReadsFromTheFloor) {
  const double dp = 0.01;
  const auto v = read_gauges("name: below\ndp: 0.01\ndomain: {min: [0,0,-0.1], max: [0.3,0.1,0.3]}\n"
                             "fluid: [{box: {min: [0,0,0], max: [0.15,0.1,0.1]}}, "
                             "{box: {min: [0.15,0,0.2], max: [0.3,0.1,0.22]}}]\n" +
                             tank + "]\n" +
                             "gauges: [{name: wet, type: height, x: 0.07, y: 0.05}, "
                             "{name: dry, type: height, x: 0.227, y: 0.05}, {name: dry2, type: height, x: 0.2444, "
                             "y: 0.05}]\n");
  EXPECT_NEAR(v[0], 0.10, dp / 2);
  EXPECT_NEAR(v[1], 0.0, dp / 2);
  EXPECT_NEAR(v[2], 0.0, dp / 2);
}

// A line over a solid box obstacle 0.05 m high: water 0.1 m deep reads 0.1; water 0.03 m
// deep (below the box's top) with a sheet above reads the box's top, at every offset from
// the lattice and for coarse and fine kernels.
TEST(Gauges, LineOverABoxObstacleReadsItsTopWhenDry) {
  const double dp = 0.01;
  const std::string obstacle = tank + ", {name: box, box: {min: [0.1,0,0], max: [0.2,0.1,0.05]}, solid: true}]\n";
  for (const char* h : {"1.0", "1.2", "1.5"}) {
    const auto deep = read_gauges(head(h) + "fluid: [{box: {min: [0,0,0], max: [0.3,0.1,0.1]}}]\n" + obstacle +
                                  lines(9, 0.12, 0.00713));
    for (double d : deep) EXPECT_NEAR(d, 0.10, dp / 2) << "h/dp " << h;
    const auto dry = read_gauges(head(h) +
                                 "fluid: [{box: {min: [0,0,0], max: [0.3,0.1,0.03]}}, "
                                 "{box: {min: [0,0,0.2], max: [0.3,0.1,0.22]}}]\n" +
                                 obstacle + lines(9, 0.12, 0.00713));
    for (double d : dry) EXPECT_NEAR(d, 0.05, dp / 2) << "h/dp " << h;
  }
}

namespace {

// The column readings of n lines from x0 in steps of dx over water 0.085-0.15 m in the
// tank `walls`, with (or without) a deposit of two layers of spheres of radius r, `lift`
// above the bed, their body particles at dp as the coupling places them.
std::vector<double> read_over_deposit(const std::string& walls, bool with_spheres, int n, double x0, double dx,
                                      double lift = 0) {
  const double dp = 0.01, r = 0.02;
  const Case c = io::read_case_text(head("1.2") + "fluid: [{box: {min: [0,0,0.085], max: [0.3,0.1,0.15]}}]\n" + walls +
                                        lines(n, x0, dx),
                                    "deposit.yaml");
  auto init = sph::build_initial_state(c);
  std::vector<dem::Sphere> spheres;
  if (with_spheres)
    for (int layer = 0; layer < 2; ++layer)
      for (double x = r; x < 0.3 - r / 2; x += 2 * r)
        for (double y = r; y < 0.1 - r / 2; y += 2 * r) {
          dem::Sphere s;
          s.pos = Vec3(Vec3d{x, y, lift + r + 2 * r * layer} - init.origin);
          s.radius = static_cast<Real>(r);
          spheres.push_back(s);
        }
  (void)coupling::add_body_particles(c, spheres, coupling::default_layers(1.2 * dp, dp), init);
  sph::WcsphSolver s(sph::solver_config(c), init);
  sph::Gauges g(c, init);
  return g.sample(s);
}

} // namespace

// A porous deposit on the floor (a slide come to rest): two layers of spheres (r = 0.02 m,
// dp = D/4 as in the slide tsunami) on a square lattice, their body particles filling
// about a third of the pile, with water above it (0.09-0.15 m) but none in its pores, as
// coarse SPH water does not enter them. The column reads the water's top over the pile at
// every offset from the lattice, not the first gap inside the pile. The same lines with
// the spheres gone (water standing on air) read the floor, and over water 0.1 m deep
// with a sheet 1.5 dp above it (a gap narrower than the kernel's reach) they read the
// water: a gap without spheres in it stays an air gap.
TEST(Gauges, ColumnReadsTheWaterOverAPorousDeposit) {
  const double dp = 0.01;
  const int n = 9;
  const double x0 = 0.1, dx = 0.00517;
  // The second tank has no floor, the lines starting at the domain's bottom: a bed that
  // reads below half filled, as the slide tsunami's deposit did at the slope's toe with the
  // dynamic boundary. The spheres fill the gap from the bed up to the water, and the
  // column reads the water's top, not a dry bed; without the spheres it reads dry.
  const std::pair<const char*, std::string> tanks[] = {
      {"floor", tank + "]\n"},
      {"no floor", "walls: [{name: tank, box: {min: [0,0,0], max: [0.3,0.1,0.3]}, open: [zmin, zmax]}]\n"}};
  for (const auto& [label, walls] : tanks)
    for (const bool with_spheres : {true, false}) {
      const auto v = read_over_deposit(walls, with_spheres, n, x0, dx);
      for (int k = 0; k < n; ++k)
        EXPECT_NEAR(v[k], with_spheres ? 0.15 : 0.0, dp / 2) << label << ", spheres " << with_spheres << ", line " << k;
    }
  // Spheres held off the bed by up to 2 dp, within the kernel's reach of it (resting on
  // others beside the line, or held off by the water: the slide tsunami's toe at 0.84 and
  // 1.1 s with the dynamic boundary, where a sphere's bottom stood 1.3 dp above the floor
  // and M1 read the bed, 6 mm): the gap between the bed's face and the lowest spheres is
  // part of the column. Before, the lines through the pores read the bed from 0.5 dp up,
  // every line from 1 dp.
  for (const double lift : {0.5 * dp, dp, 1.5 * dp, 2 * dp}) {
    const auto v = read_over_deposit(tank + "]\n", true, n, x0, dx, lift);
    for (int k = 0; k < n; ++k) EXPECT_NEAR(v[k], 0.15, dp / 2) << "lift " << lift << ", line " << k;
  }
  const auto sheet = read_gauges(head("1.2") +
                                 "fluid: [{box: {min: [0,0,0], max: [0.3,0.1,0.1]}}, "
                                 "{box: {min: [0,0,0.115], max: [0.3,0.1,0.135]}}]\n" +
                                 tank + "]\n" + lines(n, x0, dx));
  for (int k = 0; k < n; ++k) EXPECT_NEAR(sheet[k], 0.10, dp / 2) << "line " << k;
}
