// The one time loop of every run (water only, coupled, DEM only, distributed): the
// output and gauge schedule, gauges.csv, checkpoints (with every output and by wall
// clock), the stop rules (end time, time.max_steps, Ctrl-C, divergence), the restart's
// bookkeeping, the progress line and the summary's status. What is stepped, sampled and
// written belongs to a Stepper (simulation.cpp: water and spheres; dem_simulation.cpp:
// spheres only).
#pragma once
#include "surge/core/case.hpp"
#include "surge/io/checkpoint.hpp"
#include "surge/sim/simulation.hpp"

#include <chrono>
#include <string>
#include <vector>

namespace surge::sim {

struct RunCounts;

// Where the loop stands, for the summary and the progress line.
struct LoopClock {
  double t = 0;
  long steps = 0;       // of the whole run (a restart continues the count)
  long loop_steps = 0;  // of this invocation's loop
  double wall = 0;      // seconds since the program started the run
  double loop_wall = 0; // seconds since this invocation's loop started (set-up and first output excluded)
};

class Stepper {
public:
  virtual ~Stepper() = default;
  // One step of at most dt_max (a fixed-step model may overshoot: its outputs fall on the
  // first step at or after their time). `stop` (Ctrl-C) and `checkpoint_due` come in as
  // this process sees them and leave as every process agrees. Returns the step taken;
  // `failure` says why the run diverged (empty if it did not).
  virtual double step(double dt_max, double t, bool& stop, bool& checkpoint_due, std::string& failure) = 0;
  [[nodiscard]] virtual long steps() const = 0;
  [[nodiscard]] virtual std::vector<std::string> gauge_names() const = 0;
  // The gauge values now (without the time), in gauge_names' order.
  virtual std::vector<double> sample(double t) = 0;
  // Writes output frame `frame` at time t; false (nothing written, `failure` set) when the
  // state is not finite.
  virtual bool write_frame(int frame, double t, std::string& failure) = 0;
  // Adds the model's state to a checkpoint (particles, spheres, removal counts).
  virtual void save(io::Checkpoint& k) = 0;
  // A restart: the times of the frames already written, for the .pvd collections.
  virtual void restored(const std::vector<double>& frame_times) = 0;
  // What summary.json says of the run (sim/run_summary.hpp). Collective in a distributed
  // run (every process takes part; rank 0's counts are written).
  virtual RunCounts counts() = 0;
  // Appended to the progress line (after time, percent, steps/s, dt and ETA).
  [[nodiscard]] virtual std::string progress() const { return ""; }
  // The last line printed ("done: ...").
  virtual void report_end(const std::string& status, const LoopClock& clock) = 0;
  // The process that writes the files and prints (rank 0 of a distributed run).
  [[nodiscard]] virtual bool root() const { return true; }
};

// A run's output folder, once every input check has passed: particles/ and case.yaml
// (the case as read, every default written out).
void prepare_output(const Case& c, const std::string& out_dir);
// What every restart checks whatever the model: the checkpoint's gauges are the case's
// (`path`: the checkpoint, for the message).
void check_restart_gauges(const io::Checkpoint& ck, std::size_t gauges, const std::string& path);

// Runs the case with `s` from t = 0, or from the checkpoint `restart` (the model's own
// state already restored from it by the stepper); returns the exit code (0, 3, 130).
int run_loop(const Case& c, const RunOptions& opt, Stepper& s, const io::Checkpoint* restart,
             std::chrono::steady_clock::time_point wall0);

} // namespace surge::sim
