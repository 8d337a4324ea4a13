// Neighbour search throughput: sort + reorder + cell table, then one pass of
// for_each_neighbour counting neighbours, for N random particles at SPH density
// (dp lattice with jitter, radius 2.4 dp).  usage: bench_neighbour N THREADS
#include "surge/neighbour/uniform_grid.hpp"
#include "surge/particles/particle_store.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

using namespace surge;

int main(int argc, char** argv) {
  const long n_req = argc > 1 ? std::atol(argv[1]) : 1000000;
  par::set_threads(argc > 2 ? std::atoi(argv[2]) : 2);
  const int side = static_cast<int>(std::cbrt(static_cast<double>(n_req)));
  const Real dp = 0.01f;
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> jit(-0.2f, 0.2f);
  particles::HostParticles h;
  // Shuffled order, as after many steps without sorting.
  for (int k = 0; k < side; ++k)
    for (int j = 0; j < side; ++j)
      for (int i = 0; i < side; ++i)
        h.push({dp * (static_cast<Real>(i) + 0.5f + jit(rng)), dp * (static_cast<Real>(j) + 0.5f + jit(rng)),
                dp * (static_cast<Real>(k) + 0.5f + jit(rng))},
               Vec3{}, 1000, Kind::Fluid, static_cast<std::uint32_t>(h.size()));
  std::shuffle(h.pos.begin(), h.pos.end(), rng);
  particles::ParticleStore store;
  store.upload(h);
  neighbour::UniformGrid grid;
  const Real r = 2.4f * dp;
  const Real L = dp * static_cast<Real>(side);
  grid.set_spec(neighbour::make_grid({0, 0, 0}, {L, L, L}, r));
  const auto t0 = std::chrono::steady_clock::now();
  store.sort(grid);
  par::synchronize();
  const auto t1 = std::chrono::steady_clock::now();
  store.sort(grid); // already sorted: the per-step cost in a running simulation
  par::synchronize();
  const auto t2 = std::chrono::steady_clock::now();
  auto v = store.view();
  const auto g = grid.view(v.pos);
  Real* out = v.vsig;
  par::parallel_for(
      v.n, SURGE_LAMBDA(int i) {
        int count = 0;
        neighbour::for_each_neighbour(g, v.pos[i], r * r, [&](int, const Vec3&, Real) { ++count; });
        out[i] = static_cast<Real>(count);
      });
  par::synchronize();
  const auto t3 = std::chrono::steady_clock::now();
  const double pairs = par::parallel_reduce(
      v.n, 0.0, SURGE_LAMBDA(int i) { return static_cast<double>(out[i]); }, par::Sum{});
  auto s = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
  std::printf("{\"particles\": %d, \"threads\": %d, \"sort_shuffled_s\": %.4f, \"sort_sorted_s\": %.4f, "
              "\"neighbour_pass_s\": %.4f, \"neighbours_per_particle\": %.1f, \"particles_per_s_search\": %.4g}\n",
              v.n, par::threads(), s(t0, t1), s(t1, t2), s(t2, t3), pairs / v.n, v.n / (s(t1, t2) + s(t2, t3)));
  return 0;
}
