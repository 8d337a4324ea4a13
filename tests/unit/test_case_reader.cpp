// Case files: defaults, overrides, and one clear error (file, line, key) per bad input.
#include "test_helpers.hpp"

#include "surge/core/error.hpp"
#include "surge/io/case_schema.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace surge;

namespace {

// Expects an InputError whose message names `key` and whose line is `line` (0: any).
void expect_error(const std::string& text, int line, const std::string& key, const std::string& fragment,
                  const io::Overrides& sets = {}) {
  try {
    (void)io::read_case_text(text, "bad.yaml", sets);
    ADD_FAILURE() << "no error for key " << key;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.key(), key) << msg;
    if (line > 0) { EXPECT_EQ(e.line(), line) << msg; }
    EXPECT_NE(msg.find(fragment), std::string::npos) << msg;
    EXPECT_EQ(msg.rfind("bad.yaml", 0), 0U) << msg;
  }
}

} // namespace

TEST(CaseReader, DefaultsFromSpec) {
  const Case c = io::read_case_text(test::tank_case(0.01), "t.yaml");
  EXPECT_DOUBLE_EQ(c.sph.h_over_dp, 1.2);
  EXPECT_DOUBLE_EQ(c.sph.alpha, 0.01);
  EXPECT_DOUBLE_EQ(c.sph.delta, 0.1);
  EXPECT_DOUBLE_EQ(c.sph.eta, 20);
  EXPECT_DOUBLE_EQ(c.sph.cfl, 0.2);
  EXPECT_EQ(c.sph.euler_every, 10);
  // The settings docs/validation.md recommends for waves (issue 35), not the paper's.
  EXPECT_EQ(c.sph.boundary, "mdbc");
  EXPECT_EQ(c.sph.viscosity, "laminar");
  EXPECT_EQ(c.sph.shifting, "fickian");
  EXPECT_DOUBLE_EQ(c.gravity.z, -9.81);
  EXPECT_DOUBLE_EQ(c.water_depth(), 0.16);
  ASSERT_EQ(c.walls.size(), 1U);
  EXPECT_EQ(c.walls[0].open.size(), 1U);
}

TEST(CaseReader, OverridesAndRoundTrip) {
  const Case c = io::read_case_text(
      test::tank_case(0.01), "t.yaml",
      {"dp=0.02", "time.end=0.5", "sph.viscosity=artificial", "sph.alpha=0.05", "fluid.0.velocity=[1,0,0]"});
  EXPECT_DOUBLE_EQ(c.dp, 0.02);
  EXPECT_DOUBLE_EQ(c.time.end, 0.5);
  EXPECT_DOUBLE_EQ(c.sph.alpha, 0.05);
  EXPECT_DOUBLE_EQ(c.fluid[0].velocity.x, 1.0);
  // case.yaml as written must read back to the same case.
  const Case d = io::read_case_text(io::to_yaml(c), "t.yaml");
  EXPECT_EQ(io::to_yaml(c), io::to_yaml(d));
  EXPECT_DOUBLE_EQ(d.sph.alpha, 0.05);
}

// alpha belongs to the artificial viscosity, which is no longer the default: a case (or a
// --set) that gives alpha and leaves the viscosity out would silently run laminar.
TEST(CaseReader, AlphaNeedsTheArtificialViscosityNamed) {
  expect_error(test::tank_case(0.01) + "sph: {h_over_dp: 1.2,\n      alpha: 0.02}\n", 8, "sph.alpha",
               "add sph.viscosity: artificial");
  const Case c = io::read_case_text(test::tank_case(0.01) + "sph: {viscosity: artificial, alpha: 0.02}\n", "t.yaml");
  EXPECT_EQ(c.sph.viscosity, "artificial");
  EXPECT_DOUBLE_EQ(c.sph.alpha, 0.02);
  // Named on the command line, the viscosity may change a case that sets alpha (SPHERIC's
  // docs run cases/spheric_test2.yaml with --set sph.viscosity=laminar).
  EXPECT_NO_THROW((void)io::read_case_text(test::tank_case(0.01) + "sph: {viscosity: artificial, alpha: 0.02}\n",
                                           "t.yaml", {"sph.viscosity=laminar"}));
}

// Every case shipped reads back from the case.yaml a run writes: the same case (every
// list item kind: box and mesh walls, each gauge type, DEM walls, box, mesh and CSV packs).
namespace {
// The shipped cases' folder; SURGE_CASES_DIR overrides the source tree's (the device check
// runs this binary in a copy of the tree at another path).
std::string cases_dir() {
  const char* dir = std::getenv("SURGE_CASES_DIR");
  return dir != nullptr ? dir : std::string(SURGE_SOURCE_DIR) + "/cases";
}
} // namespace

TEST(CaseReader, EveryShippedCaseRoundTrips) {
  int n = 0;
  for (const auto& f : std::filesystem::directory_iterator(cases_dir())) {
    if (f.path().extension() != ".yaml") continue;
    const Case c = io::read_case(f.path().string());
    const std::string once = io::to_yaml(c);
    const Case d = io::read_case_text(once, f.path().string()); // relative files resolve from the same folder
    EXPECT_EQ(once, io::to_yaml(d)) << f.path();
    EXPECT_EQ(c.gauges.size(), d.gauges.size()) << f.path();
    EXPECT_EQ(c.dem.packs.size(), d.dem.packs.size()) << f.path();
    ++n;
  }
  EXPECT_GE(n, 11);
}

TEST(CaseReader, MalformedYaml) { expect_error("name: x\ndp: [0.01\n", 0, "", "malformed YAML"); }

TEST(CaseReader, UnknownKeyIsATypo) {
  expect_error(test::tank_case(0.01) + "sph: {h_over_dp: 1.2, alpah: 0.01}\n", 7, "sph.alpah", "did you mean 'alpha'");
}

TEST(CaseReader, WrongType) {
  expect_error(test::tank_case(0.01) + "sph: {cfl: fast}\n", 7, "sph.cfl", "expected a number");
}

TEST(CaseReader, UnknownChoice) {
  expect_error(test::tank_case(0.01) + "sph: {diffusion: fourtak}\n", 7, "sph.diffusion", "molteni or fourtakas");
  expect_error(test::tank_case(0.01) + "sph: {integrator: euler}\n", 7, "sph.integrator", "verlet or symplectic");
}

TEST(CaseReader, NegativeCheckpointInterval) {
  expect_error(test::tank_case(0.01), 0, "time.checkpoint_every_wall", "must not be negative",
               {"time.checkpoint_every_wall=-1"});
}

TEST(CaseReader, NonPositiveSpacing) {
  std::string t = test::tank_case(0.01);
  t.replace(t.find("dp: "), std::string("dp: 0.010000").size(), "dp: -0.01");
  expect_error(t, 2, "dp", "must be positive");
}

TEST(CaseReader, NonPositiveSpacingFromCommandLine) {
  expect_error(test::tank_case(0.01), 0, "dp", "--set dp", {"dp=0"});
}

TEST(CaseReader, WaterOutsideTheTank) {
  const std::string t = "name: x\ndp: 0.01\ndomain: {min: [0,0,0], max: [1,1,1]}\n"
                        "fluid:\n  - box: {min: [0,0,0], max: [1.5,1,0.5]}\n";
  expect_error(t, 5, "fluid.0.box", "outside the domain");
}

TEST(CaseReader, WaterCrossingTheTankWalls) {
  const std::string t = "name: x\ndp: 0.01\ndomain: {min: [0,0,0], max: [2,1,1]}\n"
                        "fluid:\n  - box: {min: [0,0,0], max: [1.5,1,0.5]}\n"
                        "walls:\n  - {name: tank, box: {min: [0,0,0], max: [1,1,1]}}\n";
  expect_error(t, 5, "fluid.0.box", "crosses the walls of 'tank'");
}

TEST(CaseReader, EmptyFluidRegion) {
  const std::string t = "name: x\ndp: 0.01\ndomain: {min: [0,0,0], max: [1,1,1]}\n"
                        "fluid:\n  - box: {min: [0,0,0], max: [0.5,0.005,0.5]}\n";
  expect_error(t, 5, "fluid.0.box", "thinner than dp");
}

TEST(CaseReader, MissingMesh) {
  const std::string t = "name: x\ndp: 0.01\ndomain: {min: [0,0,0], max: [1,1,1]}\n"
                        "walls:\n  - mesh: no_such_obstacle.stl\n";
  expect_error(t, 5, "walls.0.mesh", "not found");
}

TEST(CaseReader, MissingRequiredKey) {
  expect_error("name: x\ndomain: {min: [0,0,0], max: [1,1,1]}\n", 1, "dp", "required");
}

TEST(CaseReader, UnknownGaugeType) {
  expect_error(test::tank_case(0.01) + "gauges:\n  - {name: G, type: speed, at: [0.1, 0.05, 0.05]}\n", 8,
               "gauges.0.type", "unknown gauge type");
}

// A key given twice is an error naming both lines, at the top level and inside lists.
TEST(CaseReader, KeyGivenTwice) {
  // tank_case puts dp on line 2; the repeated dp is line 7.
  expect_error(test::tank_case(0.01) + "dp: 0.02\n", 7, "dp", "given twice, on line 2 and on line 7");
  expect_error(test::tank_case(0.01) + "gauges:\n  - {name: a, type: height, x: 0.1, y: 0.05, x: 0.2}\n", 8,
               "gauges.0.x", "given twice");
}

// The schema (io/case_schema.cpp) is where each key's range and choices live: for every
// key of the keyed sections, a value just outside its range (or a value not among its
// choices) is rejected with the key's name and the range's message, and every key is in
// the reference users read.
namespace {
std::string number(double v) {
  std::ostringstream s;
  s << v; // integers without a decimal point, for integer keys
  return s.str();
}
// `prefix` as --set writes it ("dem.materials.0."), `doc_prefix` as the reference does.
template <class S>
void expect_schema_checks(const std::string& text, const std::string& prefix, const std::string& doc_prefix,
                          const std::vector<io::Field<S>>& fields) {
  for (const auto& f : fields) {
    const std::string key = prefix + f.key;
    std::vector<std::string> bad;
    if (!f.choices.empty()) bad.push_back("nonsense");
    if (std::isfinite(f.range.lo)) bad.push_back(number(f.range.lo_open ? f.range.lo : f.range.lo - 1));
    if (std::isfinite(f.range.hi)) bad.push_back(number(f.range.hi_open ? f.range.hi : f.range.hi + 1));
    for (const auto& v : bad)
      expect_error(text, 0, key, f.choices.empty() ? f.range.message() : "must be " + f.choices[0], {key + "=" + v});
    EXPECT_NE(io::case_reference_markdown().find("`" + doc_prefix + f.key + "`"), std::string::npos) << key;
  }
}
} // namespace

TEST(CaseSchema, EveryRangeAndChoiceIsCheckedWithTheKeyNamed) {
  const std::string dem_case = test::tank_case(0.01) +
                               "dem:\n  materials: [{name: rock}]\n"
                               "  packs: [{box: {min: [0.05, 0.02, 0.2], max: [0.1, 0.06, 0.25]}, radius: 0.01, "
                               "material: rock}]\n";
  ASSERT_NO_THROW((void)io::read_case_text(dem_case, "bad.yaml"));
  expect_schema_checks(test::tank_case(0.01), "time.", "time.", io::time_fields());
  expect_schema_checks(test::tank_case(0.01), "sph.", "sph.", io::sph_fields());
  expect_schema_checks(test::tank_case(0.01), "coupling.", "coupling.", io::coupling_fields());
  expect_schema_checks(dem_case, "dem.", "dem.", io::dem_fields());
  expect_schema_checks(dem_case, "dem.materials.0.", "dem.materials[].", io::material_fields());
  expect_schema_checks(dem_case, "dem.packs.0.", "dem.packs[].", io::pack_fields());
  expect_schema_checks(test::tank_case(0.01), "fluid.0.", "fluid[].", io::fluid_fields());
  expect_schema_checks(test::tank_case(0.01), "walls.0.", "walls[].", io::wall_fields());
  expect_schema_checks(test::hydrostatic_tank_case(), "gauges.1.", "gauges[].", io::gauge_fields());
  // A value on the closed end of a range is allowed (dem.dt_factor = 0.5, sph.alpha = 0).
  EXPECT_NO_THROW(
      (void)io::read_case_text(dem_case, "ok.yaml", {"dem.dt_factor=0.5", "sph.viscosity=artificial", "sph.alpha=0"}));
}

// The allowed-key lists of the reader come from the schema: an unknown key is rejected
// with the closest declared one, in a list item as in a section.
TEST(CaseSchema, AllowedKeysComeFromTheSchema) {
  EXPECT_EQ(io::keys_under("coupling"), (std::vector<std::string>{"body_layers", "force_sum"}));
  EXPECT_EQ(io::keys_under("fluid[]"), (std::vector<std::string>{"box", "reservoir", "particles", "velocity", "fill"}));
  expect_error(test::tank_case(0.01) + "coupling: {force_summ: exact}\n", 7, "coupling.force_summ",
               "did you mean 'force_sum'");
  expect_error(test::tank_case(0.01), 0, "fluid.0.velocty", "did you mean 'velocity'", {"fluid.0.velocty=[1,0,0]"});
}

// Real sites (issue 22): a reservoir's level and seed, a wall of one shape, hazard maps on
// a terrain with a still level; each error names the line and key.
TEST(CaseReader, ReservoirAndHazardInputErrors) {
  const std::string head = "name: site\ndp: 0.01\ndomain: {min: [0, 0, 0], max: [0.2, 0.1, 0.3]}\n";
  expect_error(head + "fluid: [{reservoir: {level: 0.5, seed: [0.1, 0.05]}}]\n", 4, "fluid.0.reservoir.level",
               "above the domain's top");
  expect_error(head + "fluid: [{reservoir: {level: 0.005, seed: [0.1, 0.05]}}]\n", 4, "fluid.0.reservoir.level",
               "below the domain's bottom");
  expect_error(head + "fluid: [{reservoir: {level: 0.1, seed: [0.5, 0.05]}}]\n", 4, "fluid.0.reservoir.seed",
               "outside the domain");
  expect_error(head + "fluid: [{reservoir: {level: 0.1, seed: [0.1]}}]\n", 4, "fluid.0.reservoir.seed",
               "expected [x, y]");
  expect_error(head + "fluid: [{box: {min: [0, 0, 0], max: [0.1, 0.1, 0.1]}, reservoir: {level: 0.1, seed: [0, 0]}}]\n",
               4, "fluid.0", "exactly one of 'box', 'reservoir' or 'particles'");
  expect_error(test::tank_case(0.01) + "hazard: {coarsen: 2}\n", 7, "hazard", "needs a wall with 'terrain'");
  expect_error(head + "walls: [{box: {min: [0, 0, 0], max: [0.2, 0.1, 0.3]}, terrain: ground.tif}]\n", 4, "walls.0",
               "exactly one of 'box', 'mesh' (an STL file) or 'terrain'");
}

// A pack's radius range: radius_min at most radius (the largest, which sets the spacing);
// a CSV list gives each radius and takes no range, jitter or random count.
TEST(CaseReader, PackRadiusRange) {
  const std::string head = test::tank_case(0.01) + "dem:\n  materials: [{name: rock}]\n  packs: [{";
  const std::string box = "box: {min: [0.05, 0.02, 0.2], max: [0.1, 0.06, 0.25]}, radius: 0.01, material: rock";
  const auto ok = io::read_case_text(head + box + ", radius_min: 0.006}]\n", "ok.yaml");
  EXPECT_DOUBLE_EQ(ok.dem.packs[0].radius_min, 0.006);
  expect_error(head + box + ", radius_min: 0.012}]\n", 9, "dem.packs.0.radius_min", "must not exceed radius");
  expect_error(head + box + ", random: 10, jitter: 0.1}]\n", 9, "dem.packs.0", "a 'random' pack has none");
  expect_error(head + "csv: spheres.csv, material: rock, radius_min: 0.006}]\n", 9, "dem.packs.0",
               "do not apply to a CSV list");
}

// Issue 33: periodic and symmetry faces, damping zones.
namespace {
std::string slab(const std::string& domain_extra, const std::string& open = "[zmax, ymin, ymax]",
                 const std::string& extra = "", const std::string& width = "0.06") {
  return "name: slab\ndp: 0.01\ntime: {end: 0.1, output_every: 0.05}\n"
         "domain: {min: [0, 0, 0], max: [0.3, " +
         width + ", 0.2]" + domain_extra +
         "}\n"
         "fluid: [{box: {min: [0, 0, 0], max: [0.3, " +
         width +
         ", 0.1]}}]\n"
         "walls: [{name: tank, box: {min: [0, 0, 0], max: [0.3, " +
         width + ", 0.2]}, open: " + open + "}]\n" + extra;
}
} // namespace

TEST(CaseReader, ImageFacesAndDamping) {
  const Case c = io::read_case_text(slab(", periodic: [ymin, ymax], symmetry: [xmin]", "[zmax, ymin, ymax, xmin]",
                                         "damping: [{face: xmax, length: 0.1}]\n"),
                                    "t.yaml");
  EXPECT_TRUE(c.periodic[1] && !c.periodic[0] && !c.periodic[2]);
  EXPECT_TRUE(c.symmetry[0] && !c.symmetry[1]);
  ASSERT_EQ(c.damping.size(), 1U);
  EXPECT_EQ(c.damping[0].face, Face::XMax);
  EXPECT_DOUBLE_EQ(c.damping[0].length, 0.1);
  EXPECT_DOUBLE_EQ(c.damping[0].rate, 10.0);
  // Written back and read again: the same faces and zones.
  const Case d = io::read_case_text(io::to_yaml(c), "again.yaml");
  EXPECT_EQ(d.periodic, c.periodic);
  EXPECT_EQ(d.symmetry, c.symmetry);
  ASSERT_EQ(d.damping.size(), 1U);
  EXPECT_DOUBLE_EQ(d.damping[0].length, 0.1);
}

TEST(CaseReader, ImageFaceInputErrors) {
  expect_error(slab(", periodic: [ymin]"), 4, "domain.periodic", "come in pairs");
  expect_error(slab(", periodic: [ymin, ymax, ymin]"), 4, "domain.periodic", "listed twice");
  expect_error(slab(", periodic: [ymin, ymax]", "[zmax]"), 6, "walls.0.open", "add ymin to 'open'");
  expect_error(slab(", symmetry: [ymax]", "[zmax]"), 6, "walls.0.open", "add ymax to 'open'");
  expect_error(slab(", periodic: [ymin, ymax], symmetry: [ymax]"), 4, "domain.symmetry", "periodic already");
  expect_error(slab(", symmetry: [ymax, ymax]", "[zmax, ymax]"), 4, "domain.symmetry", "listed twice");
  // A period under two kernel radii (4 h = 4.8 cm at dp = 1 cm).
  expect_error(slab(", periodic: [ymin, ymax]", "[zmax, ymin, ymax]", "", "0.04"), 4, "domain.periodic",
               "at least two kernel radii");
  // A wall beyond a symmetry face (water beyond the domain is refused before).
  std::string beyond = slab(", symmetry: [xmax]", "[zmax, xmax]");
  beyond.replace(beyond.find("}]\n", beyond.find("walls:")), 3,
                 "}, {name: block, box: {min: [0.25, 0, 0], max: [0.35, 0.06, 0.05]}, solid: true}]\n");
  expect_error(beyond, 0, "walls.1.box", "beyond the symmetry face xmax");
}

TEST(CaseReader, DemWithPeriodicFaces) {
  const std::string dem = "dem:\n  materials: [{name: rock}]\n"
                          "  packs: [{box: {min: [0.1, 0, 0.12], max: [0.2, 0.06, 0.16]}, radius: 0.01, "
                          "material: rock}]\n";
  const std::string periodic = slab(", periodic: [ymin, ymax]", "[zmax, ymin, ymax]", dem, "0.1");
  EXPECT_NO_THROW((void)io::read_case_text(periodic, "t.yaml"));
  EXPECT_NO_THROW((void)io::read_case_text(
      periodic + "  walls: [{plane: {point: [0, 0, 0], normal: [0, 0, 1]}, material: rock}]\n", "t.yaml"));
  expect_error(periodic + "  walls: [{plane: {point: [0, 0, 0], normal: [0, 1, 1]}, material: rock}]\n", 0,
               "dem.walls.0.normal", "periodic axis y");
  const std::string mesh = cases_dir() + "/slide_slope.stl";
  expect_error(periodic + "  walls: [{mesh: " + mesh + ", material: rock}]\n", 0, "dem.walls.0",
               "not yet allowed with periodic or symmetry");
}

TEST(CaseReader, DemWithSymmetryFaces) {
  const std::string dem = "dem:\n  materials: [{name: rock}]\n"
                          "  packs: [{box: {min: [0.1, 0, 0.12], max: [0.2, 0.06, 0.16]}, radius: 0.01, "
                          "material: rock}]\n";
  const std::string half = slab(", symmetry: [ymax]", "[zmax, ymax]", dem, "0.1");
  EXPECT_NO_THROW((void)io::read_case_text(half, "t.yaml"));
  EXPECT_NO_THROW((void)io::read_case_text(
      half + "  walls: [{plane: {point: [0, 0, 0], normal: [0, 0, 1]}, material: rock}]\n", "t.yaml"));
  expect_error(half + "  walls: [{plane: {point: [0, 0, 0], normal: [0, 1, 1]}, material: rock}]\n", 0,
               "dem.walls.0.normal", "symmetry axis y");
  const std::string mesh = cases_dir() + "/slide_slope.stl";
  expect_error(half + "  walls: [{mesh: " + mesh + ", material: rock}]\n", 0, "dem.walls.0",
               "not yet allowed with periodic or symmetry");
  expect_error(slab(", periodic: [xmin, xmax], symmetry: [ymax]", "[zmax, xmin, xmax, ymax]", dem, "0.1"), 4,
               "domain.symmetry", "both periodic and symmetry");
}

TEST(CaseReader, DampingInputErrors) {
  expect_error(slab("", "[zmax]", "damping: [{face: xmax, length: 0.5}]\n"), 7, "damping.0.length",
               "shorter than the domain");
  expect_error(slab("", "[zmax]", "damping: [{face: xmax, length: -0.1}]\n"), 7, "damping.0.length", "positive");
  expect_error(slab("", "[zmax]", "damping: [{face: xmax, length: 0.1, rate: 0}]\n"), 7, "damping.0.rate", "positive");
  expect_error(slab("", "[zmax]", "damping: [{face: xmux, length: 0.1}]\n"), 7, "damping.0.face", "unknown face");
  expect_error(slab("", "[zmax]", "damping: [{length: 0.1}]\n"), 7, "damping.0.face", "is required");
  expect_error(slab("", "[zmax]", "damping: [{face: xmax, length: 0.1}, {face: xmax, length: 0.2}]\n"), 7,
               "damping.1.face", "given already");
  expect_error(slab(", periodic: [ymin, ymax]", "[zmax, ymin, ymax]", "damping: [{face: ymax, length: 0.01}]\n"), 7,
               "damping.0.face", "periodic or symmetry face");
  expect_error(slab(", symmetry: [xmin]", "[zmax, xmin]", "damping: [{face: xmax, length: 0.2}]\n"), 7,
               "damping.0.length", "past the middle");
  expect_error(slab("", "[zmax]", "damping: [{face: xmax, length: 0.1, speed: 3}]\n"), 7, "damping.0.speed",
               "unknown key");
}
