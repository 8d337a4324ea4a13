// What the physics modules need from a distributed run without knowing MPI: which points
// this process answers for, and how values combine across processes. Empty members mean
// one process (the default), so single-process code pays nothing.
#pragma once
#include "surge/core/types.hpp"

#include <cstddef>
#include <functional>

namespace surge {

struct Distribution {
  // This process answers for the point (a gauge's sample point, local coordinates).
  std::function<bool(const Vec3&)> owns_point;
  // Element-wise sum over processes of arrays in which at most one process holds a
  // non-zero value per element: x + 0 is exact, so the result is bitwise that process's.
  std::function<void(Real*, std::size_t)> sum_exact;
  // Element-wise sum over processes of every process's values, in rank order: the same
  // bits on every process for a given number of processes.
  std::function<void(Real*, std::size_t)> sum_ordered;
  // The minimum over processes (exact in any order).
  std::function<double(double)> min;

  [[nodiscard]] bool distributed() const { return static_cast<bool>(sum_exact); }
  [[nodiscard]] bool owns(const Vec3& x) const { return !owns_point || owns_point(x); }
  void sum(Real* data, std::size_t n) const {
    if (sum_exact) sum_exact(data, n);
  }
  [[nodiscard]] double minimum(double x) const { return min ? min(x) : x; }
};

} // namespace surge
