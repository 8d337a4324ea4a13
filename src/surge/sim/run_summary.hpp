// summary.json, written once for every kind of run (water, coupled, DEM only,
// distributed): the run loop writes it with every output and at the end, from the counts
// its stepper supplies. One format: every key is there in every run (zeros where a model
// is absent), so that scripts read any run's summary alike.
#pragma once
#include "surge/core/case.hpp"
#include "surge/sim/run_loop.hpp"

#include <string>

namespace surge::sim {

// Fluid particles removed during a run, by cause, and where (absolute).
struct Removals {
  long domain = 0, density = 0, non_finite = 0;
  Vec3d lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  [[nodiscard]] long total() const { return domain + density + non_finite; }
};

// What a stepper says of its run.
struct RunCounts {
  std::size_t fluid = 0, wall = 0, body = 0, spheres = 0; // at the start
  // The particles one step advances, for particle_steps_per_second and bytes_per_particle:
  // fluid, walls and body particles in a run with water, the spheres in a DEM-only run.
  std::size_t stepped = 0;
  long fluid_now = 0; // fluid particles held now (every process)
  Removals removed;
  std::string in_walls = "null";    // LeakRecord::json of a run with water
  std::string distributed = "null"; // DistributedRun::summary_json, or the DEM's line
  bool dem = false;                 // the DEM's line below
  double dem_dt = 0;
  long bonds = 0, broken_bonds = 0;
  double peak_rss = 0; // summed over processes
};

// The JSON text of summary.json. Throughputs over this invocation's own steps (clock.loop_*).
[[nodiscard]] std::string summary_json(const Case& c, const RunCounts& n, const std::string& status, int code,
                                       const std::string& message, const LoopClock& clock);

} // namespace surge::sim
