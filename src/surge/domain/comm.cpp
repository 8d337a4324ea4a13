#include "surge/domain/comm.hpp"

#include <chrono>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <type_traits>

#if defined(SURGE_MPI)
#include <mpi.h>
#endif

namespace surge::domain::comm {

namespace {
double g_collective_seconds = 0;
// Adds the lifetime of the scope to g_collective_seconds.
struct CollectiveTimer {
  std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
  CollectiveTimer() = default;
  CollectiveTimer(const CollectiveTimer&) = delete;
  CollectiveTimer& operator=(const CollectiveTimer&) = delete;
  ~CollectiveTimer() {
    g_collective_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
};
} // namespace

double collective_seconds() { return g_collective_seconds; }

#if defined(SURGE_MPI)
namespace {
void check(int err, const char* what) {
  if (err != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + what + " failed");
}
MPI_Datatype real_type() { return std::is_same_v<Real, float> ? MPI_FLOAT : MPI_DOUBLE; }
template <class T>
void allreduce(T* x, std::size_t n, MPI_Datatype type, MPI_Op op) {
  if (size() == 1 || n == 0) return;
  const CollectiveTimer timer;
  check(MPI_Allreduce(MPI_IN_PLACE, x, static_cast<int>(n), type, op, MPI_COMM_WORLD), "allreduce");
}
} // namespace

void init(int& argc, char**& argv) {
  int provided = 0;
  // Only the main thread calls MPI (OpenMP threads never do).
  check(MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided), "init");
}
void finalize() { MPI_Finalize(); }
bool built_with_mpi() { return true; }
int rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}
int size() {
  int s = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &s);
  return s;
}
void abort(int code) {
  MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}
void sum(double* x, std::size_t n) { allreduce(x, n, MPI_DOUBLE, MPI_SUM); }
void sum(Real* x, std::size_t n) { allreduce(x, n, real_type(), MPI_SUM); }
void min(double* x, std::size_t n) { allreduce(x, n, MPI_DOUBLE, MPI_MIN); }
void max(double* x, std::size_t n) { allreduce(x, n, MPI_DOUBLE, MPI_MAX); }

void sum_in_rank_order(Real* x, std::size_t n) {
  const int p = size();
  if (p == 1 || n == 0) return;
  const CollectiveTimer timer;
  std::vector<Real> all(n * static_cast<std::size_t>(p));
  check(
      MPI_Allgather(x, static_cast<int>(n), real_type(), all.data(), static_cast<int>(n), real_type(), MPI_COMM_WORLD),
      "allgather");
  for (std::size_t k = 0; k < n; ++k) {
    Real s = all[k];
    for (int r = 1; r < p; ++r) s += all[static_cast<std::size_t>(r) * n + k];
    x[k] = s;
  }
}

std::vector<std::vector<char>> all_to_all(const std::vector<std::vector<char>>& send) {
  const CollectiveTimer timer;
  const int p = size();
  std::vector<int> scount(p), rcount(p), sdisp(p), rdisp(p);
  std::vector<char> sbuf;
  for (int r = 0; r < p; ++r) {
    scount[r] = static_cast<int>(send[r].size());
    sdisp[r] = static_cast<int>(sbuf.size());
    sbuf.insert(sbuf.end(), send[r].begin(), send[r].end());
  }
  check(MPI_Alltoall(scount.data(), 1, MPI_INT, rcount.data(), 1, MPI_INT, MPI_COMM_WORLD), "alltoall");
  long total = 0;
  for (int r = 0; r < p; ++r) {
    rdisp[r] = static_cast<int>(total);
    total += rcount[r];
  }
  std::vector<char> rbuf(static_cast<std::size_t>(total));
  check(MPI_Alltoallv(sbuf.data(), scount.data(), sdisp.data(), MPI_CHAR, rbuf.data(), rcount.data(), rdisp.data(),
                      MPI_CHAR, MPI_COMM_WORLD),
        "alltoallv");
  std::vector<std::vector<char>> out(p);
  for (int r = 0; r < p; ++r) out[r].assign(rbuf.begin() + rdisp[r], rbuf.begin() + rdisp[r] + rcount[r]);
  return out;
}

std::vector<char> gather(const std::vector<char>& mine) {
  const int p = size();
  int n = static_cast<int>(mine.size());
  std::vector<int> counts(p), disp(p);
  check(MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD), "gather");
  long total = 0;
  for (int r = 0; r < p; ++r) {
    disp[r] = static_cast<int>(total);
    total += counts[r];
  }
  std::vector<char> out(rank() == 0 ? static_cast<std::size_t>(total) : 0);
  check(MPI_Gatherv(mine.data(), n, MPI_CHAR, out.data(), counts.data(), disp.data(), MPI_CHAR, 0, MPI_COMM_WORLD),
        "gatherv");
  return out;
}
#else
void init(int&, char**&) {}
void finalize() {}
bool built_with_mpi() { return false; }
int rank() { return 0; }
int size() { return 1; }
void abort(int code) { std::exit(code); }
void sum(double*, std::size_t) {}
void sum(Real*, std::size_t) {}
void min(double*, std::size_t) {}
void max(double*, std::size_t) {}
void sum_in_rank_order(Real*, std::size_t) {}
std::vector<std::vector<char>> all_to_all(const std::vector<std::vector<char>>& send) { return send; }
std::vector<char> gather(const std::vector<char>& mine) { return mine; }
#endif

double min(double x) {
  min(&x, 1);
  return x;
}
double max(double x) {
  max(&x, 1);
  return x;
}
double sum(double x) {
  sum(&x, 1);
  return x;
}

} // namespace surge::domain::comm
