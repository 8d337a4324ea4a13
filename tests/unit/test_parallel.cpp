// The parallel layer against exact oracles: loops, reductions, the sort, copies, and
// (in the cpu-devcheck build) the trap on host access to execution-space memory.
#include "surge/algo/algo.hpp"
#include "surge/par/parallel.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

using namespace surge;

namespace {

struct Interval {
  int lo, hi;
};
struct Hull {
  SURGE_HD Interval operator()(const Interval& a, const Interval& b) const {
    return {a.lo < b.lo ? a.lo : b.lo, a.hi > b.hi ? a.hi : b.hi};
  }
};

std::vector<int> squares_mod(int n) {
  par::Buffer<int> b(static_cast<std::size_t>(n));
  int* p = b.data();
  par::parallel_for(
      n, SURGE_LAMBDA(int i) { p[i] = (i * 7919) % 1000; });
  return par::download(b);
}

// Loop bodies live in free functions: nvcc's device lambdas may not sit in a test body
// (a private member function).
long long sum_of_indices(int n, long long init = 0) {
  return par::parallel_reduce(
      n, init, SURGE_LAMBDA(int i) { return static_cast<long long>(i); }, par::Sum{});
}
Real min_of_shuffled(int n) {
  return par::parallel_reduce(
      n, Real(1e30), SURGE_LAMBDA(int i) { return static_cast<Real>((i * 37) % n + 3); }, par::Min{});
}
Interval hull_of(int n) {
  return par::parallel_reduce(
      n, Interval{1 << 30, -(1 << 30)},
      SURGE_LAMBDA(int i) {
        return Interval{i - 5, i + 5};
      },
      Hull{});
}
#if defined(SURGE_DEVCHECK)
int sum_buffer(const int* p, int n) {
  return par::parallel_reduce(
      n, 0, SURGE_LAMBDA(int i) { return p[i]; }, par::Sum{});
}
#endif

} // namespace

TEST(Parallel, LoopWritesEveryIndexOnce) {
  for (int n : {1, 255, 256, 257, 100000}) {
    const auto h = squares_mod(n);
    for (int i = 0; i < n; ++i) ASSERT_EQ(h[i], (i * 7919) % 1000) << "n " << n;
  }
}

TEST(Parallel, ReductionsMatchTheirClosedForms) {
  // Sizes below, at and far above one block, and above the cap on blocks (grid stride).
  for (int n : {1, 7, 256, 1000, 300000, 1 << 21}) {
    EXPECT_EQ(sum_of_indices(n), static_cast<long long>(n) * (n - 1) / 2) << "n " << n;
    EXPECT_EQ(min_of_shuffled(n), Real(3)) << "n " << n;
    const Interval hull = hull_of(n);
    EXPECT_EQ(hull.lo, -5);
    EXPECT_EQ(hull.hi, n + 4);
  }
  EXPECT_EQ(sum_of_indices(0, 42), 42);
}

TEST(Parallel, SortIsStableAndMatchesStdStableSort) {
  std::mt19937 rng(3);
  for (int n : {2, 1000, 200000}) {
    for (std::uint32_t max_key : {1U, 63U, 1U << 20, 0xFFFFFFFFU}) {
      std::uniform_int_distribution<std::uint32_t> key(0, max_key);
      std::vector<std::uint32_t> k(static_cast<std::size_t>(n));
      for (auto& x : k) x = key(rng);
      par::Buffer<std::uint32_t> keys, values(static_cast<std::size_t>(n));
      par::upload(keys, k);
      algo::iota(values.data(), n);
      algo::sort_by_key(keys.data(), values.data(), n, max_key);
      std::vector<std::uint32_t> order(static_cast<std::size_t>(n));
      std::iota(order.begin(), order.end(), 0U);
      std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return k[a] < k[b]; });
      const auto got_v = par::download(values);
      const auto got_k = par::download(keys);
      for (int i = 0; i < n; ++i) {
        ASSERT_EQ(got_v[i], order[i]) << "n " << n << " max_key " << max_key << " at " << i;
        ASSERT_EQ(got_k[i], k[order[i]]);
      }
    }
  }
}

TEST(Parallel, DownloadRangeCopiesTheSlice) {
  std::vector<int> h(1000);
  std::iota(h.begin(), h.end(), 0);
  par::Buffer<int> b;
  par::upload(b, h);
  std::vector<int> part;
  par::download_range(part, b, 990, 10);
  ASSERT_EQ(part.size(), 10U);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(part[i], 990 + i);
}

#if defined(SURGE_DEVCHECK)
// The point of the cpu-devcheck build: host code that reads a buffer directly (what
// crashes the CUDA build) dies with a message, and the same read inside a loop works.
TEST(DevcheckDeathTest, HostReadOfABufferDiesWithAMessage) {
  par::Buffer<int> b(100);
  par::fill(b, 5);
  EXPECT_FALSE(par::devcheck::is_open());
  const int* p = b.data();
  EXPECT_DEATH(
      {
        volatile int x = p[3];
        (void)x;
      },
      "surge devcheck: host code touched execution-space memory");
  int* w = b.data();
  EXPECT_DEATH({ w[0] = 1; }, "surge devcheck");
  EXPECT_EQ(par::download(b)[3], 5);
  EXPECT_EQ(sum_buffer(p, 100), 500);
}
#endif
