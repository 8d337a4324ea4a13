// Sub-particle-scale (SPS) turbulence, sph.viscosity: laminar_sps (SPEC §8: Dalrymple &
// Rogers 2006, the form DualSPHysics uses), added to the laminar term:
//   S_i     = sym( sum_j V_j (v_j - v_i) (x) grad_i W_ij )      (strain rate, every neighbour;
//             a wall's or body's particle brings its own velocity)
//   tau_i/rho_i = 2 nu_t (S_i - tr(S_i)/3 I) - 2/3 C_I D^2 |S_i|^2 I,
//   nu_t = (C_s D)^2 |S_i|,  |S| = (2 S:S)^(1/2),  D = dp
//   dv_i/dt += sum_j m_j (tau_i/rho_i^2 + tau_j/rho_j^2) . grad_i W_ij  (fluid j only: the
//             stress is the water's; walls drag through the laminar term)
// Two passes, each particle writing only its own: the stress of every particle (images take
// theirs from the particles they copy, halo copies compute their own: the stress reaches one
// support further, WcsphSolver::dependency_reach), then the momentum term of each fluid
// particle, added to the acceleration the rates pass wrote.
#pragma once
#include "surge/neighbour/uniform_grid.hpp"
#include "surge/particles/particle_store.hpp"
#include "surge/sph/kernel_wendland_c2.hpp"

namespace surge::sph {

struct SpsParams {
  Real cs = Real(0.12);   // Smagorinsky constant (sph.sps_smagorinsky)
  Real ci = Real(0.0066); // Blin constant (sph.sps_blin)
  Real delta = 0;         // filter width D = dp
};

// A symmetric tensor: the strain rate S or the stress tau/rho.
struct SymTensor {
  Real xx = 0, yy = 0, zz = 0, xy = 0, xz = 0, yz = 0;
  // The tensor times the vector g.
  [[nodiscard]] SURGE_HD Vec3 dot(const Vec3& g) const {
    return {xx * g.x + xy * g.y + xz * g.z, xy * g.x + yy * g.y + yz * g.z, xz * g.x + yz * g.y + zz * g.z};
  }
  // The tensor seen in a frame mirrored on the axes whose bits are set in `mirrored` (1 x,
  // 2 y, 4 z): an off-diagonal component changes sign when one of its two axes is mirrored.
  [[nodiscard]] SURGE_HD SymTensor mirrored(unsigned m) const {
    const auto sign = [m](unsigned a, unsigned b) { return ((m >> a) ^ (m >> b)) & 1U ? Real(-1) : Real(1); };
    return {xx, yy, zz, xy * sign(0, 1), xz * sign(0, 2), yz * sign(1, 2)};
  }
};

// The strain rate's term of the pair (i, j): vji = v_j - v_i, grad = grad_i W_ij, vol = V_j.
SURGE_HD inline void add_strain_terms(const Vec3& vji, const Vec3& grad, Real vol, SymTensor& s) {
  const Real h = Real(0.5) * vol;
  s.xx += vol * vji.x * grad.x;
  s.yy += vol * vji.y * grad.y;
  s.zz += vol * vji.z * grad.z;
  s.xy += h * (vji.x * grad.y + vji.y * grad.x);
  s.xz += h * (vji.x * grad.z + vji.z * grad.x);
  s.yz += h * (vji.y * grad.z + vji.z * grad.y);
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

// The stress tau/rho of particle i (zero unless fluid).
[[nodiscard]] SURGE_HD inline SymTensor sps_stress_of(const SpsParams& c, const WendlandC2& kernel, Real mass,
                                                      const neighbour::GridView& g, const particles::ParticleView& p,
                                                      int i) {
  if (p.kind[i] != static_cast<std::uint8_t>(Kind::Fluid)) return {};
  const Vec3 vi = p.vel[i];
  SymTensor s;
  neighbour::for_each_neighbour(g, p.pos[i], kernel.support() * kernel.support(), [&](int j, const Vec3& rij, Real r2) {
    if (j == i) return;
    add_strain_terms(p.vel[j] - vi, rij * kernel.dw_over_r(std::sqrt(r2)), mass / p.rho[j], s);
  });
  return sps_stress(c, s);
}

// The SPS term of fluid particle i's acceleration, from every particle's stress tau/rho.
[[nodiscard]] SURGE_HD inline Vec3 sps_acceleration_of(const WendlandC2& kernel, Real mass,
                                                       const neighbour::GridView& g, const particles::ParticleView& p,
                                                       const SymTensor* tau, int i) {
  const auto fluid = static_cast<std::uint8_t>(Kind::Fluid);
  const Real wi = 1 / p.rho[i];
  const SymTensor ti = tau[i];
  Vec3 a{};
  neighbour::for_each_neighbour(g, p.pos[i], kernel.support() * kernel.support(), [&](int j, const Vec3& rij, Real r2) {
    if (j == i || p.kind[j] != fluid) return;
    const Vec3 grad = rij * kernel.dw_over_r(std::sqrt(r2));
    const SymTensor tj = tau[j];
    const Real wj = 1 / p.rho[j];
    const SymTensor sum{ti.xx * wi + tj.xx * wj, ti.yy * wi + tj.yy * wj, ti.zz * wi + tj.zz * wj,
                        ti.xy * wi + tj.xy * wj, ti.xz * wi + tj.xz * wj, ti.yz * wi + tj.yz * wj};
    a += sum.dot(grad) * mass;
  });
  return a;
}

} // namespace surge::sph
