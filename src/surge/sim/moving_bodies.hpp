// The run's moving bodies (issue 34): each one's motion law or free body and its pivot,
// their poses at a time, and the rigid states handed to the SPH solver (its moving walls'
// particles) and to the DEM solver (its moving planes and meshes), read by the gauges, the
// wall-leak count and the output. Bodies are numbered: the moving SPH walls first, in case
// order, then the DEM walls with a motion or body of their own; a DEM wall that `follows`
// an SPH wall is that wall's body. A law is a function of time, so the states at t are the
// same in a straight run, a restart and on any number of processes.
#pragma once
#include "surge/core/case.hpp"
#include "surge/core/rigid_state.hpp"
#include "surge/dem/dem_solver.hpp"
#include "surge/motion/free_body.hpp"
#include "surge/motion/motion_law.hpp"
#include "surge/sph/initial_state.hpp"
#include "surge/sph/wcsph_solver.hpp"

#include <memory>
#include <string>
#include <vector>

namespace surge::sim {

// The body DEM wall w of the case moves with (its index as above), or -1 for a still wall.
[[nodiscard]] int dem_wall_body(const Case& c, std::size_t w);

class MovingBodies {
public:
  // Builds every body's motion (a law, or a free body with its mass and inertia) and checks
  // that no law drives its wall out of the region the grid covers (for SPH walls the domain
  // grown by the wall layers, for DEM meshes the domain) before time.end: InputError naming
  // the wall's motion otherwise. init: the SPH walls' particles (null in DEM-only runs).
  MovingBodies(const Case& c, const sph::InitialState* init);
  [[nodiscard]] bool any() const { return !bodies_.empty(); }
  [[nodiscard]] bool any_free() const;
  // A free body that has left its region now (the domain grown by the wall layers for an
  // SPH wall, the domain for a DEM mesh: beyond it the grid clamps and nothing is tested),
  // any of its points (particles, mesh vertices) beyond it: the message naming it; empty
  // while every free body is inside. A run stops on it (exit 3, the last output kept).
  [[nodiscard]] std::string escaped() const;
  [[nodiscard]] std::size_t size() const { return bodies_.size(); }
  // The moving SPH walls: bodies [0, sph_count()).
  [[nodiscard]] std::size_t sph_count() const { return moving_.size(); }
  // Whether some DEM wall moves (the DEM solver then takes the states: attach).
  [[nodiscard]] bool moves_dem() const { return dem_walls_; }
  // Body k's pose at t; a free body's pose now.
  [[nodiscard]] motion::Pose pose(std::size_t k, double t) const;
  [[nodiscard]] const motion::FreeBody* free_body(std::size_t k) const { return bodies_[k].free.get(); }
  // Free body k's mass over its shape's volume.
  [[nodiscard]] double mean_density(std::size_t k) const { return bodies_[k].free->mass() / bodies_[k].volume; }
  // Every body's state at t, in local coordinates.
  [[nodiscard]] std::vector<RigidState> states(double t) const;

  // SPH: places the moving walls' particles at t.
  void place(sph::WcsphSolver& solver, double t) const;
  // After an SPH step of dt: the free bodies the spheres do not touch advance under gravity
  // and the water's force and moment of the solver's last rates (the step's start, as the
  // coupling's spheres); those they touch take the water's load to hold over the DEM steps.
  void advance(sph::WcsphSolver& solver, double dt);

  // DEM: hands the bodies to the solver's moving walls (once, before the first step; only
  // when moves_dem()) and places them at t.
  void attach(dem::DemSolver& dem, double t) const;
  void place(dem::DemSolver& dem, double t) const;
  // After a DEM step of dt ending at t: the free bodies the spheres touch advance under
  // gravity, the spheres' loads of that step and the water's held load; the DEM walls are
  // placed at t.
  void advance(dem::DemSolver& dem, double dt, double t);
  // The spheres' force and moment (about the pivot) on body k in the last DEM step.
  [[nodiscard]] dem::WallLoadD dem_load(std::size_t k) const { return dem_load_[k]; }

  // The free bodies' states (checkpoints; empty without free bodies) and back.
  [[nodiscard]] std::string save() const;
  void restore(const std::string& bytes, const std::string& path);
  [[nodiscard]] const sph::MovingWall& wall(std::size_t k) const { return moving_[k]; }
  // The body a gauge names (an SPH wall's or a DEM wall's), or -1.
  [[nodiscard]] int body_named(const std::string& name) const;
  // A body gauge on a DEM wall's own body at t: its state, and the spheres' load on it.
  [[nodiscard]] double dem_gauge_value(const GaugeSpec& g, double t) const;

private:
  struct Body {
    std::unique_ptr<motion::Motion> law;
    std::unique_ptr<motion::FreeBody> free;
    std::string name;
    Vec3d pivot{};        // as placed (absolute)
    bool touched = false; // some DEM wall moves with it: advanced at the DEM's steps
    Vec3d water_force{}, water_moment{};
    std::vector<Vec3d> points; // a free body's points as placed (absolute): escaped
    double volume = 0;         // a free body's shape's
    Box region;
  };
  std::vector<Body> bodies_;
  std::vector<sph::MovingWall> moving_;
  std::vector<dem::WallLoadD> dem_load_;
  Vec3d origin_{};
  bool dem_walls_ = false;
};

// surge check's lines on the moving walls (SPH and DEM): law, start, pivot and where the
// law has taken each by time.end, or the free body's mass and centre.
void print_moving_walls(const Case& c, const MovingBodies& bodies);

} // namespace surge::sim
