// The run loop's side of a distributed run (SPEC §6): slabs, halo exchange before every
// step, faces rebalanced as the water moves, particles gathered for output and
// checkpoints, step statistics combined. Inactive (and free) unless surge was built
// with MPI; on one MPI process it is active too, so that one process gives the same
// bits as several.
#pragma once
#include "surge/coupling/sph_dem_coupling.hpp"
#include "surge/domain/slab_decomposition.hpp"
#include "surge/sph/wcsph_solver.hpp"

#include <chrono>
#include <optional>

namespace surge::sim {

class DistributedRun {
public:
  DistributedRun(const Case& c, sph::WcsphSolver& solver, coupling::SphDemCoupling* coupling);
  DistributedRun(const DistributedRun&) = delete; // the distribution points into it
  DistributedRun& operator=(const DistributedRun&) = delete;

  [[nodiscard]] bool active() const { return slabs_.has_value(); }
  // Whether runs are distributed (built with MPI): the solver then starts empty.
  [[nodiscard]] static bool enabled();
  [[nodiscard]] static bool root();
  [[nodiscard]] static int ranks();
  [[nodiscard]] const Distribution& distribution() const { return dist_; }

  // Every process holds `all` alike (the initial state or a checkpoint's particles):
  // faces are placed for an even load and each keeps its slab and halo.
  // With `steps` (a checkpoint), the solver continues at that step count.
  void start(particles::HostParticles all, long steps = -1);
  // A step moved the particles: the halo copies no longer hold what the owners hold.
  void stepped() { stale_ = true; }
  // Before a step, a gauge sample or an output: halo exchange (and every 50 steps a
  // rebalance) if a step has run since the last one.
  void sync();
  // The owned particles of every process by id on rank 0 (empty elsewhere); inactive:
  // the solver's particles as stored.
  void gather(particles::HostParticles& out, bool history);
  // Sums the step's removal counts over processes and merges where they were; `stop`
  // (Ctrl-C seen by any process) and `checkpoint_due` (a wall-clock checkpoint due on any
  // process's clock) become true everywhere.
  void combine(sph::StepStats& s, bool& stop, bool& checkpoint_due) const;
  // Over processes: owned particles, a sum of per-process values.
  [[nodiscard]] long owned_particles();
  [[nodiscard]] static double total(double per_process);
  // Collective: the least and most time any process spent in collective calls (the
  // busiest process waits least; the difference is the load imbalance).
  void measure_waits();
  [[nodiscard]] std::string summary_json() const;

private:
  // For summary.json: exchange time and traffic of this process.
  struct Traffic {
    long exchanges = 0, rebalances = 0;
    double seconds = 0, bytes_sent = 0;
    long halo_now = 0;
  };
  sph::WcsphSolver& solver_;
  std::optional<domain::SlabDecomposition> slabs_;
  Distribution dist_;
  bool stale_ = false;
  Traffic traffic_;
  double wait_min_ = 0, wait_max_ = 0;
  // The last balance check: when, and the collective seconds then.
  bool balance_checked_ = false;
  std::chrono::steady_clock::time_point last_check_{};
  double last_coll_ = 0;
};

} // namespace surge::sim
