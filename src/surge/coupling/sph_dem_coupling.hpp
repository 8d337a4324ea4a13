// Two-way SPH-DEM coupling (SPEC §4): body particles follow their spheres rigidly,
// and the fluid's force and moment on each sphere come from its body particles.
//
// One coupled step (paper Fig. 4), driven by the run loop:
//   sph.step()       neighbour lists, rates of fluid, wall and body particles, fluid update
//   after_fluid_step reduce body forces per sphere -> DEM sub-steps with that force held
//                    -> body particles placed from the new sphere states
// and the EOS of the next sph.step() closes the loop.
#pragma once
#include "surge/coupling/body_particles.hpp"
#include "surge/dem/dem_solver.hpp"
#include "surge/sph/wcsph_solver.hpp"
#include <functional>

#include <vector>

namespace surge::coupling {

class SphDemCoupling {
public:
  // dt_dem: the DEM step (SPEC §3); an SPH step is split into ceil(dt / dt_dem) sub-steps.
  SphDemCoupling(const BodyLayout& layout, int n_spheres, Real dt_dem);

  // Fluid force and moment on every sphere from the body particles' accelerations of the
  // last rate evaluation (Eq. 23-24 without the sphere's own weight, which the DEM adds):
  //   F_k = sum_b m_b (a_b - g),  M_k = sum_b m_b (a_b - g) x (r_b - x_k).
  // Each sphere sums its own body particles in body-index order: no atomics, and the same
  // result on any number of threads. The result is the DEM's held external force and
  // moment (DemSolver::external_forces / external_torques read it back).
  void reduce_forces(sph::WcsphSolver& sph, dem::DemSolver& dem);
  // Places every body particle from its sphere's state: r_b = x_k + R(q_k) r_b0,
  // v_b = v_k + w_k x (r_b - x_k).
  void place_bodies(sph::WcsphSolver& sph, dem::DemSolver& dem);
  // reduce_forces, DEM sub-steps over dt, place_bodies. Returns the number of sub-steps.
  // after_sub(k, h), when given, runs after sub-step k of length h (the run's moving walls
  // of the DEM advance there).
  int after_fluid_step(sph::WcsphSolver& sph, dem::DemSolver& dem, double dt,
                       const std::function<void(int, double)>& after_sub = {});

  // A distributed run: each process holds some body particles; their accelerations and
  // positions are combined before the per-sphere sums, and every process then advances
  // the same DEM with the same force (see docs/internals.md, distributed runs).
  // per_sphere: each process's per-sphere sums are combined in rank order instead of the
  // body particles themselves (CouplingConfig::force_sum).
  void set_distribution(const Distribution& d, bool per_sphere = false) {
    dist_ = d;
    per_sphere_ = per_sphere;
  }
  [[nodiscard]] std::size_t n_body() const { return n_body_; }
  [[nodiscard]] Real dt_dem() const { return dt_dem_; }

private:
  void sum_forces(sph::WcsphSolver& sph, dem::DemSolver& dem);
  std::uint32_t first_id_ = 0;
  std::size_t n_body_ = 0;
  int n_spheres_ = 0;
  Real dt_dem_ = 0;
  par::Buffer<Vec3> offset_, ghost_; // body frame: particle offsets, mDBC ghost offsets
  par::Buffer<std::uint32_t> owner_, start_;
  par::Buffer<Vec3> body_acc_, body_pos_; // by body index: the last rates' acceleration and position
  Distribution dist_;
  bool per_sphere_ = false;
  par::Buffer<dem::RigidState> state_;
};

} // namespace surge::coupling
