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
//   or, with sph.viscosity: laminar (Morris et al. 1997, in the form of Lo & Shao 2002 that
//         DualSPHysics uses; SPEC §8), in place of Pi_ij:
//         + sum_j m_j 4 nu (r_ij.grad_i W_ij) v_ij / ((rho_i+rho_j)(r^2+0.01h^2))
//         (against a wall or body particle v_j is the wall's velocity: moving walls drag)
// With shifting (shifting.hpp) a fluid particle also sums grad C and div r over its pairs;
// with laminar_sps (sps_turbulence.hpp) its strain rate, and the SPS stress's momentum term
// from the stresses the particles carry.
// Wall and body particles sum over fluid neighbours only (dynamic boundary particles).
// Each particle i writes only its own rates, so results do not depend on thread order.
#pragma once
#include "surge/core/lanes.hpp"
#include "surge/neighbour/uniform_grid.hpp"
#include "surge/particles/particle_store.hpp"
#include "surge/sph/boundary/no_penetration.hpp"
#include "surge/sph/eos_tait.hpp"
#include "surge/sph/kernel_wendland_c2.hpp"
#include "surge/sph/shifting.hpp"
#include "surge/sph/sps_turbulence.hpp"

#include <type_traits>

namespace surge::sph {

// The momentum equation's viscous term (sph.viscosity); LaminarSps adds the SPS stress
// (sps_turbulence.hpp) to the laminar term.
enum class Viscosity : std::uint8_t { Artificial, Laminar, LaminarSps };

struct WcsphParams {
  WendlandC2 kernel;
  TaitEos eos;
  Real mass = 1;           // rho0 dp^3, the same for every SPH particle
  Real dp = 1;             // particle spacing
  Real alpha = Real(0.01); // artificial viscosity
  Real nu = Real(1e-6);    // kinematic viscosity [m^2/s] (laminar)
  Real delta = Real(0.1);  // density diffusion
  bool fourtakas = false;  // diffuse only the dynamic part of density (Fourtakas et al. 2019)
  Viscosity viscosity = Viscosity::Artificial;
  Vec3 gravity{};
  ShiftParams shift; // off unless sph.shifting
};

// A boundary (wall or body) particle's density never drops below rho0: a boundary
// particle must not pull the fluid (one rule for every integrator and for mDBC).
[[nodiscard]] SURGE_HD inline Real boundary_density(Real rho, Real rho0) { return rho < rho0 ? rho0 : rho; }

struct Rates {
  Vec3 acc{}; // without gravity for boundary particles (force per mass from the fluid)
  Real drho = 0;
  Real vsig = 0;
  WallChoice wall = no_wall; // fluid, with no penetration: the wall face or particle it would reach first
  ShiftSums shift;           // with shifting
  SymTensor strain;          // laminar_sps: the strain rate (fluid)
};

// Where a rates pass stores what a particle gives beyond the view's rates (null: not wanted).
struct RatesOut {
  WallChoice* faces = nullptr; // no penetration: each fluid particle's wall choice
  ShiftSums* shift = nullptr;  // shifting: each particle's grad C and div r
  SymTensor* strain = nullptr; // laminar_sps: each particle's strain rate
};

// The formulas below are written once for T = Real (one pair at a time: the scalar and
// CUDA paths) and for T = a SIMD vector of Reals (a batch of pairs, one per lane:
// wcsph_rates_batched.inc); core/lanes.hpp says how.

// The sums particle i accumulates over its pairs (each pair's term as in the header).
// vsig is a maximum; the others are sums, listed once in for_each_sum.
template <class T>
struct PairSums {
  T drho{}, diff{}, vsig{};
  Vec3T<T> acc{};
  Vec3T<T> grad_c{}; // shifting only
  T div_r{};
};

// What laminar_sps adds to a particle's sums (add_pair_terms' SpsPair), held apart from PairSums so
// that the other settings' pair loops carry none of it; its momentum term goes into
// PairSums::acc (6 vector sums in the batched loop, not 9).
template <class T>
struct SpsSums {
  SymTensorT<T> strain{}; // add_sps_terms' sums (strain_rate)
};

// Calls f(a.x, b.x) for every summed member x of two PairSums (of any lane types), the
// shifting sums last and only with `shifting`: the batched pass adds its lanes through it.
template <class A, class B, class F>
SURGE_HD SURGE_INLINE void for_each_sum(A& a, B& b, bool shifting, F&& f) {
  f(a.drho, b.drho);
  f(a.diff, b.diff);
  f(a.acc.x, b.acc.x);
  f(a.acc.y, b.acc.y);
  f(a.acc.z, b.acc.z);
  if (!shifting) return;
  f(a.grad_c.x, b.grad_c.x);
  f(a.grad_c.y, b.grad_c.y);
  f(a.grad_c.z, b.grad_c.z);
  f(a.div_r, b.div_r);
}

// The same for the members of two SpsSums.
template <class A, class B, class F>
SURGE_HD SURGE_INLINE void for_each_sps_sum(A& a, B& b, F&& f) {
  f(a.strain.xx, b.strain.xx);
  f(a.strain.yy, b.strain.yy);
  f(a.strain.zz, b.strain.zz);
  f(a.strain.xy, b.strain.xy);
  f(a.strain.xz, b.strain.xz);
  f(a.strain.yz, b.strain.yz);
}

// What the pair terms read of one particle of a pair.
template <class T>
struct PairSide {
  Vec3T<T> vel;
  T rho, press;
};

// rho^H_ji for Fourtakas's diffusion (0 for Molteni's): the EOS's inverse at the hydrostatic
// pressure difference rho0 g.r_ji. std::pow has no vector form: lane by lane for a batch.
template <class T>
[[nodiscard]] SURGE_HD SURGE_INLINE T hydrostatic_density(const WcsphParams& prm, const Vec3T<T>& rij) {
  if (!prm.fourtakas) return T{};
  if constexpr (std::is_same_v<T, Real>) {
    return prm.eos.density(-prm.eos.rho0 * dot(prm.gravity, rij)) - prm.eos.rho0;
  } else {
    T out{};
    for (int k = 0; k < static_cast<int>(sizeof(T) / sizeof(Real)); ++k)
      out[k] = hydrostatic_density<Real>(prm, Vec3{rij.x[k], rij.y[k], rij.z[k]});
    return out;
  }
}

// The density diffusion term of a pair of fluid particles (each argument as in add_pair_terms).
// A function, not a lambda: GCC 12 fails (an internal error) on a lambda returning a
// 32-byte vector in the SSE2 copy of the batched loop.
template <class T>
[[nodiscard]] SURGE_HD SURGE_INLINE T diffusion_term(const WcsphParams& prm, const Vec3T<T>& rij, const Vec3T<T>& grad,
                                                     T rho_i, T rho_j, T inv_rho_sum, T inv_r2e) {
  const T rho_h = hydrostatic_density(prm, rij);
  return prm.mass * 4 * inv_rho_sum * (rho_j - rho_i - rho_h) * (-dot(rij, grad)) * inv_r2e;
}

// laminar_sps's side of a pair for add_pair_terms (sps_turbulence.hpp): i's side
// tau_i/rho_i^2 (stress_over_rho, once per particle), the stress tau/rho that j carries,
// and i's SPS sums.
template <class T>
struct SpsPair {
  const SymTensorT<T>& ti;
  const SymTensorT<T>& tau_j;
  SpsSums<T>& sums;
};

// Adds the terms of the pairs (i, j) to s: rij = x_i - x_j, r2 = |rij|^2, r = |rij|;
// `diffuse`: both are fluid (density diffusion acts between fluid particles only); with
// `sps` (laminar_sps) the SPS terms of the same pairs, from the same kernel gradient and
// velocity difference, to sps->sums and s.acc.
template <class T, class Mask>
SURGE_HD SURGE_INLINE void add_pair_terms(const WcsphParams& prm, const Vec3T<T>& rij, T r2, T r, const PairSide<T>& a,
                                          const PairSide<T>& b, Mask diffuse, PairSums<T>& s,
                                          const SpsPair<T>* sps = nullptr) {
  const Real h = prm.kernel.h;
  const Real eta2 = Real(0.01) * h * h;
  const Vec3T<T> grad = rij * prm.kernel.dw_over_r(r);
  const Vec3T<T> vij = a.vel - b.vel;
  const T vr = dot(vij, rij);
  s.drho += prm.mass * dot(vij, grad);
  const T inv_r2e = 1 / (r2 + eta2);
  const T inv_rho_sum = 1 / (a.rho + b.rho);
  const T mu = h * vr * inv_r2e;
  const T amu = mu < 0 ? -mu : mu;
  s.vsig = amu > s.vsig ? amu : s.vsig;
  if constexpr (std::is_same_v<T, Real>) { // one pair: skipped where it does not act (pow for Fourtakas)
    if (diffuse) s.diff += diffusion_term(prm, rij, grad, a.rho, b.rho, inv_rho_sum, inv_r2e);
  } else { // a batch: every lane computed, 0 added where it does not act
    s.diff += diffuse ? diffusion_term(prm, rij, grad, a.rho, b.rho, inv_rho_sum, inv_r2e) : T{};
  }
  T coef = (a.press + b.press) / (a.rho * b.rho);
  if (prm.viscosity == Viscosity::Artificial) {
    const T visc = prm.alpha * prm.eos.c0 * mu * 2 * inv_rho_sum; // rho_mean = (rho_i + rho_j) / 2
    coef = vr < 0 ? coef - visc : coef;
  }
  s.acc -= grad * (prm.mass * coef);
  if (prm.viscosity == Viscosity::Laminar || prm.viscosity == Viscosity::LaminarSps)
    s.acc += vij * (prm.mass * 4 * prm.nu * dot(rij, grad) * inv_rho_sum * inv_r2e);
  if (prm.shift.on()) add_shift_terms(prm.shift, rij, grad, prm.mass / b.rho, prm.kernel.w(r), s.grad_c, s.div_r);
  if (sps) add_sps_terms(prm.mass, grad, vij, b.rho, sps->ti, sps->tau_j, sps->sums.strain, s.acc);
}

// The rates of particle i from its sums.
[[nodiscard]] SURGE_HD inline Rates finish_rates(const WcsphParams& prm, bool fluid_i, const PairSums<Real>& s,
                                                 WallChoice wall) {
  Rates out;
  out.drho = s.drho + prm.delta * prm.kernel.h * prm.eos.c0 * s.diff;
  out.acc = fluid_i ? s.acc + prm.gravity : s.acc;
  out.vsig = s.vsig;
  out.wall = wall;
  out.shift = {s.grad_c, s.div_r};
  return out;
}

// The rates of particle i with its SPS sums added.
SURGE_HD inline void add_sps_rates(const SpsSums<Real>& s, Rates& r) { r.strain = strain_rate(s.strain); }

// Writes particle i's rates (and what `out` asks for: its wall's choice, its shifting sums).
SURGE_HD inline void store_rates(const particles::ParticleView& p, const RatesOut& out, int i, const Rates& r) {
  p.acc[i] = r.acc;
  p.drho[i] = r.drho;
  p.vsig[i] = r.vsig;
  if (out.faces) out.faces[i] = r.wall;
  if (out.shift) out.shift[i] = r.shift;
  if (out.strain) out.strain[i] = r.strain;
}

// Offers the faces and the sphere of wall particle j (at x_i - rij, |rij| = r) to the
// fluid particle i's choice of the wall it would reach first (no_penetration.hpp).
SURGE_HD SURGE_NOINLINE inline void consider_wall(const WallHoldView& gh, const particles::ParticleView& p, int j,
                                                  const Vec3& xi, const Vec3& vi, const Vec3& rij, Real r,
                                                  Real keep_off, FirstContact& contact) {
  const std::uint32_t b = p.id[j] - gh.first_id;
  const WallReach reach = wall_reach(gh, b);
  const Vec3 v = vi - p.vel[j]; // relative to a moving wall (a still one: vi itself)
  for_each_held_face(p.pos[j], rij, reach, wall_offset(gh, b), gh.extra_face,
                     [&](const WallPlane& w, int what) { contact.consider(w, wall_choice(j, what), xi, v, keep_off); });
  if (r > 0)
    contact.consider(sphere_plane(p.pos[j], rij, r, reach.sphere, keep_off), wall_choice(j, sphere_of_wall), xi, v,
                     keep_off);
}

// The plane consider_wall offered as `choice` to the fluid particle at xi, rebuilt from
// the same inputs: the update calls it at the positions the rates pass saw (moving walls
// are placed after the update, and the particle's own position is read before it moves),
// so it is the same plane, bit for bit, with the wall particle's normal speed (vn: the
// update holds water in front of where the plane will be, WallPlane::after). No plane
// (normal 0) for no_wall.
[[nodiscard]] SURGE_HD inline WallPlane held_plane(const WallHoldView& gh, const particles::ParticleView& p,
                                                   WallChoice choice, const Vec3& xi, Real keep_off) {
  if (choice == no_wall) return {};
  const int j = chosen_wall(choice), what = chosen_what(choice);
  const Vec3 xb = p.pos[j];
  const Vec3 rij = xi - xb;
  const std::uint32_t b = p.id[j] - gh.first_id;
  const WallReach reach = wall_reach(gh, b);
  WallPlane w;
  if (what == sphere_of_wall) {
    w = sphere_plane(xb, rij, std::sqrt(dot(rij, rij)), reach.sphere, keep_off);
  } else {
    Real d;
    face_below(xb, face_offset(reach, wall_offset(gh, b), gh.extra_face, what), rij, reach.patch, w, d);
  }
  w.vn = dot(w.n, p.vel[j]) + Real(0); // + 0: a still wall's -0 made +0 (the plane offered has +0)
  return w;
}

// `gh`: with the no-penetration condition, the wall particles' ghost offsets and reach,
// from which each fluid particle finds the wall face or particle it would reach first.
// One pair at a time; the CPU build runs wcsph_rates_batched.inc, the same sums 8 pairs at a time.
[[nodiscard]] SURGE_HD inline Rates wcsph_rates(const WcsphParams& prm, const neighbour::GridView& g,
                                                const particles::ParticleView& p, int i, const WallHoldView& gh = {}) {
  const Real r2max = prm.kernel.support() * prm.kernel.support();
  const Vec3 xi = p.pos[i];
  const PairSide<Real> a{p.vel[i], p.rho[i], p.press[i]};
  const auto fluid = static_cast<std::uint8_t>(Kind::Fluid), wall = static_cast<std::uint8_t>(Kind::Wall);
  const bool fluid_i = p.kind[i] == fluid;
  PairSums<Real> s;
  // laminar_sps: the stress's term on every pair (a wall or body particle carries none, 0,
  // and takes the water's), the strain rate read for fluid only.
  SpsSums<Real> sps;
  const SymTensor ti = p.sps ? stress_over_rho(p.sps[i], a.rho) : SymTensor{};
  FirstContact contact; // no penetration: the wall face or wall particle this fluid particle would reach first
  const Real keep_off = keep_off_distance(prm.dp);
  // Boundary particles (fluid_i false) only ever see fluid j.
  auto pair = [&](int j, const Vec3& rij, Real r2) {
    if (j == i) return;
    const Real r = std::sqrt(r2);
    if (fluid_i && gh.hold && p.kind[j] == wall) consider_wall(gh, p, j, xi, a.vel, rij, r, keep_off, contact);
    const SpsPair<Real> sp{ti, p.sps ? p.sps[j] : ti, sps};
    add_pair_terms(prm, rij, r2, r, a, PairSide<Real>{p.vel[j], p.rho[j], p.press[j]}, fluid_i && p.kind[j] == fluid, s,
                   p.sps ? &sp : nullptr);
  };
  if (fluid_i)
    neighbour::for_each_neighbour(g, xi, r2max, pair);
  else
    neighbour::for_each_fluid_neighbour(g, xi, r2max, pair);
  Rates out = finish_rates(prm, fluid_i, s, contact.choice);
  if (p.sps && fluid_i) add_sps_rates(sps, out);
  return out;
}

// Whether fluid particle i lies at the free surface: its position divergence (shifting.hpp),
// summed over neighbours of every kind, below prm.shift.surface (the frames' `surface`).
[[nodiscard]] SURGE_HD inline bool at_free_surface(const WcsphParams& prm, const neighbour::GridView& g,
                                                   const particles::ParticleView& p, int i) {
  ShiftParams plain = prm.shift;
  plain.clump = 0; // div r is never weighted
  Vec3 grad_c{};
  Real div_r = 0;
  neighbour::for_each_neighbour(g, p.pos[i], prm.kernel.support() * prm.kernel.support(),
                                [&](int j, const Vec3& rij, Real r2) {
                                  if (j == i) return;
                                  const Vec3 grad = rij * prm.kernel.dw_over_r(std::sqrt(r2));
                                  add_shift_terms(plain, rij, grad, prm.mass / p.rho[j], Real(0), grad_c, div_r);
                                });
  return at_surface(prm.shift, div_r);
}

} // namespace surge::sph
