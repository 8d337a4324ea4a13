// Walls hold water: the no-penetration condition (sph/no_penetration.hpp) in closed form,
// a box of water thrown at a wall at 3 m/s with either boundary, and the geometric count
// of fluid found inside walls (sim::WallLeaks).
#include "test_helpers.hpp"

#include "surge/sim/wall_leaks.hpp"
#include "surge/sph/no_penetration.hpp"
#include "surge/sph/wcsph_solver.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace surge;

// A particle 0.6 dp in front of a face moving into it at 2 m/s with 1 m/s along it: kept
// at dp/4 in front, its normal velocity removed (also the leap-frog's other one), its
// tangential velocity kept; a particle moving away is left alone.
TEST(NoPenetration, KeepsAParticleAQuarterSpacingInFrontOfTheFace) {
  const Real dp = Real(0.01);
  const sph::WallPlane face{Vec3{0, 0, 1}, Real(0.1)}; // z = 0.1, water above
  Vec3 x{0.3f, 0.2f, 0.1f + 0.6f * dp}, v{1, 0, -2}, v_prev{1, 0, -2};
  const Vec3 x_next = x + v * Real(0.004); // 0.8 dp down: 0.2 dp behind the face
  Vec3 y = x_next;
  EXPECT_TRUE(sph::keep_off_face(face, dp / 4, y, v, &v_prev));
  EXPECT_NEAR(face.distance(y), dp / 4, 1e-6);
  EXPECT_FLOAT_EQ(y.x, x_next.x);
  EXPECT_FLOAT_EQ(v.x, 1);
  EXPECT_FLOAT_EQ(v.z, 0);
  EXPECT_FLOAT_EQ(v_prev.z, 0);
  Vec3 up{0.3f, 0.2f, 0.1f + 0.6f * dp}, vu{0, 0, 2};
  EXPECT_FALSE(sph::keep_off_face(face, dp / 4, up, vu));
  EXPECT_FLOAT_EQ(vu.z, 2);
}

// The face below a fluid particle from a wall particle's ghost offset: a floor particle
// dp/2 under the face gives the floor; a box's top seen from beside the box (the face
// point 1 dp away sideways) is not taken, nor is the bottom face of a box standing on
// the floor, seen by the water beside it.
TEST(NoPenetration, FaceBelowComesFromTheGhostOffsetOfTheWallParticleUnderneath) {
  const Real dp = Real(0.01);
  const Vec3 xb{0.1f, 0.1f, -0.5f * dp}, o{0, 0, dp}; // floor z = 0
  sph::WallPlane w;
  Real d = 0;
  ASSERT_TRUE(sph::face_below(xb, o, Vec3{0.2f * dp, 0.3f * dp, 0.8f * dp}, dp, w, d));
  EXPECT_NEAR(d, 0.3f * dp, 1e-7);
  EXPECT_NEAR(w.distance(Vec3{0.5f, 0.5f, 0.02f}), 0.02f, 1e-7);
  EXPECT_FALSE(sph::face_below(xb, o, Vec3{1.0f * dp, 0, -0.5f * dp}, dp, w, d));
  // A solid box standing on the floor: its bottom layer mirrors through its bottom face
  // (normal down, z = 0). Water on the floor beside the box (z = dp/2, 0.2 dp in front of
  // the box's side) is behind that face: it must not be held dp/4 below the floor.
  const Vec3 xbox{0.5f, 0.1f, 0.5f * dp}, obox{0, 0, -dp};
  EXPECT_FALSE(sph::face_below(xbox, obox, Vec3{0.7f * dp, 0, 0}, dp, w, d));
}

namespace {

// A 0.1 m box of water 3 cm from the end wall of a closed 0.4 x 0.1 x 0.8 m tank, thrown
// at it at 3 m/s (c0 = 40 m/s, over 13 times the impact speed), followed over 0.05 s (the code before the
// no-penetration condition lost 10 particles through the side walls and floor by then): the water spreads on the wall,
// runs up it and along the floor and side walls.
struct ImpactResult {
  int removed_domain = 0;
  long inside_walls = 0;  // fluid particles found behind a face, summed over checks
  double closest = 1e300; // smallest distance of any fluid particle to a face [m]
};

ImpactResult impact(const std::string& boundary, const std::string& integrator) {
  const Case c =
      io::read_case_text("name: impact\ndp: 0.01\ntime: {end: 0.05}\ndomain: {min: [0,0,0], max: [0.4,0.1,0.8]}\n"
                         "sph: {c0: 40, boundary: " +
                             boundary + ", integrator: " + integrator +
                             "}\n"
                             "fluid: [{box: {min: [0.03,0,0], max: [0.13,0.1,0.1]}, velocity: [-3,0,0]}]\n"
                             "walls: [{name: tank, box: {min: [0,0,0], max: [0.4,0.1,0.8]}}]\n",
                         "impact.yaml");
  const auto init = sph::build_initial_state(c);
  sph::WcsphSolver s(c, init);
  ImpactResult r;
  double t = 0;
  particles::HostParticles h;
  const double size[3] = {0.4, 0.1, 0.8};
  while (t < c.time.end) {
    const auto st = s.step(1.0);
    t += st.dt;
    r.removed_domain += st.removed_domain;
    if (s.step_count() % 5) continue;
    s.download(h);
    for (std::size_t i = 0; i < h.size(); ++i) {
      if (h.kind[i] != static_cast<std::uint8_t>(Kind::Fluid)) continue;
      double d = 1e300;
      for (int k = 0; k < 3; ++k) d = std::min({d, static_cast<double>(h.pos[i][k]), size[k] - h.pos[i][k]});
      r.closest = std::min(r.closest, d);
      if (d < 0) ++r.inside_walls;
    }
  }
  return r;
}

} // namespace

TEST(WallsHoldWater, ImpactAt3msWithMdbcLosesNoWaterThroughTheWalls) {
  for (const char* integrator : {"verlet", "symplectic"}) {
    const auto r = impact("mdbc", integrator);
    EXPECT_EQ(r.removed_domain, 0) << integrator;
    EXPECT_EQ(r.inside_walls, 0) << integrator;
    // The no-penetration condition keeps water dp/4 in front of every face.
    EXPECT_GE(r.closest, 0.0025 - 1e-6) << integrator;
  }
}

TEST(WallsHoldWater, ImpactAt3msWithTheDynamicBoundaryLosesNoWaterThroughTheWalls) {
  const auto r = impact("dynamic", "verlet");
  EXPECT_EQ(r.removed_domain, 0);
  EXPECT_EQ(r.inside_walls, 0);
}

// Fluid particles placed by hand, counted from the walls' geometry: in a tank's side and
// floor layers, inside a solid box, under a solid mesh (a slope), but not above the open
// top, not outside beyond the layers, not in the water.
TEST(WallLeaks, CountsFluidBehindFacesOfTanksBoxesAndMeshes) {
  const std::string slope = test::write_slope(0.02, 0.25); // z = 0.02 + 0.25 x over x, y in [-0.05, 0.35]
  const Case c = io::read_case_text("name: leaks\ndp: 0.01\ndomain: {min: [0,0,0], max: [1,1,1]}\n"
                                    "fluid: [{box: {min: [0.5,0.1,0.5], max: [0.6,0.2,0.6]}}]\n"
                                    "walls: [{name: tank, box: {min: [0,0,0], max: [1,1,1]}, open: [zmax]},\n"
                                    "        {name: block, box: {min: [0.4,0.4,0], max: [0.6,0.6,0.2]}, solid: true},\n"
                                    "        {name: slope, mesh: " +
                                        slope + ", solid: true}]\n",
                                    "leaks.yaml");
  sim::WallLeaks leaks(c);
  particles::HostParticles h;
  std::uint32_t id = 0;
  auto add = [&](double x, double y, double z, Kind k = Kind::Fluid) {
    h.push(Vec3(Vec3d{x, y, z}), Vec3{}, 1000, k, id++);
  };
  add(0.5, 0.5, 0.5);               // water
  add(-0.01, 0.5, 0.3);             // in the xmin wall's layers
  add(0.5, 1.02, 0.3);              // in the ymax wall's layers
  add(0.7, 0.3, -0.001);            // in the floor
  add(0.5, 0.5, 0.1);               // inside the block
  add(0.2, 0.05, 0.06);             // under the slope (0.07 there)
  add(0.2, 0.05, 0.08);             // on the slope
  add(-0.01, 0.5, 1.2);             // above the open top, beside the wall: splashed out, not a leak
  add(0.5, 0.5, 1.3);               // above the open top
  add(-0.2, 0.5, 0.5);              // beyond the wall's layers (left the domain)
  add(0.5, 0.5, 0.25);              // above the block
  add(-0.01, 0.5, 0.3, Kind::Wall); // a wall particle is not fluid
  const auto n = leaks.count(h, Vec3d{});
  EXPECT_EQ(n.count, 5);
  EXPECT_EQ(n.wall, "tank");
  EXPECT_NEAR(n.lo.x, -0.01, 1e-6);
  EXPECT_NEAR(n.hi.y, 1.02, 1e-6);
  EXPECT_NEAR(n.lo.z, -0.001, 1e-6);
  std::filesystem::remove(slope);
}
