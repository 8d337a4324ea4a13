// Wendland C2 kernel, 3D (Wendland 1995; SPEC §2.1). Support 2h.
// W = aD (1 - q/2)^4 (2q + 1), aD = 21 / (16 pi h^3); dW/dr = aD/h (-5q)(1 - q/2)^3.
// (The paper prints aD without the h^3.)
#pragma once
#include "surge/core/types.hpp"

namespace surge::sph {

struct WendlandC2 {
  Real h = 1;
  Real ad = 0; // 21 / (16 pi h^3)
  Real h2_inv = 1;
  Real h_inv = 1;

  SURGE_HD WendlandC2() = default;
  SURGE_HD explicit WendlandC2(Real h_)
      : h(h_), ad(Real(21.0 / (16.0 * 3.14159265358979323846)) / (h_ * h_ * h_)), h2_inv(1 / (h_ * h_)), h_inv(1 / h_) {
  }

  [[nodiscard]] SURGE_HD Real support() const { return 2 * h; }
  // T as for dw_over_r.
  template <class T>
  [[nodiscard]] SURGE_HD SURGE_INLINE T w(T r) const {
    const T q = r * h_inv;
    const T t = 1 - q / 2;
    const T f = ad * t * t * t * t * (2 * q + 1);
    return q >= 2 ? T{} : f;
  }
  // (1/r) dW/dr, so that grad_i W_ij = r_ij * f(r); finite at r -> 0. T is Real, or a
  // SIMD vector of Reals (one r per lane; the pair loop of wcsph_rates_batched.inc).
  template <class T>
  [[nodiscard]] SURGE_HD SURGE_INLINE T dw_over_r(T r) const {
    const T q = r * h_inv;
    const T t = 1 - q / 2;
    const T f = -5 * ad * h2_inv * t * t * t;
    return q >= 2 ? T{} : f;
  }
};

} // namespace surge::sph
