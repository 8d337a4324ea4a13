// Formulas written once for one value (T = Real: the scalar and CUDA paths) and for a
// batch of values, one per lane (T = a GCC vector of Reals: the CPU's batched pair loops).
// The arithmetic operators and `m ? a : b` work lane by lane on GCC's vector types; what
// differs between the two is here: the mask type of a comparison (bool, or a vector of
// integers), a square root, a test of whether any lane holds, a select of vectors.
// A formula written with these gives, in every lane, the bits of the scalar formula: the
// same operations in the same order (no fused multiply-adds in either, CMakeLists.txt).
#pragma once
#include "surge/core/types.hpp"

#include <cmath>
#include <type_traits>

namespace surge {

// The result type of comparing two Ts.
template <class T>
using MaskOf = decltype(T{} < T{});

// A T with every lane x.
template <class T>
[[nodiscard]] SURGE_HD SURGE_INLINE T splat(Real x) {
  return T{} + x;
}

// A mask with every lane b.
template <class T>
[[nodiscard]] SURGE_HD SURGE_INLINE MaskOf<T> splat_mask(bool b) {
  if constexpr (std::is_same_v<T, Real>)
    return b;
  else
    return T{} < (b ? T{} + 1 : T{});
}

template <class T>
[[nodiscard]] SURGE_HD SURGE_INLINE T sqrt_of(T x) {
  if constexpr (std::is_same_v<T, Real>) {
    return std::sqrt(x);
  } else {
    T r;
    for (int k = 0; k < static_cast<int>(sizeof(T) / sizeof(Real)); ++k)
      r[k] = std::sqrt(x[k]); // one vector square root (-fno-math-errno)
    return r;
  }
}

template <class T>
[[nodiscard]] SURGE_HD SURGE_INLINE T norm_of(const Vec3T<T>& a) {
  return sqrt_of(dot(a, a));
}

// Masks combined lane by lane (&&, || and ! on one value).
template <class M>
[[nodiscard]] SURGE_HD SURGE_INLINE M both(M a, M b) {
  if constexpr (std::is_same_v<M, bool>)
    return a && b;
  else
    return a & b;
}
template <class M>
[[nodiscard]] SURGE_HD SURGE_INLINE M either(M a, M b) {
  if constexpr (std::is_same_v<M, bool>)
    return a || b;
  else
    return a | b;
}
template <class M>
[[nodiscard]] SURGE_HD SURGE_INLINE M negate(M a) {
  if constexpr (std::is_same_v<M, bool>)
    return !a;
  else
    return ~a;
}

// Whether m holds in some lane: a batch takes a rare branch when any of its lanes does.
template <class M>
[[nodiscard]] SURGE_HD SURGE_INLINE bool any_lane(M m) {
  if constexpr (std::is_same_v<M, bool>) {
    return m;
  } else {
    bool any = false;
    for (int k = 0; k < static_cast<int>(sizeof(M) / sizeof(m[0])); ++k) any = any || m[k] != 0;
    return any;
  }
}

// a where m holds, b elsewhere.
template <class T, class M>
[[nodiscard]] SURGE_HD SURGE_INLINE T pick(M m, T a, T b) {
  return m ? a : b;
}
template <class T, class M>
[[nodiscard]] SURGE_HD SURGE_INLINE Vec3T<T> pick(M m, const Vec3T<T>& a, const Vec3T<T>& b) {
  return {pick(m, a.x, b.x), pick(m, a.y, b.y), pick(m, a.z, b.z)};
}

} // namespace surge
