// Weakly-compressible SPH solver (SPEC §2): owns the particles and advances them.
#pragma once
#include "surge/core/distribution.hpp"
#include "surge/domain/images.hpp"
#include "surge/neighbour/uniform_grid.hpp"
#include "surge/par/phase_timer.hpp"
#include "surge/particles/particle_store.hpp"
#include "surge/sph/boundary/boundary_model.hpp"
#include "surge/sph/boundary/wall_hold.hpp"
#include "surge/sph/initial_state.hpp"
#include "surge/sph/moving_walls.hpp"
#include "surge/sph/solver_config.hpp"
#include "surge/sph/wcsph_rates.hpp"

#include <cstdint>
#include <memory>
#include <vector>

namespace surge::sph {

struct StepStats {
  double dt = 0;
  int removed_domain = 0;          // left the domain this step
  int removed_density = 0;         // density left [rho_min, rho_max] rho0
  int non_finite = 0;              // NaN / inf in position, velocity or density
  Vec3 removed_lo{}, removed_hi{}; // where: bounding box of the removed particles with finite positions (local)
};

class WcsphSolver {
public:
  // Holds init.particles, or `held` instead (a distributed run starts empty and receives its
  // slab; the grid still covers every particle of init).
  WcsphSolver(const SolverConfig& cfg, const InitialState& init, const particles::HostParticles* held = nullptr);
  // The same, taking init's particles (released as they are uploaded: the construction's
  // peak memory stays below the run's); init's other members are left as they were.
  WcsphSolver(const SolverConfig& cfg, InitialState&& init);

  // Sorts, computes rates, chooses dt (clipped to dt_max), integrates, flags removals.
  StepStats step(double dt_max);
  // The time step the current state allows (SPEC §2.5); computes rates if needed.
  double stable_dt();

  [[nodiscard]] const WcsphParams& params() const { return cfg_.prm; }
  // A distributed run: the store carries halo flags and sorts by id; dt is the minimum
  // over processes; halo particles are neither counted in dt nor flagged for removal.
  void set_distribution(const Distribution& d);
  // How far (local units) a particle's state after one step depends on others': the kernel
  // support per rate evaluation, plus what the wall model reads beyond it (mDBC: the ghost
  // offset and a support around the ghost). A process holding exact copies of everything
  // within this reach of the particles it owns advances them exactly as one process would.
  [[nodiscard]] double dependency_reach() const;
  // The store, for a distributed run's halo exchange (domain::SlabDecomposition), which
  // adds and removes particles: call invalidate() after changing it.
  particles::ParticleStore& store() { return store_; }
  // Replaces the particles (a distributed run's start); the step count is kept.
  void replace(const particles::HostParticles& h);
  // Particles this process owns (all of them unless distributed).
  [[nodiscard]] int owned_count();
  // The wall model's offsets that turn with the bodies (execution space), by
  // id - first_boundary_id(): the coupling rewrites those of body particles as their
  // spheres turn. Null unless the model keeps them (mdbc).
  [[nodiscard]] Vec3* ghost_offsets() { return boundary_->ghost_offsets(); }
  [[nodiscard]] std::uint32_t first_boundary_id() const { return first_boundary_id_; }
  [[nodiscard]] int size() const { return store_.size(); }
  [[nodiscard]] long step_count() const { return steps_; }
  [[nodiscard]] std::size_t bytes() const {
    return store_.bytes() + grid_.bytes() + boundary_->bytes() + hold_.bytes() + moving_.bytes() + images_.bytes() +
           shift_.size() * sizeof(ShiftSums) + strain_.size() * sizeof(SymTensor);
  }
  [[nodiscard]] neighbour::GridView grid_view() {
    const particles::ParticleView v = store_.view();
    return grid_.view(v.pos, v.kind);
  }
  particles::ParticleView view() { return store_.view(); }
  // What the rates kernel reads of the walls for the no-penetration condition.
  [[nodiscard]] WallHoldView hold_view() const { return hold_.view(); }
  // The particles as stored, images left out (a distributed run's copies kept).
  void download(particles::HostParticles& h, bool history = false) const;
  // The periodic and mirror images (off unless the case has periodic or symmetry faces).
  [[nodiscard]] const domain::Images& images() const { return images_; }
  // Continues from a checkpoint: particles with their integration history, and the step count.
  void restore(const particles::HostParticles& h, long steps);
  // Ensures sorted arrays, pressures and rates describe the current positions (for gauges/output).
  void refresh();
  // Refreshes, then flags the fluid particles at the free surface (the frames' `surface`,
  // shifting.hpp's criterion: position divergence below sph.free_surface).
  void mark_surface();
  // Places the moving walls' particles from their bodies' states (states[k] for
  // InitialState::moving[k]), turning their ghost offsets and no-penetration faces: the run
  // loop calls it after each step with the states at the new time, and at the start.
  void move_walls(const std::vector<RigidState>& states);
  [[nodiscard]] bool has_moving_walls() const { return moving_.any(); }
  // The water's force and moment (about centre[k], local) on the moving walls with
  // wanted[k], from the last rates (MovingWalls::loads).
  std::vector<MovingWalls::Load> moving_loads(const std::vector<bool>& wanted, const std::vector<Vec3d>& centre) {
    return moving_.loads(store_.view(), wanted, centre, cfg_.prm.mass, dist_);
  }
  // Particles were changed from outside (body particles moved, a halo exchange): rates must be recomputed.
  void invalidate() { fresh_ = false; }

private:
  // Everything but the particles (the public constructors upload them).
  struct Unloaded {};
  WcsphSolver(const SolverConfig& cfg, const InitialState& init, Unloaded /*unused*/);
  void sort_and_rates();
  void set_up_images(const InitialState& init);
  void rates();          // the wall model's boundary densities, EOS and rates at the current positions
  void set_sps_stress(); // laminar_sps: each particle's stress from its strain rate of the last rates
  double dt_from_rates();
  int flag_removals(StepStats& s);

  SolverConfig cfg_;
  std::unique_ptr<BoundaryModel> boundary_; // sph.boundary
  WallHold hold_;                           // sph.no_penetration
  MovingWalls moving_;                      // walls with a motion
  domain::Images images_;                   // domain.periodic and domain.symmetry
  par::Buffer<ShiftSums> shift_;            // sph.shifting: each particle's sums from the last rates
  par::Buffer<SymTensor> strain_;           // laminar_sps: each particle's strain rate from the last rates
  std::uint32_t first_boundary_id_ = 0;
  particles::ParticleStore store_;
  neighbour::UniformGrid grid_;
  Vec3 dom_lo_{}, dom_hi_{}; // where fluid may be (InitialState::fluid_lo / fluid_hi)
  Distribution dist_;
  bool fresh_ = false;      // rates match positions
  bool sps_primed_ = false; // laminar_sps: the particles carry the stress of their state (not 0)
  long steps_ = 0;
};

} // namespace surge::sph
