// One DEM step of a sphere's motion (SPEC §3): Newton–Euler with semi-implicit Euler
// (velocity, then position with the new velocity), the orientation quaternion advanced by
// dq/dt = 1/2 (0, w) q with the new angular velocity and renormalised; Cundall's local
// damping where it is on (each component of the unbalanced force loses a_d |F_k| against
// the motion, F_k - a_d |F_k| sign(v_k), SPEC §3: "useful to settle a pack").
// Written once for one sphere (T = Real: the scalar and CUDA passes) and for a batch
// (T = a vector of Reals: dem_batched.inc), with the same bits in every lane.
#pragma once
#include "surge/core/lanes.hpp"

namespace surge::dem::detail {

template <class T>
struct MotionT {
  Vec3T<T> pos, vel, omega;
  T q[4]; // orientation (w, x, y, z)
};

// Cundall's local damping of f for velocity v.
template <class T>
[[nodiscard]] SURGE_HD SURGE_INLINE Vec3T<T> local_damping(const Vec3T<T>& f, const Vec3T<T>& v, Real ad) {
  Vec3T<T> out = f;
  for (int k = 0; k < 3; ++k) {
    const T mag = pick(f[k] < 0, -f[k], f[k]);
    out[k] -= pick(v[k] > 0, ad * mag, pick(v[k] < 0, -ad * mag, T{}));
  }
  return out;
}

// Advances s by dt under force f and moment m (contacts, fluid and gravity summed).
template <class T>
SURGE_HD SURGE_INLINE void advance(MotionT<T>& s, Vec3T<T> f, Vec3T<T> m, T mass, T inertia, Real ad, Real dt) {
  if (ad > 0) { // the same for every sphere: no per-sphere branches on the signs of v (dynamic runs)
    f = local_damping(f, s.vel, ad);
    m = local_damping(m, s.omega, ad);
  }
  s.vel += f * (dt / mass);
  s.pos += s.vel * splat<T>(dt);
  const Vec3T<T> w = (s.omega += m * (dt / inertia));
  const Real h = dt / 2;
  const T q0 = s.q[0], q1 = s.q[1], q2 = s.q[2], q3 = s.q[3];
  const T n0 = q0 + h * (-w.x * q1 - w.y * q2 - w.z * q3);
  const T n1 = q1 + h * (w.x * q0 + w.y * q3 - w.z * q2);
  const T n2 = q2 + h * (-w.x * q3 + w.y * q0 + w.z * q1);
  const T n3 = q3 + h * (w.x * q2 - w.y * q1 + w.z * q0);
  const T il = 1 / sqrt_of(n0 * n0 + n1 * n1 + n2 * n2 + n3 * n3);
  s.q[0] = n0 * il;
  s.q[1] = n1 * il;
  s.q[2] = n2 * il;
  s.q[3] = n3 * il;
}

} // namespace surge::dem::detail
