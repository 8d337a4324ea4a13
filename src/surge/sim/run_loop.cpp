#include "surge/sim/run_loop.hpp"

#include "surge/core/error.hpp"
#include "surge/io/atomic_file.hpp"
#include "surge/io/case_reader.hpp"
#include "surge/sim/run_summary.hpp"
#include "surge/sim/run_support.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace surge::sim {

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
} // namespace

namespace {
// One invocation of the loop: the schedule, the gauge rows and the frames written, and
// the steps that advance them (run_loop below reads as the sequence).
class Loop {
public:
  Loop(const Case& c, const RunOptions& opt, Stepper& s, Clock::time_point wall0)
      : c_(c), opt_(opt), s_(s), out_(opt.out_dir), root_(s.root()), quiet_(opt.quiet || !root_),
        names_(s.gauge_names()), next_out_(c.time.output_every), next_gauge_(c.time.gauge_every),
        wall_checkpoints_(c.time.checkpoint_every_wall), wall0_(wall0), loop0_(Clock::now()), steps0_(s.steps()) {}

  // Continues exactly where the checkpoint was written.
  void restore(const io::Checkpoint& k) {
    t_ = k.time;
    frame_ = k.frame;
    next_out_ = k.next_output;
    next_gauge_ = k.next_gauge;
    // Checkpoints of builds before 2026-11-22 were written before the next output time
    // was advanced: never take a zero-length step on their account.
    while (next_out_ <= t_ + 1e-9 * c_.time.end) next_out_ += c_.time.output_every;
    while (next_gauge_ <= t_ + 1e-9 * c_.time.end) next_gauge_ += c_.time.gauge_every;
    // A restart asked for denser outputs or gauges (--set time.output_every=...) gets them
    // from now, not after the old schedule's next time; the schedule itself (the same
    // bits) is kept wherever it comes first.
    const double slack = 1e-9 * c_.time.end;
    if (t_ + c_.time.output_every < next_out_ - slack) next_out_ = t_ + c_.time.output_every;
    if (t_ + c_.time.gauge_every < next_gauge_ - slack) next_gauge_ = t_ + c_.time.gauge_every;
    frame_times_ = k.frame_times;
    rows_ = k.gauge_rows;
    rows_written_ = rows_.size();
    s_.restored(frame_times_);
    if (!quiet_) std::fprintf(stderr, "restarting at t = %g s (step %ld)\n", t_, s_.steps());
  }

  // The gauges and the first frame at t = 0 (a non-finite start sets `failure`).
  void start(std::string& failure) {
    sample();
    (void)write_output(failure);
  }

  // Steps to the end time, a stop rule or a failure (`failure` set: the run diverged).
  void advance(std::string& failure) {
    const double eps = 1e-9 * c_.time.end;
    last_report_ = loop0_ = Clock::now();
    steps0_ = s_.steps();
    t0_ = t_;
    while (t_ < c_.time.end - eps && failure.empty()) {
      if (stop_) break;
      if (c_.time.max_steps > 0 && s_.steps() >= c_.time.max_steps) break;
      // An end within eps of an output or gauge time is that time, bit for bit: a run
      // stopped there and restarted then steps exactly as the straight run did.
      double end = c_.time.end;
      for (const double x : {next_out_, next_gauge_})
        if (std::fabs(x - c_.time.end) <= eps) end = x;
      const double dt_max = std::min({next_out_, next_gauge_, end}) - t_;
      stop_ = opt_.stop && *opt_.stop;
      // Wall-clock checkpoints are collective (a gather): every process must agree to write one.
      bool checkpoint_due = wall_checkpoints_.due();
      const double dt = s_.step(dt_max, t_, stop_, checkpoint_due, failure);
      t_ += dt;
      if (!failure.empty()) break;
      if (t_ >= next_gauge_ - eps) {
        sample();
        next_gauge_ += c_.time.gauge_every;
      }
      if (t_ >= next_out_ - eps) {
        next_out_ += c_.time.output_every; // before the checkpoint is written: a restart continues from here
        if (!write_output(failure)) break;
      } else if (checkpoint_due) {
        save_progress(); // no frame
      }
      report(dt);
    }
    if (opt_.progress_tty && !quiet_) std::fprintf(stderr, "\n");
  }

  // The exit code: 3 after a failure (the last good output kept), 130 when stopped, else
  // 0; the final state written unless it was just written (the end on an output time).
  int finish(const std::string& failure) {
    if (!failure.empty()) {
      write_summary("diverged", 3, failure);
      if (root_)
        std::fprintf(stderr, "error: %s\n  the last good output (t = %g s) is in %s\n", failure.c_str(),
                     frame_times_.empty() ? 0.0 : frame_times_.back(), out_.string().c_str());
      return 3;
    }
    const bool interrupted = stop_;
    const double eps = 1e-9 * c_.time.end;
    if (interrupted || rows_.size() > rows_written_ || frame_times_.empty() || t_ > frame_times_.back() + eps) {
      std::string last;
      (void)write_output(last);
    }
    const std::string status = interrupted ? "interrupted" : "completed";
    write_summary(status, interrupted ? 130 : 0, interrupted ? "stopped by the user" : "");
    if (!quiet_) s_.report_end(interrupted ? "interrupted" : "done", clock());
    return interrupted ? 130 : 0;
  }

private:
  LoopClock clock() const {
    return LoopClock{t_, s_.steps(), s_.steps() - steps0_, seconds_since(wall0_), seconds_since(loop0_)};
  }
  void write_summary(const std::string& status, int code, const std::string& message) {
    const RunCounts n = s_.counts(); // collective
    if (root_)
      io::write_file_atomic((out_ / "summary.json").string(), summary_json(c_, n, status, code, message, clock()));
  }
  void sample() {
    auto v = s_.sample(t_);
    v.insert(v.begin(), t_);
    rows_.push_back(std::move(v));
  }
  // The gauge rows so far, the checkpoint and the summary: with every output, and between
  // outputs when a wall-clock checkpoint is due.
  void save_progress() {
    if (root_) io::write_file_atomic((out_ / "gauges.csv").string(), csv_text(names_, rows_));
    rows_written_ = rows_.size();
    io::Checkpoint k;
    k.time = t_;
    k.steps = s_.steps();
    k.frame = frame_;
    k.next_output = next_out_;
    k.next_gauge = next_gauge_;
    k.frame_times = frame_times_;
    k.gauge_rows = rows_;
    s_.save(k); // collective in a distributed run (a gather)
    if (root_) io::write_checkpoint((out_ / "checkpoint.bin").string(), k);
    wall_checkpoints_.written();
    write_summary("running", 0, "");
  }
  bool write_output(std::string& failure) {
    if (!s_.write_frame(frame_, t_, failure)) return false; // the last good files stay
    frame_times_.push_back(t_);
    ++frame_;
    save_progress();
    return true;
  }
  // The progress line: on a terminal twice a second, else every opt.report_every_s.
  void report(double dt) {
    const double since = seconds_since(last_report_);
    if (quiet_ || !(opt_.progress_tty ? since > 0.5 : since > opt_.report_every_s)) return;
    last_report_ = Clock::now();
    const double el = seconds_since(loop0_);
    // Rates over this invocation only (a restart starts the clock at its checkpoint).
    const double sps = static_cast<double>(s_.steps() - steps0_) / el;
    const double eta_s = el * (c_.time.end - t_) / std::max(t_ - t0_, 1e-12);
    std::fprintf(stderr, "%st = %.4f / %g s  %5.1f%%  %.1f steps/s  dt %.2e s  ETA %s%s%s",
                 opt_.progress_tty ? "\r" : "", t_, c_.time.end, 100.0 * t_ / c_.time.end, sps, dt, hms(eta_s).c_str(),
                 s_.progress().c_str(), opt_.progress_tty ? "   " : "\n");
  }

  const Case& c_;
  const RunOptions& opt_;
  Stepper& s_;
  const std::filesystem::path out_;
  const bool root_, quiet_;
  const std::vector<std::string> names_;
  double t_ = 0, t0_ = 0;
  int frame_ = 0;
  std::vector<double> frame_times_;
  std::vector<std::vector<double>> rows_;
  std::size_t rows_written_ = 0;
  double next_out_, next_gauge_;
  WallCheckpoints wall_checkpoints_;
  Clock::time_point wall0_, loop0_, last_report_;
  long steps0_;
  bool stop_ = false; // Ctrl-C, agreed by every process
};
} // namespace

void prepare_output(const Case& c, const std::string& out_dir) {
  std::filesystem::create_directories(std::filesystem::path(out_dir) / "particles");
  io::write_file_atomic((std::filesystem::path(out_dir) / "case.yaml").string(), io::to_yaml(c));
}

void check_restart_gauges(const io::Checkpoint& ck, std::size_t gauges, const std::string& path) {
  if (ck.gauge_rows.empty() || ck.gauge_rows.front().size() != gauges + 1)
    throw InputError(path, 0, "gauges",
                     "the checkpoint's gauges differ from the case's; restart with the case.yaml of that run");
}

int run_loop(const Case& c, const RunOptions& opt, Stepper& s, const io::Checkpoint* restart, Clock::time_point wall0) {
  Loop loop(c, opt, s, wall0);
  std::string failure;
  if (restart)
    loop.restore(*restart);
  else
    loop.start(failure);
  loop.advance(failure);
  return loop.finish(failure);
}

} // namespace surge::sim
