// Cost of a coupled SPH-DEM step against the same water without spheres, and how it
// grows with the number of spheres. A tank 1 x 1 x 0.5 m of water at dp = 10 mm holds
// N loose spheres (r = 15 mm, D = 3 dp, 14 body particles each) on a lattice clear of
// each other; the water inside the spheres is removed.
// usage: bench_coupling N_SPHERES STEPS THREADS
#include "phase_report.hpp"
#include "surge/io/case_reader.hpp"
#include "surge/sim/dem_setup.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>

int main(int argc, char** argv) {
  using namespace surge;
  if (argc < 4) {
    std::fprintf(stderr, "usage: bench_coupling N_SPHERES STEPS THREADS\n");
    return 2;
  }
  const long n_spheres = std::atol(argv[1]);
  const long steps = std::atol(argv[2]);
  par::set_threads(std::atoi(argv[3]));
  const double r = 0.015;
  std::string text = "name: bench_coupling\ndp: 0.01\ntime: {end: 10}\ndomain: {min: [0, 0, 0], max: [1, 1, 0.6]}\n"
                     "fluid:\n  - box: {min: [0, 0, 0], max: [1, 1, 0.5]}\n"
                     "walls:\n  - {name: tank, box: {min: [0, 0, 0], max: [1, 1, 0.6]}, open: [zmax]}\n";
  const std::string csv = "/tmp/bench_coupling_spheres.csv";
  if (n_spheres > 0) {
    // Lattice spacing s with n^2 m >= N in the water (0.04 m clear of the walls).
    const double L = 0.92, H = 0.42;
    double s = std::cbrt(L * L * H / static_cast<double>(n_spheres));
    long n = 0, nz = 0;
    while (true) {
      n = static_cast<long>(std::floor(L / s));
      nz = static_cast<long>(std::floor(H / s));
      if (n * n * nz >= n_spheres) break;
      s *= 0.98;
    }
    if (s < 2.05 * r) {
      std::fprintf(stderr, "too many spheres for the tank\n");
      return 2;
    }
    std::ofstream f(csv);
    long k = 0;
    for (long iz = 0; iz < nz && k < n_spheres; ++iz)
      for (long iy = 0; iy < n && k < n_spheres; ++iy)
        for (long ix = 0; ix < n && k < n_spheres; ++ix, ++k)
          f << 0.04 + (static_cast<double>(ix) + 0.5) * s << ", " << 0.04 + (static_cast<double>(iy) + 0.5) * s << ", "
            << 0.04 + (static_cast<double>(iz) + 0.5) * s << ", " << r << "\n";
    text += "dem:\n  materials: [{name: grain, density: 2500, E: 1.0e6}]\n  packs:\n    - {csv: " + csv +
            ", material: grain}\n";
  }
  const Case c = io::read_case_text(text, "bench_coupling.yaml");
  auto init = sph::build_initial_state(c);
  std::unique_ptr<sim::CoupledParts> cp;
  if (c.coupled()) cp = std::make_unique<sim::CoupledParts>(c, init);
  sph::WcsphSolver solver(sph::solver_config(c), init);
  const std::size_t n_all = init.particles.size();
  auto one_step = [&] {
    const auto s = solver.step(1.0);
    if (cp) cp->coupling->after_fluid_step(solver, *cp->dem, s.dt);
  };
  one_step(); // warm-up
  const auto t0 = std::chrono::steady_clock::now();
  for (long k = 0; k < steps; ++k) one_step();
  par::synchronize();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::string phases = bench::phase_breakdown(std::max(1L, steps / 4), one_step);
  std::printf("{\"bench\": \"coupling\", \"threads\": %d, \"spheres\": %ld, \"body\": %zu, \"fluid\": %zu, "
              "\"particles\": %zu, \"steps\": %ld, \"seconds_per_step\": %.4g, "
              "\"particle_steps_per_s\": %.4g, \"backend\": \"%s\", \"phases_ms_share\": %s}\n",
              par::threads(), n_spheres, cp ? cp->coupling->n_body() : 0, init.n_fluid, n_all, steps,
              wall / static_cast<double>(steps), static_cast<double>(n_all) * static_cast<double>(steps) / wall,
              par::backend_name(), phases.c_str());
  return 0;
}
