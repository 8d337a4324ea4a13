// DEM throughput: spheres of r = 0.03 m touching on a cubic lattice with small jitter,
// settling under gravity on a floor, dt = 1e-5 s. MODEL full (the default): the linear
// spring with shear history, rolling and twisting resistance, bonds enabled and intact;
// hooke: the linear spring with shear history only (LAMMPS's gran/hooke/history);
// hertz_mindlin: Hertz-Mindlin with shear history only (LAMMPS's pair granular
// hertz/material ... tangential mindlin). Reports sphere-steps per second, contacts per
// sphere, ns per contact per core and bytes per sphere.
// usage: bench_dem N_SPHERES STEPS THREADS [full|hooke|hertz_mindlin]
#include "phase_report.hpp"
#include "surge/dem/dem_solver.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <sys/resource.h>

using namespace surge;

int main(int argc, char** argv) {
  const long n_req = argc > 1 ? std::atol(argv[1]) : 20000;
  const long steps = argc > 2 ? std::atol(argv[2]) : 2000;
  par::set_threads(argc > 3 ? std::atoi(argv[3]) : 2);
  const std::string model = argc > 4 ? argv[4] : "full";
  if (model != "full" && model != "hooke" && model != "hertz_mindlin") {
    std::fprintf(stderr, "MODEL must be full, hooke or hertz_mindlin\n");
    return 2;
  }
  const bool full = model == "full";
  const Real r = 0.03f;
  const int nx = static_cast<int>(std::cbrt(static_cast<double>(n_req) / 2)) * 2, ny = nx / 2;
  const int nz = static_cast<int>(n_req / (static_cast<long>(nx) * ny));
  dem::Material m;
  if (full) {
    m.k_roll = 0.5f;
    m.k_roll_max = 0.05f;
    m.k_twist = 0.5f;
    m.k_twist_max = 0.05f;
    m.bonded = true;
    m.bond_cn = 1e9f; // strong enough to stay intact
    m.bond_cs = 1e9f;
  }
  const Real L = 2 * r * static_cast<Real>(nx), W = 2 * r * static_cast<Real>(ny), H = 2 * r * static_cast<Real>(nz);
  dem::DemSolver s({m}, {{{0, 0, 0}, {0, 0, 1}, 0}}, Vec3{0, 0, -9.81f}, Vec3{-r, -r, -r}, Vec3{L + r, W + r, H + r},
                   model == "hertz_mindlin" ? dem::contact_law_index("hertz_mindlin") : 0);
  std::vector<dem::Sphere> sp;
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> jit(-0.002f, 0.002f);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        sp.push_back({{r * (2 * static_cast<Real>(i) + 1) + jit(rng) * r,
                       r * (2 * static_cast<Real>(j) + 1) + jit(rng) * r, r * (2 * static_cast<Real>(k) + 1)},
                      {},
                      {},
                      r * (1 + jit(rng)),
                      0});
  s.set_spheres(sp);
  const long bonds = full ? s.bond_touching(0.01f * r) : 0;
  const Real dt = 1e-5f;
  s.step(dt);
  const auto t0 = std::chrono::steady_clock::now();
  for (long k = 0; k < steps; ++k) s.step(dt);
  par::synchronize();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::string phases = bench::phase_breakdown(std::max(1L, steps / 4), [&] { s.step(dt); });
  double contacts = 0;
  for (auto c : s.contact_counts()) contacts += c;
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  const double n = static_cast<double>(sp.size());
  const double sps = n * static_cast<double>(steps) / wall;
  std::printf("{\"model\": \"%s\", \"spheres\": %zu, \"threads\": %d, \"steps\": %ld, \"bonds\": %ld, "
              "\"sphere_steps_per_s\": %.4g, "
              "\"contacts_per_sphere\": %.2f, \"ns_per_contact_per_core\": %.1f, \"bytes_per_sphere\": %.0f, "
              "\"seconds\": %.2f, \"backend\": \"%s\", \"phases_ms_share\": %s}\n",
              model.c_str(), sp.size(), par::threads(), steps, bonds, sps, contacts / n,
              1e9 * wall * par::threads() / (static_cast<double>(steps) * contacts),
              static_cast<double>(u.ru_maxrss) * 1024.0 / n, wall, par::backend_name(), phases.c_str());
  return 0;
}
