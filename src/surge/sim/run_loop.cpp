#include "surge/sim/run_loop.hpp"

#include "surge/io/atomic_file.hpp"
#include "surge/sim/run_support.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>

namespace surge::sim {

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
} // namespace

int run_loop(const Case& c, const RunOptions& opt, Stepper& s, const io::Checkpoint* restart, Clock::time_point wall0) {
  namespace fs = std::filesystem;
  const fs::path out(opt.out_dir);
  const bool root = s.root();
  const bool quiet = opt.quiet || !root;
  const std::vector<std::string> names = s.gauge_names();

  double t = 0;
  int frame = 0;
  std::vector<double> frame_times;
  std::vector<std::vector<double>> rows;
  std::size_t rows_written = 0;
  double next_out = c.time.output_every, next_gauge = c.time.gauge_every;
  WallCheckpoints wall_checkpoints(c.time.checkpoint_every_wall);
  auto loop0 = Clock::now();
  long steps0 = s.steps();
  auto clock = [&] { return LoopClock{t, s.steps(), s.steps() - steps0, seconds_since(wall0), seconds_since(loop0)}; };
  auto sample = [&] {
    auto v = s.sample(t);
    v.insert(v.begin(), t);
    rows.push_back(std::move(v));
  };
  // The gauge rows so far, the checkpoint and the summary: with every output, and between
  // outputs when a wall-clock checkpoint is due.
  auto save_progress = [&] {
    if (root) io::write_file_atomic((out / "gauges.csv").string(), csv_text(names, rows));
    rows_written = rows.size();
    io::Checkpoint k;
    k.time = t;
    k.steps = s.steps();
    k.frame = frame;
    k.next_output = next_out;
    k.next_gauge = next_gauge;
    k.frame_times = frame_times;
    k.gauge_rows = rows;
    s.save(k); // collective in a distributed run (a gather)
    if (root) io::write_checkpoint((out / "checkpoint.bin").string(), k);
    wall_checkpoints.written();
    s.write_summary("running", 0, "", clock());
  };
  auto write_output = [&](std::string& failure) {
    if (!s.write_frame(frame, t, failure)) return false; // the last good files stay
    frame_times.push_back(t);
    ++frame;
    save_progress();
    return true;
  };

  std::string failure;
  if (restart) {
    // Continue exactly where the checkpoint was written.
    t = restart->time;
    frame = restart->frame;
    next_out = restart->next_output;
    next_gauge = restart->next_gauge;
    // Checkpoints of builds before 2026-11-22 were written before the next output time
    // was advanced: never take a zero-length step on their account.
    while (next_out <= t + 1e-9 * c.time.end) next_out += c.time.output_every;
    while (next_gauge <= t + 1e-9 * c.time.end) next_gauge += c.time.gauge_every;
    frame_times = restart->frame_times;
    rows = restart->gauge_rows;
    rows_written = rows.size();
    s.restored(frame_times);
    if (!quiet) std::fprintf(stderr, "restarting at t = %g s (step %ld)\n", t, s.steps());
  } else {
    sample();
    (void)write_output(failure); // a non-finite start is caught by the first step
  }

  const double eps = 1e-9 * c.time.end;
  auto last_report = Clock::now();
  loop0 = Clock::now();
  steps0 = s.steps();
  const double t0 = t;
  bool stop = false; // Ctrl-C, agreed by every process
  while (t < c.time.end - eps && failure.empty()) {
    if (stop) break;
    if (c.time.max_steps > 0 && s.steps() >= c.time.max_steps) break;
    const double dt_max = std::min({next_out, next_gauge, c.time.end}) - t;
    stop = opt.stop && *opt.stop;
    // Wall-clock checkpoints are collective (a gather): every process must agree to write one.
    bool checkpoint_due = wall_checkpoints.due();
    const double dt = s.step(dt_max, t, stop, checkpoint_due, failure);
    t += dt;
    if (!failure.empty()) break;
    if (t >= next_gauge - eps) {
      sample();
      next_gauge += c.time.gauge_every;
    }
    if (t >= next_out - eps) {
      next_out += c.time.output_every; // before the checkpoint is written: a restart continues from here
      if (!write_output(failure)) break;
    } else if (checkpoint_due) {
      save_progress(); // no frame
    }
    const double since = seconds_since(last_report);
    if (!quiet && (opt.progress_tty ? since > 0.5 : since > opt.report_every_s)) {
      last_report = Clock::now();
      const double el = seconds_since(loop0);
      // Rates over this invocation only (a restart starts the clock at its checkpoint).
      const double sps = static_cast<double>(s.steps() - steps0) / el;
      const double eta_s = el * (c.time.end - t) / std::max(t - t0, 1e-12);
      std::fprintf(stderr, "%st = %.4f / %g s  %5.1f%%  %.1f steps/s  dt %.2e s  ETA %s%s%s",
                   opt.progress_tty ? "\r" : "", t, c.time.end, 100.0 * t / c.time.end, sps, dt, hms(eta_s).c_str(),
                   s.progress().c_str(), opt.progress_tty ? "   " : "\n");
    }
  }
  if (opt.progress_tty && !quiet) std::fprintf(stderr, "\n");
  if (!failure.empty()) {
    // Outputs written so far are the last good state; nothing after it is written.
    s.write_summary("diverged", 3, failure, clock());
    if (root)
      std::fprintf(stderr,
                   "error: %s\n  the last good output (t = %g s) is in %s; try a smaller sph.cfl or dem.dt_factor, or "
                   "a finer dp\n",
                   failure.c_str(), frame_times.empty() ? 0.0 : frame_times.back(), out.string().c_str());
    return 3;
  }
  const bool interrupted = stop;
  // The final state, unless it was just written (the end on an output time).
  if (interrupted || rows.size() > rows_written || frame_times.empty() || t > frame_times.back() + eps) {
    std::string last;
    (void)write_output(last);
  }
  const std::string status = interrupted ? "interrupted" : "completed";
  s.write_summary(status, interrupted ? 130 : 0, interrupted ? "stopped by the user" : "", clock());
  if (!quiet) s.report_end(interrupted ? "interrupted" : "done", clock());
  return interrupted ? 130 : 0;
}

} // namespace surge::sim
