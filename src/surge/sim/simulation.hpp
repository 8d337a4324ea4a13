// One run of a case: time loop, output schedule, gauges, summary. The only
// place where the solvers meet the output files.
#pragma once
#include "surge/core/case.hpp"

#include <csignal>
#include <string>

namespace surge::sim {

struct RunOptions {
  std::string out_dir;                        // created only after the case is valid
  volatile std::sig_atomic_t* stop = nullptr; // set by Ctrl-C: stop cleanly
  bool progress_tty = false;                  // one updating line instead of periodic lines
  double report_every_s = 10.0;               // plain progress lines every so many seconds
  bool quiet = false;
  bool restart = false; // continue from out_dir/checkpoint.bin
};

// Exit codes: 0 done, 3 diverged, 130 interrupted. A checkpoint (checkpoint.bin)
// is written with every output; with opt.restart the run continues from it.
int run(const Case& c, const RunOptions& opt);

// Prints what `surge check` reports; returns 0.
int check(const Case& c);

// The DEM-only versions (cases with dem.packs and no water), dem_simulation.cpp.
int run_dem(const Case& c, const RunOptions& opt);
int check_dem(const Case& c);

} // namespace surge::sim
