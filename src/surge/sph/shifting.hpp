// Particle shifting (SPEC §8: Lind et al. 2012, the Fickian form DualSPHysics uses, Mokos
// et al. 2017) and the free-surface detection it needs:
//   grad C_i = sum_j V_j grad_i W_ij            (the concentration's gradient, V_j = m/rho_j)
//   div r_i  = -sum_j V_j r_ij . grad_i W_ij    (3 inside the water in 3D, less near a free surface)
//   dr_i     = -A h |u_i| dt f_i grad C_i,  f_i = clamp((div r_i - s) / (3 - s), 0, 1)
// over every neighbour, wall and body particles included: a wall's particles fill the
// concentration on their side, so water next to a wall is not shifted into it. Applied to
// fluid only, after the position update; velocities are not shifted.
// The free surface (div r < s, `surface`): SPEC §8 keeps the tangential part of the shift
// there, with n = -grad C / |grad C|; but that part of grad C is zero by construction, so the
// projection removes the whole shift at the surface and leaves it whole a particle below,
// where grad C, truncated by the surface, pulls water outwards. The factor f (DualSPHysics
// 4's free-surface treatment) brings the shift to zero across the layer where div r drops
// from 3 to s instead: no outward drift of the surface, and the bulk shifted fully.
#pragma once
#include "surge/core/lanes.hpp"

namespace surge::sph {

struct ShiftParams {
  Real coefficient = 0;      // A (sph.shifting_coefficient); 0: no shifting (sph.shifting: none)
  Real surface = Real(2.75); // div r below which a particle is at the free surface (sph.free_surface)
  // delta_plus (Sun et al. 2017): the speed in D in place of |u_i| (Ma c0), and the
  // anti-clumping weight 1 + R (W_ij / W(dp))^4 of each pair's term; speed 0: fickian.
  Real speed = 0;
  Real clump = 0;    // R (0.2)
  Real inv_w_dp = 0; // 1 / W(dp)
  [[nodiscard]] SURGE_HD bool on() const { return coefficient > 0; }
};

// What a particle's pairs give its shift.
struct ShiftSums {
  Vec3 grad_c{};
  Real div_r = 0;
};

// The terms of the pair (i, j): rij = x_i - x_j, grad = grad_i W_ij, vol = V_j, w = W_ij.
template <class T>
SURGE_HD SURGE_INLINE void add_shift_terms(const ShiftParams& s, const Vec3T<T>& rij, const Vec3T<T>& grad, T vol, T w,
                                           Vec3T<T>& grad_c, T& div_r) {
  div_r -= vol * dot(rij, grad);
  if (s.clump > 0) {
    const T q = w * s.inv_w_dp;
    const T q2 = q * q;
    vol = vol * (1 + s.clump * q2 * q2);
  }
  grad_c += grad * vol;
}

// Whether a particle with these sums lies at the free surface (the `surface` output).
[[nodiscard]] SURGE_HD inline bool at_surface(const ShiftParams& s, Real div_r) { return div_r < s.surface; }

// The shift of a fluid particle moving at u over dt (h the smoothing length).
[[nodiscard]] SURGE_HD inline Vec3 shift_displacement(const ShiftParams& s, const ShiftSums& g, const Vec3& u, Real h,
                                                      Real dt) {
  Real f = (g.div_r - s.surface) / (3 - s.surface);
  f = f < 0 ? Real(0) : (f > 1 ? Real(1) : f);
  const Real speed = s.speed > 0 ? s.speed : std::sqrt(dot(u, u));
  return g.grad_c * (-s.coefficient * h * speed * dt * f);
}

} // namespace surge::sph
