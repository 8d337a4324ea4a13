// The terms of one DEM contact (SPEC §3) under contact law L, shared by every law:
// normal force, bond breakage, the shear spring with its Coulomb limit, rolling and
// twisting resistance. The solver's pair and wall passes (dem_solver.cpp) and the CPU's
// batched pair pass (dem_batched.inc) call the same templates.
#pragma once
#include "surge/core/lanes.hpp"
#include "surge/dem/dem_solver.hpp"

namespace surge::dem::detail {

// The pair terms of one contact, for the canonical side A (lower id, or the sphere
// against a plane). Everything both sides need comes from here, computed once per side
// with identical inputs, so the two sides agree exactly. Written once for one contact
// (T = Real) and for a batch of them (T = a vector of Reals: dem_batched.inc), with
// the same bits in every lane (core/lanes.hpp).
template <class T>
struct PairInputT {
  Vec3T<T> n; // unit normal, from B to A
  T un;       // overlap
  T ra, rb;   // radii (rb: 0 for a plane)
  Vec3T<T> va, wa, vb, wb;
  T tan_phi;
  T k_roll, k_roll_max, k_twist, k_twist_max;
  T rmin;             // r' = min(r_A, r_B)
  T bond_cn, bond_cs; // bond strengths (used while the slot is bonded)
};
using PairInput = PairInputT<Real>;

// A contact's springs: its history without the partner.
template <class T>
struct SpringsT {
  Vec3T<T> shear; // shear force on the canonical A sphere
  Vec3T<T> roll;  // accumulated rolling rotation (A relative to B)
  Vec3T<T> twist; // accumulated twisting rotation
  MaskOf<T> bonded;
};

template <class T>
struct PairResultT {
  Vec3T<T> force_a;  // total contact force on A
  Vec3T<T> torque_a; // about A's centre
  Vec3T<T> torque_b; // about B's centre (zero for planes)
  SpringsT<T> springs;
  MaskOf<T> broke;
};
using PairResult = PairResultT<Real>;

[[nodiscard]] SURGE_HD inline SpringsT<Real> springs_of(const ContactSlot& s) {
  return {s.shear, s.roll, s.twist, s.bonded != 0};
}
[[nodiscard]] SURGE_HD inline ContactSlot slot_of(const SpringsT<Real>& s, std::uint32_t partner) {
  return {partner, s.shear, s.roll, s.twist, s.bonded ? 1U : 0U};
}

// The shear force of law L: the incremental spring with the Coulomb limit on it, or, for
// a law that damps shear, on the spring and the damping together (the spring then keeps
// what the limit leaves of the total). `spring` is the history to keep.
template <class T>
struct ShearTermsT {
  Vec3T<T> force, spring;
  MaskOf<T> slipped;
};
template <class L, class T>
SURGE_HD SURGE_INLINE ShearTermsT<T> shear_terms(const Vec3T<T>& old, const Vec3T<T>& n, const Vec3T<T>& vrel, T dt,
                                                 T ks, T cs, T limit) {
  if constexpr (!L::damps_shear) {
    (void)cs;
    const ShearUpdateT<T> sh = shear_force(old, n, vrel * dt, ks, limit);
    return {sh.force, sh.force, sh.slipped};
  } else {
    const Vec3T<T> vt = tangential(vrel, n);
    const Vec3T<T> spring = rotate_into_plane(old, n) - vt * (dt * ks);
    const Vec3T<T> total = spring - vt * cs;
    const MaskOf<T> slipped = norm_of(total) > limit;
    const Vec3T<T> capped = cap_length(total, limit);
    return {pick(slipped, capped, total), pick(slipped, capped + vt * cs, spring), slipped};
  }
}

template <class L, class T>
SURGE_HD SURGE_INLINE PairResultT<T> pair_terms(const PairInputT<T>& in, const typename L::template PairT<T>& law,
                                                const SpringsT<T>& old, T dt) {
  using M = MaskOf<T>;
  const Vec3T<T> n = in.n;
  const Vec3T<T> ca = n * (-(in.ra - in.un / 2)); // contact point relative to A's centre
  const Vec3T<T> cb = n * (in.rb - in.un / 2);    // ... relative to B's centre
  const Vec3T<T> vrel = (in.va + cross(in.wa, ca)) - (in.vb + cross(in.wb, cb));
  const T dun = -dot(vrel, n);
  M bonded = old.bonded;
  T fn = L::normal_force(law, in.un, dun, bonded);
  const T area = in.rmin * in.rmin;
  const M torn = both(bonded, -fn > in.bond_cn * area); // tension beyond C_n r'^2
  M broke = torn;
  if (any_lane(torn)) {
    bonded = both(bonded, negate(torn));
    fn = pick(torn, L::normal_force(law, in.un, dun, splat_mask<T>(false)), fn);
  }
  const T fn_abs = pick(fn < 0, -fn, fn);
  const T ks = L::shear_stiffness(law, in.un), cs = L::shear_damping(law, in.un);
  ShearTermsT<T> sh =
      shear_terms<L>(old.shear, n, vrel, dt, ks, cs, fn_abs * in.tan_phi + pick(bonded, in.bond_cs * area, T{}));
  const M slid = both(bonded, sh.slipped);
  if (any_lane(slid)) { // shear beyond |F_n| tan(phi) + C_s r'^2: the bond breaks, friction remains
    bonded = both(bonded, negate(slid));
    broke = either(broke, slid);
    fn = pick(slid, L::normal_force(law, in.un, dun, splat_mask<T>(false)), fn);
    const ShearTermsT<T> free = shear_terms<L>(old.shear, n, vrel, dt, ks, cs, fn * in.tan_phi);
    sh.force = pick(slid, free.force, sh.force);
    sh.spring = pick(slid, free.spring, sh.spring);
  }
  // Rolling and twisting resistance where their stiffness is positive (a batch computes
  // them when any lane needs them).
  const Vec3T<T> dtheta = (in.wa - in.wb) * dt;
  const T kr = in.k_roll * in.rmin * in.rmin * ks, kt = in.k_twist * in.rmin * in.rmin * ks;
  Vec3T<T> m_roll{}, m_twist{}, roll{}, twist{};
  if (const M rolls = kr > 0; any_lane(rolls)) {
    const ResistanceUpdateT<T> u =
        resistance_moment(rotate_into_plane(old.roll, n), tangential(dtheta, n), kr, in.k_roll_max * fn * in.rmin);
    roll = pick(rolls, u.theta, roll);
    m_roll = pick(rolls, u.moment, m_roll);
  }
  if (const M twists = kt > 0; any_lane(twists)) {
    const ResistanceUpdateT<T> u =
        resistance_moment(n * dot(old.twist, n), n * dot(dtheta, n), kt, in.k_twist_max * fn * in.rmin);
    twist = pick(twists, u.theta, twist);
    m_twist = pick(twists, u.moment, m_twist);
  }
  // Every member given (no zeroing of the whole result first: it showed in the profile).
  return PairResultT<T>{n * fn + sh.force, cross(ca, sh.force) + m_roll + m_twist,
                        cross(cb, sh.force * splat<T>(-1)) - m_roll - m_twist,
                        SpringsT<T>{sh.spring, roll, twist, bonded}, broke};
}

// Pair properties from the two materials that every law shares (the law's own constants
// come from L::pair and L::wall); mixed once per material pair (DemView::mixed).
SURGE_HD inline MixedPair mix(const Material& ma, const Material& mb) {
  MixedPair m;
  m.tan_phi = ma.tan_phi < mb.tan_phi ? ma.tan_phi : mb.tan_phi;
  m.k_roll = (ma.k_roll + mb.k_roll) / 2;
  m.k_roll_max = (ma.k_roll_max + mb.k_roll_max) / 2;
  m.k_twist = (ma.k_twist + mb.k_twist) / 2;
  m.k_twist_max = (ma.k_twist_max + mb.k_twist_max) / 2;
  const bool bondable = ma.bonded && mb.bonded;
  m.bond_cn = bondable ? (ma.bond_cn < mb.bond_cn ? ma.bond_cn : mb.bond_cn) : 0;
  m.bond_cs = bondable ? (ma.bond_cs < mb.bond_cs ? ma.bond_cs : mb.bond_cs) : 0;
  return m;
}
template <class T>
SURGE_HD SURGE_INLINE void set_mixed(const MixedPairT<T>& m, T ra, T rb, PairInputT<T>& in) {
  in.tan_phi = m.tan_phi;
  in.k_roll = m.k_roll;
  in.k_roll_max = m.k_roll_max;
  in.k_twist = m.k_twist;
  in.k_twist_max = m.k_twist_max;
  in.rmin = pick(ra < rb, ra, rb);
  in.bond_cn = m.bond_cn;
  in.bond_cs = m.bond_cs;
}

// The input of sphere pair (A, B): dab = x_A - x_B and its length, the radii, the
// velocities and the two materials' mixed properties.
template <class T>
SURGE_HD SURGE_INLINE PairInputT<T> sphere_pair_input(const Vec3T<T>& dab, T dist, T ra, T rb, const Vec3T<T>& va,
                                                      const Vec3T<T>& wa, const Vec3T<T>& vb, const Vec3T<T>& wb,
                                                      const MixedPairT<T>& m) {
  PairInputT<T> in;
  in.n = dab * (1 / dist);
  in.un = ra + rb - dist;
  in.ra = ra;
  in.rb = rb;
  in.va = va;
  in.wa = wa;
  in.vb = vb;
  in.wb = wb;
  set_mixed(m, ra, rb, in);
  return in;
}

// Whether a listed pair is in contact: closer than r_A + r_B (reach), or bonded (a bond
// acts across a gap too), and apart (dist > 0). Without short circuits: the batched pass
// sorts pairs by it without a branch.
[[nodiscard]] SURGE_HD inline bool in_contact(Real dist, Real reach, bool held) {
  return (static_cast<int>(dist < reach) | static_cast<int>(held)) & static_cast<int>(!(dist <= 0));
}

} // namespace surge::dem::detail
