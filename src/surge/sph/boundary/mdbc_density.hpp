// Modified dynamic boundary condition (mDBC; English, Domínguez, Vacondio, Crespo,
// Stansby, Lind, Chiapponi & Gómez-Gesteira 2022, Comp. Part. Mech. 9:1-15).
//
// With plain dynamic boundary particles (SPEC §2.6, the paper's) a wall particle's
// density comes from its own continuity equation, which overestimates it next to the
// water: the wall pushes the fluid about one spacing away (the "gap effect"). mDBC
// instead gives each boundary particle b the density the fluid has at its ghost node
// x_g, b mirrored through the wall surface into the water, extrapolated back to b:
//
//   [rho_g, grad rho_g] = A^-1 [sum_j V_j rho_j W_gj, sum_j V_j rho_j grad W_gj]
//   A = sum_j V_j [[W_gj, (x_j - x_g) W_gj], [grad W_gj, (x_j - x_g) (x) grad W_gj]]
//   rho_b = rho_g + (x_b - x_g) . grad rho_g
//
// a first-order consistent (linear) interpolation over fluid j near x_g. Where A is
// near singular (|det A| < 1e-3: too few fluid neighbours, near the free surface) the
// Shepard average sum V rho W / sum V W is used; with no fluid near the ghost the
// density is left as it is. Boundary densities stay clamped at rho0 (no suction).
#pragma once
#include "surge/sph/wcsph_rates.hpp"

namespace surge::sph {

// Solves the 4x4 system a x = b in place (Gaussian elimination with partial pivoting);
// returns det(a), 0 if singular.
[[nodiscard]] SURGE_HD inline Real solve4(Real a[4][4], Real b[4]) {
  Real det = 1;
  for (int c = 0; c < 4; ++c) {
    int piv = c;
    for (int r = c + 1; r < 4; ++r)
      if ((a[r][c] < 0 ? -a[r][c] : a[r][c]) > (a[piv][c] < 0 ? -a[piv][c] : a[piv][c])) piv = r;
    if (a[piv][c] == 0) return 0;
    if (piv != c) {
      for (int k = 0; k < 4; ++k) {
        const Real t = a[c][k];
        a[c][k] = a[piv][k];
        a[piv][k] = t;
      }
      const Real t = b[c];
      b[c] = b[piv];
      b[piv] = t;
      det = -det;
    }
    det *= a[c][c];
    for (int r = c + 1; r < 4; ++r) {
      const Real f = a[r][c] / a[c][c];
      for (int k = c; k < 4; ++k) a[r][k] -= f * a[c][k];
      b[r] -= f * b[c];
    }
  }
  for (int r = 3; r >= 0; --r) {
    Real s = b[r];
    for (int k = r + 1; k < 4; ++k) s -= a[r][k] * b[k];
    b[r] = s / a[r][r];
  }
  return det;
}

// The sums a ghost node gathers over its fluid neighbours: A and the right-hand side b
// (the header's system). T is Real, or a SIMD vector of Reals (one neighbour per lane: the
// batched CPU pass of wcsph_rates_batched.inc, whose lanes are summed before the solve).
template <class T>
struct GhostSums {
  T a[4][4]{};
  T b[4]{};
};

// Adds the terms of fluid neighbour j: d = x_g - x_j, r = |d|, rho = rho_j, `vol` its
// volume m / rho_j (0 in a batch's unused lanes: every term is then exactly 0).
template <class T>
SURGE_HD SURGE_INLINE void add_ghost_terms(const WcsphParams& prm, const Vec3T<T>& d, T r, T rho, T vol,
                                           GhostSums<T>& s) {
  // grad W_gj (with respect to x_g) = d (1/r) dW/dr
  const T w = prm.kernel.w(r) * vol;
  const Vec3T<T> gw = d * (prm.kernel.dw_over_r(r) * vol);
  const Vec3T<T> dx = d * splat<T>(Real(-1)); // x_j - x_g
  s.a[0][0] += w;
  s.b[0] += rho * w;
  for (int k = 0; k < 3; ++k) {
    s.a[0][k + 1] += dx[k] * w;
    s.a[k + 1][0] += gw[k];
    s.b[k + 1] += rho * gw[k];
    for (int l = 0; l < 3; ++l) s.a[k + 1][l + 1] += dx[l] * gw[k];
  }
}

// The density of the boundary particle at xb from its ghost node's sums; `current` when no
// fluid is near the ghost, the Shepard average where A is near singular.
[[nodiscard]] SURGE_HD inline Real ghost_density(GhostSums<Real>& s, const Vec3& xb, const Vec3& xg, Real current) {
  if (!(s.a[0][0] > 0)) return current;
  const Real shepard = s.b[0] / s.a[0][0];
  const Real det = solve4(s.a, s.b);
  const Real det_abs = det < 0 ? -det : det;
  if (!(det_abs >= Real(1e-3))) return shepard;
  const Vec3 grad{s.b[1], s.b[2], s.b[3]};
  return s.b[0] + dot(xb - xg, grad);
}

// The mDBC density of the boundary particle at xb with ghost node xg, one neighbour at a
// time (the CUDA and scalar paths); `current` when no fluid is near the ghost.
[[nodiscard]] SURGE_HD inline Real mdbc_density(const WcsphParams& prm, const neighbour::GridView& g,
                                                const particles::ParticleView& p, const Vec3& xb, const Vec3& xg,
                                                Real current) {
  const Real r2max = prm.kernel.support() * prm.kernel.support();
  GhostSums<Real> s;
  neighbour::for_each_fluid_neighbour(g, xg, r2max, [&](int j, const Vec3& d, Real r2) {
    add_ghost_terms(prm, d, std::sqrt(r2), p.rho[j], prm.mass / p.rho[j], s);
  });
  return ghost_density(s, xb, xg, current);
}

} // namespace surge::sph
