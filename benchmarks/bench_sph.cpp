// SPH throughput: runs a case for a fixed number of steps and reports fluid and
// all-particle steps per second, bytes per particle (solver buffers, and peak RSS /
// particles), then the time per phase (ms per step, share) from a shorter profiled run.
// usage: bench_sph CASE STEPS THREADS [--set KEY=VALUE]...
#include "phase_report.hpp"
#include "surge/io/case_reader.hpp"
#include "surge/sph/wcsph_solver.hpp"
#if defined(SURGE_SIMD)
#include "surge/sph/wcsph_rates_simd.hpp"
#endif

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <sys/resource.h>
#include <utility>

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: bench_sph CASE STEPS THREADS [--set KEY=VALUE]...\n");
    return 2;
  }
  surge::io::Overrides sets;
  for (int i = 4; i + 1 < argc; i += 2) sets.emplace_back(argv[i + 1]);
  const surge::Case c = surge::io::read_case(argv[1], sets);
  const long steps = std::atol(argv[2]);
  surge::par::set_threads(std::atoi(argv[3]));
  std::size_t n_fluid = 0, n_all = 0;
  std::unique_ptr<surge::sph::WcsphSolver> solver;
  {
    auto init = surge::sph::build_initial_state(c);
    n_fluid = init.n_fluid;
    n_all = init.particles.size();
    solver = std::make_unique<surge::sph::WcsphSolver>(surge::sph::solver_config(c), std::move(init));
  }
  solver->step(1.0); // warm-up: first sort of an unsorted set, page faults
  const auto t0 = std::chrono::steady_clock::now();
  for (long k = 0; k < steps; ++k) solver->step(1.0);
  surge::par::synchronize();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::string phases = surge::bench::phase_breakdown(std::max(1L, steps / 4), [&] { solver->step(1.0); });
#if defined(SURGE_SIMD)
  const char* pair_loop = surge::sph::batched_rates_name(); // avx2, sse2 or off (the scalar loop)
#else
  const char* pair_loop = "scalar";
#endif
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  const double rss = static_cast<double>(u.ru_maxrss) * 1024.0;
  std::printf("{\"case\": \"%s\", \"threads\": %d, \"steps\": %ld, \"fluid\": %zu, \"particles\": %zu, "
              "\"fluid_steps_per_s\": %.4g, \"particle_steps_per_s\": %.4g, "
              "\"solver_bytes_per_particle\": %.1f, \"rss_bytes_per_particle\": %.1f, \"seconds\": %.3f, \"backend\": "
              "\"%s\", \"pair_loop\": \"%s\", \"phases_ms_share\": %s}\n",
              c.name.c_str(), surge::par::threads(), steps, n_fluid, n_all,
              static_cast<double>(n_fluid) * static_cast<double>(steps) / wall,
              static_cast<double>(n_all) * static_cast<double>(steps) / wall,
              static_cast<double>(solver->bytes()) / static_cast<double>(n_all), rss / static_cast<double>(n_all), wall,
              surge::par::backend_name(), pair_loop, phases.c_str());
  return 0;
}
