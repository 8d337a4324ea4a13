// The per-phase breakdown the benchmarks print: a separate run of `steps` steps with the
// phase timer on (on the GPU it synchronises after every phase, so the throughput figure
// comes from an unprofiled run), reported as milliseconds per step and share of the sum.
#pragma once
#include "surge/par/phase_timer.hpp"

#include <cstdio>
#include <string>

namespace surge::bench {

template <class StepFn>
std::string phase_breakdown(long steps, StepFn&& step) {
  auto& t = par::PhaseTimer::global();
  t.reset();
  t.enable(true);
  for (long k = 0; k < steps; ++k) step();
  t.enable(false);
  double total = 0;
  for (int p = 0; p < static_cast<int>(par::Phase::count); ++p) total += t.seconds(static_cast<par::Phase>(p));
  std::string out = "{";
  for (int p = 0; p < static_cast<int>(par::Phase::count); ++p) {
    const double s = t.seconds(static_cast<par::Phase>(p));
    if (s == 0) continue;
    char buf[128];
    std::snprintf(buf, sizeof buf, "%s\"%s\": [%.4g, %.3f]", out.size() > 1 ? ", " : "",
                  par::phase_name(static_cast<par::Phase>(p)), 1e3 * s / static_cast<double>(steps),
                  total > 0 ? s / total : 0.0);
    out += buf;
  }
  return out + "}";
}

} // namespace surge::bench
