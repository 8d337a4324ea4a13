// Sub-particle-scale (SPS) turbulence, sph.viscosity: laminar_sps (SPEC §8: Dalrymple &
// Rogers 2006, the form DualSPHysics uses), added to the laminar term:
//   S_i     = sym( sum_j V_j (v_j - v_i) (x) grad_i W_ij )      (strain rate, every neighbour;
//             a wall's or body's particle brings its own velocity)
//   tau_i/rho_i = 2 nu_t (S_i - tr(S_i)/3 I) - 2/3 C_I D^2 |S_i|^2 I,
//   nu_t = (C_s D)^2 |S_i|,  |S| = (2 S:S)^(1/2),  D = dp
//   dv_i/dt += sum_j m_j (tau_i/rho_i^2 + tau_j/rho_j^2) . grad_i W_ij  (every pair with water
//             in it; a wall's or body's particle carries no stress, tau = 0, as in DualSPHysics)
// So the water's stress reaches the walls: the wall pairs carry the momentum the water
// loses to them (action and reaction: a wall or body particle takes m_j tau_j/rho_j^2 from
// each fluid j), half the stress tau_xz A at the wall in the continuum (the walls' kernel
// fraction there is 1/2). With the pairs left out, as before 2026-12-07, a wall took none:
// the truncated sum then moved momentum between the layers of water only, a free-slip wall.
// In DualSPHysics's order: the stress is a particle's state (ParticleView::sps: sorted,
// exchanged, checkpointed). The rates pass sums the strain rate and the momentum term from
// the stresses the particles carry, in the same pair loop; the step then sets each
// particle's stress from its strain rate (WcsphSolver::step), so the momentum term reads
// the stress of the step before (of the half step, symplectic). A run's first pass is done
// twice, the stress set between (WcsphSolver::rates): the first step is not one late.
#pragma once
#include "surge/core/lanes.hpp"
#include "surge/core/sym_tensor.hpp"

namespace surge::sph {

struct SpsParams {
  Real cs = Real(0.12);   // Smagorinsky constant (sph.sps_smagorinsky)
  Real ci = Real(0.0066); // Blin constant (sph.sps_blin)
  Real delta = 0;         // filter width D = dp
};

// The strain rate S from add_sps_terms' sums. Their off-diagonals hold 2 S (both halves of
// the symmetric part): halved here once per particle, which gives the same bits as halving
// each term (a factor 2 is exact) for one multiplication per pair less.
[[nodiscard]] SURGE_HD inline SymTensor strain_rate(const SymTensor& sums) {
  const Real half = Real(0.5);
  return {sums.xx, sums.yy, sums.zz, half * sums.xy, half * sums.xz, half * sums.yz};
}

// A particle's side of the momentum term, tau/rho^2, from the stress tau/rho it carries.
template <class T>
[[nodiscard]] SURGE_HD SURGE_INLINE SymTensorT<T> stress_over_rho(const SymTensorT<T>& t, T rho) {
  const T w = 1 / rho;
  return {t.xx * w, t.yy * w, t.zz * w, t.xy * w, t.xz * w, t.yz * w};
}

// The SPS stress tau/rho of a strain rate S.
[[nodiscard]] SURGE_HD inline SymTensor sps_stress(const SpsParams& c, const SymTensor& s) {
  const Real ss = s.xx * s.xx + s.yy * s.yy + s.zz * s.zz + 2 * (s.xy * s.xy + s.xz * s.xz + s.yz * s.yz);
  const Real mag = std::sqrt(2 * ss);
  const Real d2 = c.delta * c.delta;
  const Real two_nut = 2 * c.cs * c.cs * d2 * mag;
  const Real third_tr = (s.xx + s.yy + s.zz) / 3;
  const Real iso = Real(2) / 3 * c.ci * d2 * mag * mag;
  return {two_nut * (s.xx - third_tr) - iso,
          two_nut * (s.yy - third_tr) - iso,
          two_nut * (s.zz - third_tr) - iso,
          two_nut * s.xy,
          two_nut * s.xz,
          two_nut * s.yz};
}

// The SPS terms of the pair (i, j) (add_pair_terms: vij = v_i - v_j): i's strain rate from
// j, and the stress's momentum term, added to acc; ti is i's side tau_i/rho_i^2
// (stress_over_rho, once per particle; 0 for a wall or body particle), tau_j the stress
// tau/rho that j carries (0 for a wall or body particle). The strain sums are read for
// fluid i only. Written for the pair loop's arithmetic, which is what laminar_sps costs:
// m grad W once for both terms, 1/rho_j once for V_j and tau_j/rho_j^2, and the strain's
// v_j - v_i folded into the sums' signs.
template <class T>
SURGE_HD SURGE_INLINE void add_sps_terms(Real mass, const Vec3T<T>& grad, const Vec3T<T>& vij, T rho_j,
                                         const SymTensorT<T>& ti, const SymTensorT<T>& tau_j, SymTensorT<T>& strain,
                                         Vec3T<T>& acc) {
  const T inv_rho = 1 / rho_j;
  const Vec3T<T> mgrad = grad * splat<T>(mass);
  const Vec3T<T> vgrad = mgrad * inv_rho; // V_j grad_i W_ij, V_j = m / rho_j
  // No copy fuses multiply-adds (-ffp-contract=off): each product costs a multiplication
  // and an addition, so each sum takes its products one at a time.
  strain.xx -= vij.x * vgrad.x;
  strain.yy -= vij.y * vgrad.y;
  strain.zz -= vij.z * vgrad.z;
  strain.xy -= vij.x * vgrad.y;
  strain.xy -= vij.y * vgrad.x;
  strain.xz -= vij.x * vgrad.z;
  strain.xz -= vij.z * vgrad.x;
  strain.yz -= vij.y * vgrad.z;
  strain.yz -= vij.z * vgrad.y;
  const SymTensorT<T> sum{ti.xx + tau_j.xx * inv_rho, ti.yy + tau_j.yy * inv_rho, ti.zz + tau_j.zz * inv_rho,
                          ti.xy + tau_j.xy * inv_rho, ti.xz + tau_j.xz * inv_rho, ti.yz + tau_j.yz * inv_rho};
  const Vec3T<T>& g = mgrad;
  acc.x += sum.xx * g.x;
  acc.x += sum.xy * g.y;
  acc.x += sum.xz * g.z;
  acc.y += sum.xy * g.x;
  acc.y += sum.yy * g.y;
  acc.y += sum.yz * g.z;
  acc.z += sum.xz * g.x;
  acc.z += sum.yz * g.y;
  acc.z += sum.zz * g.z;
}

} // namespace surge::sph
