// Weakly-compressible SPH solver (SPEC §2): owns the particles and advances them.
#pragma once
#include "surge/core/case.hpp"
#include "surge/core/distribution.hpp"
#include "surge/neighbour/uniform_grid.hpp"
#include "surge/par/phase_timer.hpp"
#include "surge/particles/particle_store.hpp"
#include "surge/sph/boundary_mdbc.hpp"
#include "surge/sph/initial_state.hpp"
#include "surge/sph/wcsph_rates.hpp"

#include <cstdint>
#include <string>
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
  WcsphSolver(const Case& c, const InitialState& init, const particles::HostParticles* held = nullptr);

  // Sorts, computes rates, chooses dt (clipped to dt_max), integrates, flags removals.
  StepStats step(double dt_max);
  // The time step the current state allows (SPEC §2.5); computes rates if needed.
  double stable_dt();

  [[nodiscard]] const WcsphParams& params() const { return prm_; }
  // A distributed run: the store carries halo flags and sorts by id; dt is the minimum
  // over processes; halo particles are neither counted in dt nor flagged for removal.
  void set_distribution(const Distribution& d);
  // How far (local units) a particle's state after one step depends on others': the kernel
  // support per rate evaluation, plus, with mDBC, the ghost offset and the support around the
  // ghost. A process holding exact copies of everything within this reach of the particles
  // it owns advances them exactly as one process would.
  [[nodiscard]] double dependency_reach() const;
  // The store, for a distributed run's halo exchange (domain::SlabDecomposition), which
  // adds and removes particles: call invalidate() after changing it.
  particles::ParticleStore& store() { return store_; }
  // Replaces the particles (a distributed run's start); the step count is kept.
  void replace(const particles::HostParticles& h);
  // Particles this process owns (all of them unless distributed).
  [[nodiscard]] int owned_count();
  // Ghost offsets of the boundary particles (execution space), by id - first_boundary_id():
  // the coupling rewrites those of body particles as their spheres turn. Null unless mdbc
  // (the no-penetration condition alone reads the wall particles' offsets only).
  [[nodiscard]] Vec3* ghost_offsets() { return mdbc_ ? ghost_.data() : nullptr; }
  [[nodiscard]] std::uint32_t first_boundary_id() const { return ghosts_.first_id; }
  [[nodiscard]] int size() const { return store_.size(); }
  [[nodiscard]] long step_count() const { return steps_; }
  [[nodiscard]] std::size_t bytes() const {
    return store_.bytes() + grid_.bytes() + ghost_.bytes() + reach_.bytes() + extra_faces_.bytes() + faces_.bytes();
  }
  [[nodiscard]] neighbour::GridView grid_view() { return grid_.view(store_.view().pos); }
  particles::ParticleView view() { return store_.view(); }
  void download(particles::HostParticles& h, bool history = false) const { store_.download(h, history); }
  // Continues from a checkpoint: particles with their integration history, and the step count.
  void restore(const particles::HostParticles& h, long steps);
  // Ensures sorted arrays, pressures and rates describe the current positions (for gauges/output).
  void refresh();
  // Particles were changed from outside (body particles moved, a halo exchange): rates must be recomputed.
  void invalidate() { fresh_ = false; }

private:
  void sort_and_rates();
  void rates(); // (mDBC boundary densities,) EOS and rates at the current positions
  double dt_from_rates();
  int flag_removals(StepStats& s);

  Case case_;
  WcsphParams prm_;
  bool mdbc_ = false;             // sph.boundary: mdbc (boundary densities from the ghost nodes)
  BoundaryGhosts ghosts_;         // hold: sph.no_penetration
  par::Buffer<Vec3> ghost_;       // mdbc or no penetration: 12 B per boundary particle
  par::Buffer<WallReach> reach_;  // no penetration: 12 B per wall particle
  par::Buffer<Vec3> extra_faces_; // no penetration: 12 B per extra face of an edge or corner particle
  par::Buffer<WallPlane> faces_;  // no penetration: each particle's nearest wall plane, from the last rates (16 B)
  particles::ParticleStore store_;
  neighbour::UniformGrid grid_;
  Vec3 dom_lo_{}, dom_hi_{};
  Distribution dist_;
  double ghost_reach_ = 0; // longest mDBC ghost offset
  bool symplectic_ = false;
  bool fresh_ = false; // rates match positions
  long steps_ = 0;
};

} // namespace surge::sph
