// The surge command-line program.
#include "surge/core/error.hpp"
#include "surge/core/version.hpp"
#include "surge/domain/comm.hpp"
#include "surge/io/case_reader.hpp"
#include "surge/io/case_schema.hpp"
#include "surge/par/parallel.hpp"
#include "surge/sim/simulation.hpp"

#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <optional>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

volatile std::sig_atomic_t g_stop = 0;
extern "C" void on_signal(int) { g_stop = 1; }

constexpr const char* usage = R"(surge - SPH-DEM simulator for landslide-generated tsunamis

usage:
  surge run CASE [--out DIR] [--threads N] [--set KEY=VALUE]... [--quiet]
  surge restart DIR [--threads N] [--set KEY=VALUE]... [--quiet]
  surge check CASE [--set KEY=VALUE]...
  surge keys [PREFIX | --markdown]
  surge --version
  surge --help

  run      runs the case; output goes to DIR (default out/<name>)
  restart  continues the run in DIR from its last checkpoint (written with every
           output), with DIR/case.yaml; e.g. --set time.end=10 to run longer
  check    validates the case and prints particle counts, memory, first time
           step, estimated run time and resolution warnings
  keys     lists the case file's keys (those starting with PREFIX, e.g. sph.) with
           their type, default, unit, allowed values and meaning; --markdown
           prints docs/case_reference.md
  --set    overrides any case-file value, e.g. --set dp=0.02 --set time.end=0.5
           (list elements by index: --set fluid.0.box.max=[0.1,0.2,0.3])

exit codes: 0 done, 1 internal error, 2 bad input, 3 run diverged, 130 interrupted
)";

int fail_usage(const std::string& msg) {
  if (surge::domain::comm::rank() == 0)
    std::fprintf(stderr, "error: %s\n(run 'surge --help' for usage)\n", msg.c_str());
  return 2;
}

// The arguments of run, check and restart.
struct CaseCommand {
  std::string case_path, out_dir;
  surge::io::Overrides sets;
  int threads = 0;
  bool quiet = false;
};

// Parses args[1..] of `cmd` into `out`; a usage message when they do not fit.
std::optional<std::string> parse_case_command(const std::string& cmd, const std::vector<std::string>& args,
                                              CaseCommand& out) {
  const bool runs = cmd == "run" || cmd == "restart";
  for (std::size_t i = 1; i < args.size(); ++i) {
    const std::string& a = args[i];
    const std::string* v = i + 1 < args.size() ? &args[i + 1] : nullptr; // the option's value, if any
    if (a == "--set") {
      if (!v) return "--set needs KEY=VALUE";
      out.sets.push_back(*v);
      ++i;
    } else if (a == "--out" && runs) {
      if (!v) return "--out needs a folder";
      out.out_dir = *v;
      ++i;
    } else if (a == "--threads" && runs) {
      char* end = nullptr;
      const long n = v ? std::strtol(v->c_str(), &end, 10) : 0;
      if (!v || *end != '\0' || n < 1 || n > 4096) return "--threads needs a positive integer";
      out.threads = static_cast<int>(n);
      ++i;
    } else if (a == "--quiet" && runs) {
      out.quiet = true;
    } else if (!a.empty() && a[0] == '-') {
      return "unknown option '" + a + "'";
    } else if (out.case_path.empty()) {
      out.case_path = a;
    } else {
      return "more than one case file given";
    }
  }
  if (out.case_path.empty()) return cmd == "restart" ? "no output folder given" : "no case file given";
  if (cmd == "restart") {
    if (!out.out_dir.empty()) return "restart writes into the folder it continues; --out is not allowed";
    out.out_dir = out.case_path;
    out.case_path = out.out_dir + "/case.yaml";
  }
  return std::nullopt;
}

// Runs or checks the case; the exit code (README: 0, 2 bad input, 3 diverged, 130, 1).
int case_command(const std::string& cmd, const CaseCommand& a, bool root) {
  try {
    const surge::Case c = surge::io::read_case(a.case_path, a.sets);
    if (cmd == "check") return root ? surge::sim::check(c) : 0;
    surge::par::set_threads(a.threads);
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    surge::sim::RunOptions opt;
    opt.out_dir = a.out_dir.empty() ? "out/" + c.name : a.out_dir;
    if (std::error_code ec; std::filesystem::exists(opt.out_dir, ec) && !std::filesystem::is_directory(opt.out_dir, ec))
      throw surge::InputError(opt.out_dir, 0, "--out", "exists and is not a folder; name a folder for the output");
    opt.stop = &g_stop;
    opt.progress_tty = isatty(STDERR_FILENO) != 0;
    opt.quiet = a.quiet || !root;
    opt.restart = cmd == "restart";
    return surge::sim::run(c, opt);
  } catch (const surge::InputError& e) {
    // Input is read alike by every process, so every process stops here with the same
    // error: rank 0 says it.
    if (surge::domain::comm::rank() == 0) std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    // Possibly seen by one process only: end them all rather than leave any waiting.
    std::fprintf(stderr, "error (process %d): %s\n", surge::domain::comm::rank(), e.what());
    if (surge::domain::comm::size() > 1) surge::domain::comm::abort(1);
    return 1;
  }
}

// The command, on every process of a distributed run (mpirun -n N surge run ...).
int surge_main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) return fail_usage("no command given");
  const bool root = surge::domain::comm::rank() == 0; // under mpirun, one process speaks
  if (args[0] == "--help" || args[0] == "-h") {
    if (root) std::fputs(usage, stdout);
    return 0;
  }
  if (args[0] == "--version") {
    if (root)
      std::printf("surge %s (%s backend%s)\n", surge::version_string, surge::par::backend_name(),
                  surge::domain::comm::built_with_mpi() ? ", MPI" : "");
    return 0;
  }
  const std::string cmd = args[0];
  if (cmd == "keys") {
    if (args.size() > 2) return fail_usage("keys takes at most one PREFIX or --markdown");
    const std::string a = args.size() == 2 ? args[1] : "";
    const std::string text = a == "--markdown" ? surge::io::case_reference_markdown() : surge::io::keys_text(a);
    if (text.empty()) return fail_usage("no case key starts with '" + a + "'");
    if (root) std::fputs(text.c_str(), stdout);
    return 0;
  }
  if (cmd != "run" && cmd != "check" && cmd != "restart") return fail_usage("unknown command '" + cmd + "'");
  CaseCommand a;
  if (const auto bad = parse_case_command(cmd, args, a)) return fail_usage(*bad);
  return case_command(cmd, a, root);
}

} // namespace

int main(int argc, char** argv) {
  surge::domain::comm::init(argc, argv);
  const int code = surge_main(argc, argv);
  surge::domain::comm::finalize();
  return code;
}
