// Gauges (SPEC §2.7): free-surface height on a vertical line, Shepard-interpolated
// pressure and velocity at a point, force on a wall.
#pragma once
#include "surge/core/case.hpp"
#include "surge/sph/wcsph_solver.hpp"

#include <functional>
#include <string>
#include <vector>

namespace surge::sph {

// Kernel sums at a point over fluid particles: sum V W, sum V W p, sum V W v; and
// sum V W over wall and body particles (solid around the point: a slide's spheres under
// the water are part of the column a wave gauge reads, not an air gap in it), and over
// body particles alone (the DEM spheres: a column's gap inside a porous deposit).
struct PointSums {
  Real vw = 0, vwp = 0;
  Vec3 vwv{};
  Real vw_solid = 0; // walls and bodies; vw + vw_solid is the filled fraction
  Real vw_body = 0;  // the spheres' body particles alone
};
constexpr int kPointSumReals = 7;
static_assert(sizeof(PointSums) == kPointSumReals * sizeof(Real), "PointSums is combined across processes as Reals");

[[nodiscard]] SURGE_HD inline PointSums fluid_sums(const WcsphParams& prm, const neighbour::GridView& g,
                                                   const particles::ParticleView& p, const Vec3& x) {
  PointSums s;
  const Real r2max = prm.kernel.support() * prm.kernel.support();
  const auto fluid = static_cast<std::uint8_t>(Kind::Fluid), wall = static_cast<std::uint8_t>(Kind::Wall),
             body = static_cast<std::uint8_t>(Kind::Body);
  neighbour::for_each_neighbour(g, x, r2max, [&](int j, const Vec3&, Real r2) {
    if (p.kind[j] == wall || p.kind[j] == body) s.vw_solid += prm.mass / p.rho[j] * prm.kernel.w(std::sqrt(r2));
    if (p.kind[j] == body) s.vw_body += prm.mass / p.rho[j] * prm.kernel.w(std::sqrt(r2));
    if (p.kind[j] != fluid) return;
    const Real vw = prm.mass / p.rho[j] * prm.kernel.w(std::sqrt(r2));
    s.vw += vw;
    s.vwp += vw * p.press[j];
    s.vwv += p.vel[j] * vw;
  });
  return s;
}

class Gauges {
public:
  Gauges(const Case& c, const InitialState& init);
  [[nodiscard]] const std::vector<std::string>& names() const { return names_; }
  // One value per gauge for the solver's current state; sphere and dem_wall gauges read
  // the DEM through `sphere_value`, which the coupled run loop supplies.
  // In a distributed run each point is read by the process that owns it and every wall
  // particle's force by its owner: the values are those of one process, bit for bit.
  std::vector<double> sample(WcsphSolver& solver, const std::function<double(const GaugeSpec&)>& sphere_value = {},
                             const Distribution& dist = {});
  // The water column of each height gauge, in gauge order (other gauges read zeros): its
  // bed and top (absolute z; top == bed when dry, as the gauge reads) and the velocity
  // averaged over the column's depth (Shepard sums of its samples up to the top). The same
  // bits on any number of processes, like sample.
  struct Column {
    double bed = 0, top = 0;
    Vec3d velocity{};
    double fluid = 0; // the highest fluid fraction (without walls) of its samples up to the top
    // The water's own surface in the column: where the fluid fraction last falls below 0.5
    // going up to the top (so a slide's spheres standing above the water are not read as
    // water); the bed when no sample reaches 0.5.
    double water_top = 0;
  };
  std::vector<Column> columns(WcsphSolver& solver, const Distribution& dist = {});
  // The moving walls' states (InitialState::moving order, local) that body gauges read.
  void set_bodies(const std::vector<RigidState>& states) { bodies_ = states; }

private:
  struct Probe {
    GaugeSpec spec;
    int first_sample = 0, n_samples = 0;
    std::uint32_t id0 = 0, id1 = 0;
    int body = -1; // body gauges: index into InitialState::moving
  };
  std::vector<RigidState> bodies_;
  Vec3d origin_{};
  std::vector<Probe> probes_;
  std::vector<std::string> names_;
  std::vector<Vec3> points_host_;
  par::Buffer<Vec3> points_;
  par::Buffer<PointSums> sums_;
  par::Buffer<Vec3> wall_acc_; // a force gauge's wall particles' accelerations, by id - first id
  // The water's force on a wall's particles and, with `about` (local), its moment about it.
  struct Load {
    Vec3d force{}, moment{};
  };
  [[nodiscard]] Load wall_load(WcsphSolver& solver, const Probe& pr, const Distribution& dist,
                               const Vec3* about = nullptr);
  [[nodiscard]] double body_value(WcsphSolver& solver, const Probe& pr, const Distribution& dist);
  par::Buffer<Vec3> wall_pos_; // a body gauge's wall particles' positions, by id - first id
  double dz_ = 0;
  int bed_reach_ = 0; // a column's samples within the kernel's reach (2 h) of the bed's face
  double origin_z_ = 0;
  // The kernel sums at every sample point, combined across processes.
  std::vector<PointSums> point_sums(WcsphSolver& solver, const Distribution& dist);
  // column_top's surface and the last sample below it (-1: dry).
  struct Top {
    double z;
    int last;
  };
  [[nodiscard]] Top column_top(const Probe& pr, const std::vector<PointSums>& sums) const;
  [[nodiscard]] int past_pores(const Probe& pr, const std::vector<PointSums>& sums, int k) const;
  [[nodiscard]] int first_near(const Probe& pr, const std::vector<PointSums>& sums) const;
  [[nodiscard]] double highest_wet(const Probe& pr, const std::vector<PointSums>& sums) const;
};

} // namespace surge::sph
