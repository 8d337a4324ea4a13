// Memory bandwidth of this machine, STREAM's triad a[i] = b[i] + s c[i] on arrays far
// larger than the caches (3 x 128 MiB of double), best of 10: the figure beside which
// SPH throughput compares across machines (SPH steps are bound by memory traffic).
// usage: bench_stream THREADS
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

int main(int argc, char** argv) {
  const int threads = argc > 1 ? std::atoi(argv[1]) : 1;
  omp_set_num_threads(threads);
  const long n = 1L << 24;
  std::vector<double> a(static_cast<std::size_t>(n)), b(static_cast<std::size_t>(n)), c(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    a[i] = 0;
    b[i] = 1;
    c[i] = 2;
  }
  double best = 1e30;
  const double s = 3.0;
  for (int rep = 0; rep < 10; ++rep) {
    const auto t0 = std::chrono::steady_clock::now();
#pragma omp parallel for schedule(static)
    for (long i = 0; i < n; ++i) a[i] = b[i] + s * c[i];
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  const double bytes = 3.0 * 8.0 * static_cast<double>(n); // read b, c; write a (no write-allocate counted)
  std::printf("{\"bench\": \"stream_triad\", \"threads\": %d, \"gb_per_s\": %.2f, \"check\": %.1f}\n", threads,
              bytes / best / 1e9, a[static_cast<std::size_t>(n / 2)]);
  return 0;
}
