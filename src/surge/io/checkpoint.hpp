// Checkpoints: everything needed to continue a run exactly where it was written.
#pragma once
#include "surge/particles/particle_store.hpp"

#include <string>
#include <vector>

namespace surge::io {

struct Checkpoint {
  double time = 0;
  long steps = 0;
  int frame = 0; // next fluid_NNNN.vtp index
  double next_output = 0, next_gauge = 0;
  std::vector<double> frame_times; // times of the frames written so far
  std::vector<std::vector<double>> gauge_rows;
  long removed_domain = 0, removed_density = 0, non_finite = 0;
  particles::HostParticles particles; // with vel_prev / rho_prev
  std::string dem_state;              // coupled runs: DemSolver::save(), opaque; empty otherwise
  std::string hazard_state;           // sph::HazardMaps::save(), opaque; empty without hazard maps
  std::string body_state;             // sim::MovingBodies::save(): free bodies, opaque; empty without them
};

// Binary, little-endian, written atomically.
void write_checkpoint(const std::string& path, const Checkpoint& c);
// Throws InputError naming the file when it is missing, truncated or not a checkpoint.
Checkpoint read_checkpoint(const std::string& path);

} // namespace surge::io
