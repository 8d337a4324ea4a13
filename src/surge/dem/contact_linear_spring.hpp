// Linear spring-dashpot contact law of the paper's DEM (SPEC §3), as host/device
// value types, and `LinearSpring`, the law the DEM solver runs by default
// (`dem.contact: linear_spring`; contact_law.hpp says what a law provides).
//
// normal:   F_n = k_n u_n + c_n du_n/dt along n, 1/k_n = 1/(E_A r_A) + 1/(E_B r_B),
//           c_n = 2 beta sqrt(m* k_n), beta = -ln e / sqrt(pi^2 + ln^2 e);
//           an unbonded contact never pulls: F_n < 0 is clipped to 0.
// shear:    incremental, F_s <- R(F_s) - k_s du_s, |F_s| <= |F_n| tan(phi) (+ C_s r'^2 bonded),
//           1/k_s = 1/(E_A nu_A r_A) + 1/(E_B nu_B r_B)
// rolling / twisting: M = K theta, K = k_{r/t} r'^2 k_s, |M| <= k^max |F_n| r', at the
//           cap theta is reset so that K theta = M_max.
#pragma once
#include "surge/core/lanes.hpp"
#include "surge/dem/material.hpp"

#include <cmath>

namespace surge::dem {

inline constexpr double pi = 3.14159265358979323846;

// Series stiffness of two springs of stiffness a and b.
[[nodiscard]] SURGE_HD inline Real series(Real a, Real b) { return 1 / (1 / a + 1 / b); }

// k_n from the two-spring formula.
[[nodiscard]] SURGE_HD inline Real normal_stiffness(Real e_a, Real r_a, Real e_b, Real r_b) {
  return series(e_a * r_a, e_b * r_b);
}
// k_s from the two-spring formula (nu: shear-to-normal stiffness ratio).
[[nodiscard]] SURGE_HD inline Real shear_stiffness(Real e_a, Real nu_a, Real r_a, Real e_b, Real nu_b, Real r_b) {
  return series(e_a * nu_a * r_a, e_b * nu_b * r_b);
}
// Damping ratio that gives restitution e for the unclipped linear oscillator.
[[nodiscard]] SURGE_HD inline Real damping_ratio(Real e) {
  if (e >= 1) return 0;
  const Real l = std::log(e);
  return -l / std::sqrt(Real(pi * pi) + l * l);
}

struct NormalSpringDashpot {
  Real kn = 0; // stiffness [N/m]
  Real cn = 0; // damping [N s/m]

  SURGE_HD NormalSpringDashpot() = default;
  SURGE_HD NormalSpringDashpot(Real kn_, Real mstar, Real restitution)
      : NormalSpringDashpot(with_ratio(kn_, mstar, damping_ratio(restitution))) {}
  // From the damping ratio beta = damping_ratio(e) itself: a solver computes it once per
  // material, not a logarithm per contact and step.
  [[nodiscard]] SURGE_HD static NormalSpringDashpot with_ratio(Real kn_, Real mstar, Real beta) {
    NormalSpringDashpot law;
    law.kn = kn_;
    law.cn = 2 * beta * std::sqrt(mstar * kn_);
    return law;
  }

  // Normal force along n (positive pushes apart) for overlap un and overlap rate dun
  // (dun > 0 while approaching). Unbonded contacts are clipped at zero.
  [[nodiscard]] SURGE_HD Real force(Real un, Real dun, bool bonded) const { return force_of(kn, cn, un, dun, bonded); }
  // The same for one contact or a batch of them (core/lanes.hpp).
  template <class T, class M>
  [[nodiscard]] SURGE_HD SURGE_INLINE static T force_of(T kn, T cn, T un, T dun, M bonded) {
    const T f = kn * un + cn * dun;
    return pick(both(negate(bonded), f < 0), T{}, f);
  }
};

// The shear, rolling and twisting springs below are written once for one contact
// (T = Real) and for a batch (T = a vector of Reals, core/lanes.hpp): their branches are
// selects, lane by lane, with the scalar path's bits.

// Removes from v its component along the unit normal n.
template <class T>
[[nodiscard]] SURGE_HD SURGE_INLINE Vec3T<T> tangential(const Vec3T<T>& v, const Vec3T<T>& n) {
  return v - n * dot(v, n);
}

// Stored shear force rotated into the tangent plane of the new normal, keeping its magnitude.
template <class T>
[[nodiscard]] SURGE_HD SURGE_INLINE Vec3T<T> rotate_into_plane(const Vec3T<T>& fs, const Vec3T<T>& n) {
  const Vec3T<T> t = tangential(fs, n);
  const T lt = norm_of(t), lf = norm_of(fs);
  return pick(lt > 0, t * (lf / lt), Vec3T<T>{});
}

// Scales v back to length at most cap (Coulomb limit, rolling cap).
template <class T>
[[nodiscard]] SURGE_HD SURGE_INLINE Vec3T<T> cap_length(const Vec3T<T>& v, T cap) {
  const T l = norm_of(v);
  return pick(both(l > cap, l > 0), v * (cap / l), v);
}

// Incremental shear spring: previous force (any orientation), new normal n, tangential
// relative displacement of the contact point du over the step, Coulomb limit.
// Returns the new shear force and whether the contact slipped.
template <class T>
struct ShearUpdateT {
  Vec3T<T> force;
  MaskOf<T> slipped;
};
using ShearUpdate = ShearUpdateT<Real>;
template <class T>
[[nodiscard]] SURGE_HD SURGE_INLINE ShearUpdateT<T> shear_force(const Vec3T<T>& fs_old, const Vec3T<T>& n,
                                                                const Vec3T<T>& du, T ks, T limit) {
  const Vec3T<T> trial = rotate_into_plane(fs_old, n) - tangential(du, n) * ks;
  const MaskOf<T> slipped = norm_of(trial) > limit;
  return {pick(slipped, cap_length(trial, limit), trial), slipped};
}

// Rolling or twisting spring with a cap: theta accumulates the relative rotation;
// the moment is K theta capped at m_max, and theta is reset to m_max / K at the cap.
template <class T>
struct ResistanceUpdateT {
  Vec3T<T> theta;
  Vec3T<T> moment;
};
template <class T>
[[nodiscard]] SURGE_HD SURGE_INLINE ResistanceUpdateT<T> resistance_moment(const Vec3T<T>& theta_old,
                                                                           const Vec3T<T>& dtheta, T k, T m_max) {
  const Vec3T<T> theta = theta_old + dtheta;
  const Vec3T<T> m = theta * k;
  const T lm = norm_of(m);
  const MaskOf<T> capped = both(lm > m_max, lm > 0);
  const Vec3T<T> m_capped = m * (m_max / lm);
  // the moment opposes the relative rotation
  return {pick(capped, m_capped * (1 / k), theta), -pick(capped, m_capped, m)};
}

// The paper's law as a contact law (contact_law.hpp): the two-spring stiffnesses and the
// damping of the lower restitution, fixed for a listed pair; a wall acts as a sphere of
// the sphere's own radius and infinite mass (SPEC §3).
struct LinearSpring {
  static constexpr const char* name = "linear_spring";
  static constexpr const char* time_scale_name = "sqrt(m / k_n)";
  static constexpr bool damps_shear = false;
  // The per-pair constants, for one pair or a batch (core/lanes.hpp).
  template <class T>
  struct PairT {
    T kn, ks, cn;
  };
  using Pair = PairT<Real>;
  // A material's damping constant: the damping ratio of its restitution.
  static Real damping(Real restitution) { return damping_ratio(restitution); }
  // Why a material does not suit this law (nullptr: it does); the key named.
  static const char* unsuitable(const Material& m, const char** key) {
    *key = "nu";
    return m.nu > 0 ? nullptr : "must be positive with the linear spring (the shear-to-normal stiffness ratio)";
  }
  [[nodiscard]] SURGE_HD static Pair pair(const Material& a, const Material& b, Real ra, Real rb, Real mstar) {
    Pair p;
    p.kn = normal_stiffness(a.young, ra, b.young, rb);
    p.ks = dem::shear_stiffness(a.young, a.nu, ra, b.young, b.nu, rb);
    // c_n = 2 beta sqrt(m* k_n), beta that of the lower restitution (damping_ratio falls
    // as e rises, so it is the larger of the two materials' ratios).
    p.cn = NormalSpringDashpot::with_ratio(p.kn, mstar, a.damping > b.damping ? a.damping : b.damping).cn;
    return p;
  }
  [[nodiscard]] SURGE_HD static Pair wall(const Material& sphere, const Material& w, Real r, Real m) {
    return pair(sphere, w, r, r, m);
  }
  template <class T, class M>
  [[nodiscard]] SURGE_HD SURGE_INLINE static T normal_force(const PairT<T>& p, T un, T dun, M bonded) {
    return NormalSpringDashpot::force_of(p.kn, p.cn, un, dun, bonded);
  }
  template <class T>
  [[nodiscard]] SURGE_HD SURGE_INLINE static T shear_stiffness(const PairT<T>& p, T un) {
    (void)un;
    return p.ks;
  }
  template <class T>
  [[nodiscard]] SURGE_HD SURGE_INLINE static T shear_damping(const PairT<T>& p, T un) {
    (void)p, (void)un;
    return T{};
  }
  // sqrt(m / k_n) of a sphere against an equal one (the step is dem.dt_factor times the
  // smallest; SPEC §3).
  static Real time_scale(const Material& m, Real r, Real mass) {
    return std::sqrt(mass / normal_stiffness(m.young, r, m.young, r));
  }
};

} // namespace surge::dem
