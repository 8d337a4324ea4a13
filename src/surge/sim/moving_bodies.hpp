// The run's moving walls (issue 34): each one's motion law and pivot, their poses at a
// time, and the rigid states handed to the SPH solver (and read by the gauges, the wall
// leak count and the output). A law is a function of time, so the states at t are the same
// in a straight run, a restart and on any number of processes.
#pragma once
#include "surge/core/case.hpp"
#include "surge/core/rigid_state.hpp"
#include "surge/motion/free_body.hpp"
#include "surge/motion/motion_law.hpp"
#include "surge/sph/initial_state.hpp"
#include "surge/sph/wcsph_solver.hpp"

#include <memory>
#include <string>
#include <vector>

namespace surge::sim {

class MovingBodies {
public:
  // Builds every wall's motion (a law, or a free body with its mass and inertia) and checks
  // that no law drives its wall out of the region the grid and the removal cover (the
  // domain grown by the wall layers) before time.end: InputError naming the wall's motion
  // otherwise.
  MovingBodies(const Case& c, const sph::InitialState& init);
  [[nodiscard]] bool any() const { return !bodies_.empty(); }
  [[nodiscard]] bool any_free() const;
  [[nodiscard]] std::size_t size() const { return bodies_.size(); }
  // Body k's pose at t (k indexes InitialState::moving); a free body's pose now.
  [[nodiscard]] motion::Pose pose(std::size_t k, double t) const;
  [[nodiscard]] const motion::FreeBody* free_body(std::size_t k) const { return bodies_[k].free.get(); }
  // Advances the free bodies over dt under gravity and the water's force and moment of the
  // solver's last rates (the step's start, as the coupling's spheres).
  void advance(sph::WcsphSolver& solver, double dt);
  // The free bodies' states (checkpoints; empty without free bodies) and back.
  [[nodiscard]] std::string save() const;
  void restore(const std::string& bytes, const std::string& path);
  // Every body's state at t, in local coordinates.
  [[nodiscard]] std::vector<RigidState> states(double t) const;
  // Places the moving walls' particles in the solver at time t.
  void place(sph::WcsphSolver& solver, double t) const;
  // The body that moves wall w (index into Case::walls), or -1.
  [[nodiscard]] int body_of_wall(std::size_t w) const;
  [[nodiscard]] const sph::MovingWall& wall(std::size_t k) const { return moving_[k]; }

private:
  struct Body {
    std::unique_ptr<motion::Motion> law;
    std::unique_ptr<motion::FreeBody> free;
  };
  std::vector<Body> bodies_;
  std::vector<sph::MovingWall> moving_;
  Vec3d origin_{};
};

} // namespace surge::sim
