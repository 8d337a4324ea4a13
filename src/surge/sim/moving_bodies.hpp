// The run's moving walls (issue 34): each one's motion law and pivot, their poses at a
// time, and the rigid states handed to the SPH solver (and read by the gauges, the wall
// leak count and the output). A law is a function of time, so the states at t are the same
// in a straight run, a restart and on any number of processes.
#pragma once
#include "surge/core/case.hpp"
#include "surge/core/rigid_state.hpp"
#include "surge/motion/motion_law.hpp"
#include "surge/sph/initial_state.hpp"
#include "surge/sph/wcsph_solver.hpp"

#include <vector>

namespace surge::sim {

class MovingBodies {
public:
  // Builds every wall's motion and checks that none drives its wall out of the region the
  // grid and the removal cover (the domain grown by the wall layers) before time.end:
  // InputError naming the wall's motion otherwise.
  MovingBodies(const Case& c, const sph::InitialState& init);
  [[nodiscard]] bool any() const { return !motions_.empty(); }
  [[nodiscard]] std::size_t size() const { return motions_.size(); }
  // Body k's pose at t (k indexes InitialState::moving).
  [[nodiscard]] motion::Pose pose(std::size_t k, double t) const { return motions_[k].at(t); }
  // Every body's state at t, in local coordinates.
  [[nodiscard]] std::vector<RigidState> states(double t) const;
  // Places the moving walls' particles in the solver at time t.
  void place(sph::WcsphSolver& solver, double t) const;
  // The body that moves wall w (index into Case::walls), or -1.
  [[nodiscard]] int body_of_wall(std::size_t w) const;
  [[nodiscard]] const sph::MovingWall& wall(std::size_t k) const { return moving_[k]; }

private:
  std::vector<motion::Motion> motions_;
  std::vector<sph::MovingWall> moving_;
  Vec3d origin_{};
};

} // namespace surge::sim
