// Where a step's time goes, per phase, for the benchmarks. Off by default (then a scope
// costs nothing and synchronises nothing). When on, the CUDA build brackets each phase
// with two CUDA events and waits for the second, so asynchronous kernels are charged to
// the phase that launched them; the CPU build's loops are synchronous and use a clock.
#pragma once
#include "surge/par/parallel.hpp"

#include <array>
#include <chrono>

namespace surge::par {

enum class Phase {
  Sort,
  Boundary,
  Rates,
  TimeStep,
  Integrate,
  Removal,
  Coupling,
  DemSort,
  DemContacts,
  DemIntegrate,
  count
};
inline const char* phase_name(Phase p) {
  constexpr std::array<const char*, static_cast<int>(Phase::count)> names = {
      "sort",    "mdbc_boundary", "rates",    "dt_reduction", "integrate",
      "removal", "coupling",      "dem_sort", "dem_contacts", "dem_integrate"};
  return names[static_cast<std::size_t>(p)];
}

class PhaseTimer {
public:
  // One timer for the process: the solvers time themselves, a benchmark reads the sums.
  static PhaseTimer& global() {
    static PhaseTimer t;
    return t;
  }
  void enable(bool on) { on_ = on; }
  [[nodiscard]] bool enabled() const { return on_; }
  void reset() { seconds_.fill(0); }
  [[nodiscard]] double seconds(Phase p) const { return seconds_[static_cast<std::size_t>(p)]; }

  // Times its own lifetime as phase p (nested scopes are each charged in full).
  class Scope {
  public:
    Scope(PhaseTimer& t, Phase p) : t_(t.on_ ? &t : nullptr), p_(p) {
      if (t_) t_->begin();
    }
    ~Scope() {
      if (t_) t_->seconds_[static_cast<std::size_t>(p_)] += t_->end();
    }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

  private:
    PhaseTimer* t_;
    Phase p_;
  };

private:
#if defined(SURGE_BACKEND_CUDA)
  void begin() {
    if (!start_) {
      check_cuda(cudaEventCreate(&start_), "cudaEventCreate");
      check_cuda(cudaEventCreate(&stop_), "cudaEventCreate");
    }
    check_cuda(cudaEventRecord(start_), "cudaEventRecord");
  }
  double end() {
    check_cuda(cudaEventRecord(stop_), "cudaEventRecord");
    check_cuda(cudaEventSynchronize(stop_), "cudaEventSynchronize");
    float ms = 0;
    check_cuda(cudaEventElapsedTime(&ms, start_, stop_), "cudaEventElapsedTime");
    return 1e-3 * static_cast<double>(ms);
  }
  cudaEvent_t start_ = nullptr, stop_ = nullptr;
#else
  void begin() { t0_ = std::chrono::steady_clock::now(); }
  double end() { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count(); }
  std::chrono::steady_clock::time_point t0_;
#endif
  bool on_ = false;
  std::array<double, static_cast<std::size_t>(Phase::count)> seconds_{};
};

// const auto t = par::timed(par::Phase::Sort); at the top of a phase's block.
[[nodiscard]] inline PhaseTimer::Scope timed(Phase p) { return {PhaseTimer::global(), p}; }

} // namespace surge::par
