// The per-particle sums of weakly-compressible SPH (SPEC §2.3, §2.4):
//   drho_i/dt = sum_j m_j v_ij . grad_i W_ij + D_i                 (continuity)
//   D_i = delta h c0 sum_j m_j 4/(rho_i+rho_j) (rho_j-rho_i) (r_ji.grad_i W_ij)/(r^2+0.01h^2)
//         (Molteni & Colagrossi 2009 delta-SPH; fluid-fluid pairs only)
//   Fourtakas et al. (2019) variant (prm.fourtakas): rho_j - rho_i replaced by its dynamic
//         part rho_j - rho_i - rho^H_ji, rho^H_ji = rho0 ((1 + rho0 g.r_ji / B)^(1/gamma) - 1),
//         the hydrostatic density difference between the two positions, so that water at
//         rest is not diffused towards uniform density (the plain term's drift near walls).
//   dv_i/dt = -sum_j m_j ((p_i+p_j)/(rho_i rho_j) + Pi_ij) grad_i W_ij + g
//   Pi_ij = -alpha c0 mu_ij / rho_mean,  mu_ij = h v_ij.r_ij/(r^2+0.01h^2) when v_ij.r_ij < 0
//         (Monaghan 1992; the standard form with rho_mean = (rho_i+rho_j)/2, not the
//          paper's Eq. 21 which divides by rho_i+rho_j)
// Wall and body particles sum over fluid neighbours only (dynamic boundary particles).
// Each particle i writes only its own rates, so results do not depend on thread order.
#pragma once
#include "surge/neighbour/uniform_grid.hpp"
#include "surge/particles/particle_store.hpp"
#include "surge/sph/boundary/no_penetration.hpp"
#include "surge/sph/eos_tait.hpp"
#include "surge/sph/kernel_wendland_c2.hpp"

namespace surge::sph {

struct WcsphParams {
  WendlandC2 kernel;
  TaitEos eos;
  Real mass = 1;           // rho0 dp^3, the same for every SPH particle
  Real dp = 1;             // particle spacing
  Real alpha = Real(0.01); // artificial viscosity
  Real delta = Real(0.1);  // density diffusion
  bool fourtakas = false;  // diffuse only the dynamic part of density (Fourtakas et al. 2019)
  Vec3 gravity{};
};

// A boundary (wall or body) particle's density never drops below rho0: a boundary
// particle must not pull the fluid (one rule for every integrator and for mDBC).
[[nodiscard]] SURGE_HD inline Real boundary_density(Real rho, Real rho0) { return rho < rho0 ? rho0 : rho; }

struct Rates {
  Vec3 acc{}; // without gravity for boundary particles (force per mass from the fluid)
  Real drho = 0;
  Real vsig = 0;
  WallPlane wall; // fluid, with no penetration: the wall face or particle it would reach first (no_penetration.hpp)
};

// `gh`: with the no-penetration condition, the wall particles' ghost offsets and reach,
// from which each fluid particle finds the wall face or particle it would reach first.
[[nodiscard]] SURGE_HD inline Rates wcsph_rates(const WcsphParams& prm, const neighbour::GridView& g,
                                                const particles::ParticleView& p, int i, const WallHoldView& gh = {}) {
  const Real h = prm.kernel.h;
  const Real eta2 = Real(0.01) * h * h;
  const Real r2max = prm.kernel.support() * prm.kernel.support();
  const Vec3 xi = p.pos[i];
  const Vec3 vi = p.vel[i];
  const Real rhoi = p.rho[i];
  const Real pi = p.press[i];
  const bool fluid_i = p.kind[i] == static_cast<std::uint8_t>(Kind::Fluid);
  const Real c0 = prm.eos.c0;
  Real drho = 0, diff = 0, vsig = 0;
  Vec3 acc{};
  FirstContact contact; // no penetration: the wall face or wall particle this fluid particle would reach first
  const Real keep_off = keep_off_distance(prm.dp);
  const auto wall = static_cast<std::uint8_t>(Kind::Wall);
  // One pair term; boundary particles (fluid_i false) only ever see fluid j.
  auto pair = [&](int j, const Vec3& rij, Real r2) {
    if (j == i) return;
    const bool fluid_j = p.kind[j] == static_cast<std::uint8_t>(Kind::Fluid);
    const Real r = std::sqrt(r2);
    const Vec3 grad = rij * prm.kernel.dw_over_r(r);
    const Vec3 vij = vi - p.vel[j];
    const Real rhoj = p.rho[j];
    const Real vr = dot(vij, rij);
    drho += prm.mass * dot(vij, grad);
    const Real inv_r2e = 1 / (r2 + eta2);
    const Real inv_rho_sum = 1 / (rhoi + rhoj);
    const Real mu = h * vr * inv_r2e;
    const Real amu = mu < 0 ? -mu : mu;
    vsig = amu > vsig ? amu : vsig;
    if (fluid_i && gh.hold && p.kind[j] == wall) {
      const std::uint32_t b = p.id[j] - gh.first_id;
      const WallReach reach = gh.reach[b];
      for_each_held_face(p.pos[j], rij, reach, gh.offset[b], gh.extra_face,
                         [&](const WallPlane& w) { contact.consider(w, xi, vi, keep_off); });
      if (r > 0) contact.consider(sphere_plane(p.pos[j], rij, r, reach.sphere, keep_off), xi, vi, keep_off);
    }
    if (fluid_i && fluid_j) {
      // rho^H_ji from the EOS's inverse at the hydrostatic pressure difference rho0 g.r_ji.
      const Real rho_h = prm.fourtakas ? prm.eos.density(-prm.eos.rho0 * dot(prm.gravity, rij)) - prm.eos.rho0 : 0;
      diff += prm.mass * 4 * inv_rho_sum * (rhoj - rhoi - rho_h) * (-dot(rij, grad)) * inv_r2e;
    }
    Real coef = (pi + p.press[j]) / (rhoi * rhoj);
    if (vr < 0) coef -= prm.alpha * c0 * mu * 2 * inv_rho_sum; // rho_mean = (rho_i + rho_j) / 2
    acc -= grad * (prm.mass * coef);
  };
  if (fluid_i)
    neighbour::for_each_neighbour(g, xi, r2max, pair);
  else
    neighbour::for_each_fluid_neighbour(g, xi, r2max, pair);
  Rates out;
  out.drho = drho + prm.delta * h * c0 * diff;
  out.acc = fluid_i ? acc + prm.gravity : acc;
  out.vsig = vsig;
  out.wall = contact.plane;
  return out;
}

} // namespace surge::sph
