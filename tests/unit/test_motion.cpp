// Prescribed motion laws (motion/) against their closed forms, and the case reader's
// refusals of bad motions.
#include "surge/core/error.hpp"
#include "surge/io/case_reader.hpp"
#include "surge/motion/motion_law.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

using namespace surge;

namespace {
motion::Pose pose_of(MotionSpec s, double t, double g = 9.81) {
  return motion::Motion(s, motion::MotionContext{g, "test", "walls.0.motion"}).at(t);
}
// The law's velocity is its displacement's derivative (central difference, 1e-6 s).
void expect_consistent(const MotionSpec& s, double t, double tol) {
  const double e = 1e-6;
  const Vec3d d = (pose_of(s, t + e).shift - pose_of(s, t - e).shift) * (1 / (2 * e));
  const Vec3d v = pose_of(s, t).vel;
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(v[k], d[k], tol) << s.law << " at t = " << t;
}
std::string write_file(const std::string& name, const std::string& text) {
  const auto p = std::filesystem::temp_directory_path() / (name + std::to_string(::getpid()));
  std::ofstream(p) << text;
  return p.string();
}
} // namespace

TEST(MotionLaws, ConstantVelocityAndUniformAccelerationFromTheirStart) {
  MotionSpec s;
  s.law = "constant_velocity";
  s.velocity = {0, 0, 1.5};
  s.start = 0.1;
  EXPECT_EQ(pose_of(s, 0.05).shift.z, 0);
  EXPECT_EQ(pose_of(s, 0.05).vel.z, 0); // at rest before start
  EXPECT_NEAR(pose_of(s, 0.3).shift.z, 0.3, 1e-12);
  EXPECT_NEAR(pose_of(s, 0.3).vel.z, 1.5, 1e-12);
  s.law = "uniform_acceleration";
  s.velocity = {1, 0, 0};
  s.acceleration = {0, 2, 0};
  const motion::Pose p = pose_of(s, 1.1);
  EXPECT_NEAR(p.shift.x, 1.0, 1e-12);
  EXPECT_NEAR(p.shift.y, 1.0, 1e-12);
  EXPECT_NEAR(p.vel.y, 2.0, 1e-12);
  expect_consistent(s, 0.7, 1e-6);
}

// s = s0 ln cosh(t/t0): starts with acceleration s0/t0^2, ends at speed s0/t0; no overflow late.
TEST(MotionLaws, LnCoshReachesItsTerminalSpeed) {
  MotionSpec s;
  s.law = "ln_cosh";
  s.direction = {std::cos(0.5), 0, -std::sin(0.5)}; // down a slope
  s.s0 = 0.8;
  s.t0 = 0.4;
  EXPECT_NEAR(pose_of(s, 0.01).shift.x / std::cos(0.5), 0.8 * std::log(std::cosh(0.01 / 0.4)), 1e-12);
  EXPECT_NEAR(norm(pose_of(s, 1e-3).vel) / 1e-3, 0.8 / (0.4 * 0.4), 1e-3);
  EXPECT_NEAR(norm(pose_of(s, 1000).vel), 2.0, 1e-12);
  EXPECT_NEAR(norm(pose_of(s, 1000).shift), 0.8 * (1000 / 0.4 - std::log(2.0)), 1e-9);
  expect_consistent(s, 0.3, 1e-6);
}

TEST(MotionLaws, CappedAccelerationIsContinuousAtTheCap) {
  MotionSpec s;
  s.law = "capped_acceleration";
  s.direction = {0, 0, 2}; // normalised
  s.accel = 4;
  s.terminal = 2; // reached at t = 0.5 s, s = 0.5 m
  EXPECT_NEAR(pose_of(s, 0.25).shift.z, 0.125, 1e-12);
  EXPECT_NEAR(pose_of(s, 0.5 - 1e-9).shift.z, 0.5, 1e-8);
  EXPECT_NEAR(pose_of(s, 0.5 + 1e-9).shift.z, 0.5, 1e-8);
  EXPECT_NEAR(pose_of(s, 1.5).shift.z, 2.5, 1e-12);
  EXPECT_NEAR(pose_of(s, 1.5).vel.z, 2, 1e-12);
}

// A flap about a hinge: the rotation angle and its rate; a point on the flap moves on a circle.
TEST(MotionLaws, SinusoidalPistonAndFlap) {
  MotionSpec s;
  s.law = "sinusoidal";
  s.period = 2;
  s.amplitude = {0.1, 0, 0};
  EXPECT_NEAR(pose_of(s, 0.5).shift.x, 0.1, 1e-12);
  EXPECT_NEAR(pose_of(s, 1.0).shift.x, 0, 1e-12);
  expect_consistent(s, 0.3, 1e-6);
  s.amplitude = {};
  s.angle = 10;
  s.axis = {0, 1, 0};
  const motion::Pose p = pose_of(s, 0.5); // the full 10 degrees
  const Vec3d pivot{1, 0, 0}, top{1, 0, 0.5};
  const Vec3d moved = p.place(pivot, top);
  EXPECT_NEAR(norm(moved - pivot), 0.5, 1e-12);
  EXPECT_NEAR(std::atan2(moved.x - 1, moved.z), 10 * M_PI / 180, 1e-12);
  EXPECT_NEAR(p.unplace(pivot, moved).z, 0.5, 1e-12);
  EXPECT_NEAR(pose_of(s, 1e-9).omega.y, 10 * M_PI / 180 * M_PI, 1e-9); // amplitude x 2 pi / period
}

// Goring's piston: the paddle moves with the water under the wave (dX/dt = c eta / (h + eta)),
// its stroke is 2A/(kh) (integral of c eta/(h+eta) over the passage of the wave: 2 A / (k h)
// for the first-order profile), it starts and ends at rest.
TEST(MotionLaws, SolitaryPistonStrokeAndSpeed) {
  MotionSpec s;
  s.law = "solitary";
  s.height = 0.024;
  s.depth = 0.12;
  const double g = 9.81, k = std::sqrt(3 * s.height / (4 * std::pow(s.depth, 3))), c = std::sqrt(g * 0.144);
  const double duration = 2 * (3.8 + 0.2) / (k * c);
  const double stroke = pose_of(s, duration + 1).shift.x;
  // The wave's volume per width over h: 2A/(kh) up to the tails cut at +-3.8 (tanh 3.8 = 0.999).
  EXPECT_NEAR(stroke, 2 * s.height / (k * s.depth), 0.01 * stroke);
  EXPECT_LT(pose_of(s, 0).vel.x, 0.01 * c * s.height / s.depth);
  EXPECT_EQ(pose_of(s, duration + 1).vel.x, 0);
  // At mid-stroke the crest is at the paddle: speed c A / (h + A).
  EXPECT_NEAR(pose_of(s, duration / 2).vel.x, c * s.height / (s.depth + s.height), 1e-3 * c);
  expect_consistent(s, 0.4 * duration, 1e-6);
}

TEST(MotionLaws, TimeSeriesInterpolatesAndHoldsItsLastRow) {
  MotionSpec s;
  s.law = "time_series";
  s.csv_path = write_file("surge_ts_", "t, dx, dy, dz, rx, ry, rz\n0, 0, 0, 0, 0, 0, 0\n1, 0.2, 0, 0, 0, 0, 90\n"
                                       "2, 0.2, 0, 0.4, 0, 0, 90\n");
  const motion::Pose p = pose_of(s, 0.5);
  EXPECT_NEAR(p.shift.x, 0.1, 1e-12);
  EXPECT_NEAR(p.vel.x, 0.2, 1e-12);
  EXPECT_NEAR(p.omega.z, M_PI / 2, 1e-12);
  const Vec3d x = p.place({0, 0, 0}, {1, 0, 0}); // turned by 45 degrees about z
  EXPECT_NEAR(x.x, 0.1 + std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(x.y, std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(pose_of(s, 1.5).shift.z, 0.2, 1e-12);
  EXPECT_NEAR(pose_of(s, 5).shift.z, 0.4, 1e-12);
  EXPECT_EQ(pose_of(s, 5).vel.z, 0);
}

TEST(MotionLaws, BadTimeSeriesNameTheFileAndLine) {
  MotionSpec s;
  s.law = "time_series";
  s.csv_path = write_file("surge_ts_bad_", "0, 0, 0, 0\n0.5, 1, 0, 0\n0.5, 2, 0, 0\n");
  try {
    (void)pose_of(s, 0);
    FAIL() << "accepted a time series whose t does not increase";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), s.csv_path);
    EXPECT_EQ(e.line(), 3);
  }
  s.csv_path = write_file("surge_ts_one_", "0, 0, 0, 0\n");
  EXPECT_THROW((void)pose_of(s, 0), InputError);
  s.csv_path = write_file("surge_ts_cols_", "0, 0, 0\n1, 0, 0\n");
  EXPECT_THROW((void)pose_of(s, 0), InputError);
}

namespace {
// The reader's message for a case whose gate has `motion`, or "" if it reads.
std::string motion_error(const std::string& motion, const std::string& gauges = "") {
  const std::string text = "name: g\ndp: 0.01\ndomain: {min: [0,0,0], max: [0.5,0.1,0.8]}\n"
                           "fluid: [{box: {min: [0,0,0], max: [0.1,0.1,0.2]}}]\n"
                           "walls:\n  - {name: tank, box: {min: [0,0,0], max: [0.5,0.1,0.4]}, open: [zmax]}\n"
                           "  - name: gate\n    box: {min: [0.1,0,0], max: [0.13,0.1,0.3]}\n    solid: true\n" +
                           motion + gauges;
  try {
    const Case c = io::read_case_text(text, "gate.yaml");
    (void)io::read_case_text(io::to_yaml(c), "gate.yaml"); // case.yaml of the run reads back
  } catch (const InputError& e) { return e.what(); }
  return "";
}
} // namespace

TEST(MotionCase, ReadsALawAndRefusesBadOnesNamingTheKey) {
  EXPECT_EQ(motion_error("    motion: {law: constant_velocity, velocity: [0, 0, 1.2]}\n"), "");
  EXPECT_NE(motion_error("    motion: {law: constant_speed, velocity: [0, 0, 1]}\n").find("unknown motion law"),
            std::string::npos);
  const std::string missing = motion_error("    motion: {law: ln_cosh, direction: [1, 0, 0], s0: 1}\n");
  EXPECT_NE(missing.find("walls.1.motion.t0"), std::string::npos) << missing;
  EXPECT_NE(missing.find("is required"), std::string::npos) << missing;
  const std::string extra = motion_error("    motion: {law: constant_velocity, velocity: [0, 0, 1], period: 2}\n");
  EXPECT_NE(extra.find("walls.1.motion.period"), std::string::npos) << extra;
  EXPECT_NE(extra.find("does not apply"), std::string::npos) << extra;
  EXPECT_NE(motion_error("    motion: {law: sinusoidal, period: 1}\n").find("amplitude"), std::string::npos);
  EXPECT_NE(motion_error("    motion: {law: time_series, csv: nowhere.csv}\n").find("not found"), std::string::npos);
  // A body gauge reads a moving wall only.
  const std::string still = motion_error("", "gauges: [{name: b, type: body, wall: tank, component: fx}]\n");
  EXPECT_NE(still.find("does not move"), std::string::npos) << still;
  EXPECT_EQ(motion_error("    motion: {law: constant_velocity, velocity: [0, 0, 1]}\n",
                         "gauges: [{name: b, type: body, wall: gate, component: vz}]\n"),
            "");
}

// --- free bodies (motion/free_body.hpp, geometry/mass_properties.hpp)
#include "surge/geometry/mass_properties.hpp"
#include "surge/motion/free_body.hpp"

namespace {
motion::Matrix3 diag(double a, double b, double c) { return {{{a, 0, 0}, {0, b, 0}, {0, 0, c}}}; }

// A slider on a dry incline at `deg` degrees, released from rest: its speed after 1 s.
double incline_speed(double deg, double mu_s, double mu_k) {
  const double th = deg * M_PI / 180;
  BodySpec b;
  b.free = true;
  b.constraint = "line";
  b.direction = {std::cos(th), 0, -std::sin(th)};
  b.mu_static = mu_s;
  b.mu_kinetic = mu_k;
  motion::FreeBody body(b, 2.0, {0, 0, 1}, diag(1, 1, 1), {0, 0, -9.81});
  for (int k = 0; k < 1000; ++k) body.advance({}, {}, 1e-3);
  return dot(body.pose().vel, b.direction);
}
} // namespace

// Coulomb friction on a rail: a block sticks below tan(theta) = mu_s and slides above with
// a = g (sin(theta) - mu_k cos(theta)).
TEST(FreeBody, SliderOnADryInclineSticksOrSlidesAsCoulombSays) {
  const double mu_s = 0.5, mu_k = 0.4; // tan(26.57 deg) = 0.5
  EXPECT_EQ(incline_speed(25, mu_s, mu_k), 0);
  EXPECT_EQ(incline_speed(26.5, mu_s, mu_k), 0);
  for (double deg : {27.0, 35.0, 45.0}) {
    const double th = deg * M_PI / 180, a = 9.81 * (std::sin(th) - mu_k * std::cos(th));
    EXPECT_NEAR(incline_speed(deg, mu_s, mu_k), a * 1.0, 0.01 * a * 1.0) << deg << " degrees";
  }
  EXPECT_NEAR(incline_speed(35, 0, 0), 9.81 * std::sin(35 * M_PI / 180), 1e-9); // frictionless
}

// A slider stops where friction has taken its speed and stays (it does not run backwards).
TEST(FreeBody, ASliderThatFrictionStopsStaysStopped) {
  BodySpec b;
  b.free = true;
  b.constraint = "line";
  b.direction = {1, 0, 0};
  b.mu_static = 0.6;
  b.mu_kinetic = 0.5;
  b.velocity = {1, 0, 0}; // on a level rail: decelerates at mu_k g, stops after 1 / (0.5 g) s
  motion::FreeBody body(b, 1.0, {}, diag(1, 1, 1), {0, 0, -9.81});
  for (int k = 0; k < 400; ++k) body.advance({}, {}, 1e-3);
  EXPECT_EQ(body.pose().vel.x, 0);
  const double x = body.pose().shift.x;
  EXPECT_NEAR(x, 1 / (2 * 0.5 * 9.81), 1e-3);
  for (int k = 0; k < 400; ++k) body.advance({}, {}, 1e-3);
  EXPECT_EQ(body.pose().shift.x, x);
}

// 6 DOF: a constant moment about a principal axis spins it up as M t / I; without a moment
// an asymmetric body tumbling keeps its angular momentum and kinetic energy; a force gives
// F / m + g.
TEST(FreeBody, SixDegreesOfFreedomFollowEulersEquations) {
  BodySpec b;
  b.free = true;
  motion::FreeBody spin(b, 3.0, {}, diag(0.1, 0.2, 0.3), {0, 0, 0});
  for (int k = 0; k < 100; ++k) spin.advance({0, 0, 0}, {0, 0, 0.6}, 1e-3);
  EXPECT_NEAR(spin.pose().omega.z, 0.6 * 0.1 / 0.3, 1e-12);
  EXPECT_NEAR(spin.pose().omega.x, 0, 1e-12);
  motion::FreeBody tumble(b, 3.0, {}, diag(0.1, 0.2, 0.3), {0, 0, -9.81});
  tumble.advance({0, 0, 29.43}, {0.02, 0.05, 0.01}, 1.0); // an angular impulse, its weight held up, then free
  const Vec3d l0 = tumble.angular_momentum();
  auto energy = [&] {
    const Vec3d w = tumble.pose().omega;
    return 0.5 * dot(w, l0);
  };
  const double e0 = energy();
  for (int k = 0; k < 2000; ++k) tumble.advance({0, 0, 29.43}, {}, 1e-3); // weight held up: no net force
  EXPECT_EQ(tumble.angular_momentum().x, l0.x);
  EXPECT_NEAR(energy(), e0, 2e-3 * e0); // first-order rotation update: small drift
  EXPECT_NEAR(tumble.pose().vel.z, 0, 1e-12);
  const motion::Quat q = tumble.pose().q;
  EXPECT_NEAR(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z, 1, 1e-12);
}

// A closed mesh of a box gives the box's volume, centroid and inertia, either winding.
TEST(MassProperties, AClosedMeshOfABoxIsTheBox) {
  const Box box{{0.1, 0.2, 0.3}, {0.5, 0.4, 0.9}};
  const geometry::MassProperties ref = geometry::box_mass_properties(box);
  EXPECT_NEAR(ref.volume, 0.4 * 0.2 * 0.6, 1e-15);
  geometry::Mesh m;
  const Vec3d c[8] = {{0.1, 0.2, 0.3}, {0.5, 0.2, 0.3}, {0.5, 0.4, 0.3}, {0.1, 0.4, 0.3},
                      {0.1, 0.2, 0.9}, {0.5, 0.2, 0.9}, {0.5, 0.4, 0.9}, {0.1, 0.4, 0.9}};
  const int f[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                        {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  for (auto flip : {false, true}) {
    m.tris.clear();
    for (const auto& t : f)
      m.tris.push_back(flip ? geometry::Triangle{c[t[0]], c[t[2]], c[t[1]]}
                            : geometry::Triangle{c[t[0]], c[t[1]], c[t[2]]});
    const geometry::MassProperties p = geometry::mesh_mass_properties(m);
    EXPECT_NEAR(p.volume, ref.volume, 1e-15);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(p.centroid[k], ref.centroid[k], 1e-14);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) EXPECT_NEAR(p.inertia[i][j], ref.inertia[i][j], 1e-15) << i << j;
  }
}

TEST(MotionCase, FreeBodiesNeedAMassAndASolid) {
  EXPECT_EQ(motion_error("    body: {density: 500}\n"), "");
  EXPECT_EQ(
      motion_error("    body: {mass: 2, constraint: line, direction: [1, 0, -1], mu_static: 0.5, mu_kinetic: 0.4}\n"),
      "");
  EXPECT_NE(motion_error("    body: {constraint: line}\n").find("mass or its density"), std::string::npos);
  EXPECT_NE(motion_error("    body: {mass: 1, density: 500}\n").find("mass or its density"), std::string::npos);
  EXPECT_NE(motion_error("    body: {mass: 1, mu_static: 0.3}\n").find("constraint: line"), std::string::npos);
  EXPECT_NE(
      motion_error("    body: {mass: 1}\n    motion: {law: constant_velocity, velocity: [0, 0, 1]}\n").find("not both"),
      std::string::npos);
  EXPECT_NE(motion_error("    body: {mass: 1, inertia: [1, 0, 1]}\n").find("walls.1.body.inertia"), std::string::npos);
  EXPECT_NE(motion_error("    body: {mass: 1, constraint: rail}\n").find("walls.1.body.constraint"), std::string::npos);
}

// A slider with a travel stops for good at the rail's end.
TEST(FreeBody, ASliderStopsAtTheEndOfItsTravel) {
  BodySpec b;
  b.free = true;
  b.constraint = "line";
  b.direction = {0, 0, -1};
  b.travel = 0.1;
  motion::FreeBody body(b, 1.0, {0, 0, 1}, diag(1, 1, 1), {0, 0, -9.81});
  for (int k = 0; k < 1000; ++k) body.advance({}, {}, 1e-3);
  EXPECT_NEAR(body.pose().shift.z, -0.1, 1e-12);
  EXPECT_EQ(body.pose().vel.z, 0);
}
