// Hertz–Mindlin contact law (`dem.contact: hertz_mindlin`), the default of LIGGGHTS and
// EDEM and LAMMPS's `granular hertz/material ... tangential mindlin`:
//
// normal:   F_n = K u_n^(3/2) + c_n u_n^(1/4) du_n/dt, K = 4/3 E* sqrt(R*), clipped at 0;
//           1/E* = (1 - nu_A^2)/E_A + (1 - nu_B^2)/E_B, 1/R* = 1/r_A + 1/r_B (a wall: R* = r).
// damping:  c_n = alpha(e) sqrt(m* K) (Tsuji et al. 1992): alpha is found once per
//           material so that the clipped damped Hertz impact rebounds with restitution e
//           exactly (the impact's restitution does not depend on its speed). LIGGGHTS's
//           closed form, 2 sqrt(5/6) beta(e) sqrt(S_n m*), is an approximation of the
//           same law: it rebounds with 0.55 for e = 0.5, 0.32 for e = 0.2.
// shear:    no-slip Mindlin stiffness k_t = 8 G* sqrt(R* u_n), 1/G* = 2(2 - nu_A)(1 + nu_A)/E_A
//           + 2(2 - nu_B)(1 + nu_B)/E_B; incremental spring F_s <- R(F_s) - k_t du_s plus the
//           damping -c_t u_n^(1/4) v_t, c_t = c_n sqrt(k_t / (3/2 K sqrt(u_n))) (LIGGGHTS's
//           ratio S_t / S_n); Coulomb limit on the total, the spring keeping what is left.
// rolling / twisting: as the linear spring's, with k_t in place of k_s.
// time step: dem.dt_factor times the Rayleigh time pi r sqrt(rho / G) / (0.1631 nu + 0.8766)
//           of the smallest sphere.
// Bonds (the paper's CFM) are part of the linear law only; surge refuses bonded
// materials with this law.
#pragma once
#include "surge/core/lanes.hpp"
#include "surge/dem/contact_linear_spring.hpp"
#include "surge/dem/material.hpp"

#include <cmath>

namespace surge::dem {

// alpha such that the clipped impact u'' = -u^(3/2) - alpha u^(1/4) u' (units in which the
// stiffness, the mass and the approach speed are 1) rebounds at speed e; 0 for e >= 1.
double hertz_damping_factor(double restitution);
// The restitution of that impact for a given alpha (the inverse, for tests).
double hertz_restitution(double alpha);

struct HertzMindlin {
  static constexpr const char* name = "hertz_mindlin";
  static constexpr const char* time_scale_name = "Rayleigh time";
  static constexpr bool damps_shear = true;
  // The per-pair constants, for one pair or a batch (core/lanes.hpp).
  template <class T>
  struct PairT {
    T k;  // 4/3 E* sqrt(R*)
    T kt; // 8 G* sqrt(R*)
    T cn; // alpha sqrt(m* k)
    T ct; // alpha sqrt(m* 2/3 kt)
  };
  using Pair = PairT<Real>;
  static Real damping(Real restitution) { return static_cast<Real>(hertz_damping_factor(restitution)); }
  static const char* unsuitable(const Material& m, const char** key) {
    *key = "nu";
    if (!(m.nu > -1 && m.nu < Real(0.5))) return "must lie in (-1, 0.5) with hertz_mindlin (Poisson's ratio)";
    *key = "bond";
    if (m.bonded) return "bonds belong to the linear spring (SPEC 3.4); use dem.contact: linear_spring";
    return nullptr;
  }
  [[nodiscard]] SURGE_HD static Pair make(Real estar, Real gstar, Real rstar, Real mstar, Real alpha) {
    Pair p;
    const Real sr = std::sqrt(rstar);
    p.k = Real(4.0 / 3.0) * estar * sr;
    p.kt = 8 * gstar * sr;
    p.cn = alpha * std::sqrt(mstar * p.k);
    p.ct = alpha * std::sqrt(mstar * Real(2.0 / 3.0) * p.kt);
    return p;
  }
  [[nodiscard]] SURGE_HD static Real inv_estar(const Material& m) { return (1 - m.nu * m.nu) / m.young; }
  [[nodiscard]] SURGE_HD static Real inv_gstar(const Material& m) { return 2 * (2 - m.nu) * (1 + m.nu) / m.young; }
  // Two materials meeting with effective radius R* and mass m*.
  [[nodiscard]] SURGE_HD static Pair mixed(const Material& a, const Material& b, Real rstar, Real mstar) {
    return make(1 / (inv_estar(a) + inv_estar(b)), 1 / (inv_gstar(a) + inv_gstar(b)), rstar, mstar,
                a.damping > b.damping ? a.damping : b.damping);
  }
  [[nodiscard]] SURGE_HD static Pair pair(const Material& a, const Material& b, Real ra, Real rb, Real mstar) {
    return mixed(a, b, ra * rb / (ra + rb), mstar);
  }
  // A wall: a flat surface (infinite radius) of infinite mass.
  [[nodiscard]] SURGE_HD static Pair wall(const Material& sphere, const Material& w, Real r, Real m) {
    return mixed(sphere, w, r, m);
  }
  // (A batch computes every lane and keeps 0 where un <= 0.)
  template <class T, class M>
  [[nodiscard]] SURGE_HD SURGE_INLINE static T normal_force(const PairT<T>& p, T un, T dun, M bonded) {
    (void)bonded; // never bonded (unsuitable)
    const T s = sqrt_of(un);
    const T f = p.k * s * un + p.cn * sqrt_of(s) * dun;
    return pick(both(un > 0, negate(f < 0)), f, T{});
  }
  template <class T>
  [[nodiscard]] SURGE_HD SURGE_INLINE static T shear_stiffness(const PairT<T>& p, T un) {
    return pick(un > 0, p.kt * sqrt_of(un), T{});
  }
  template <class T>
  [[nodiscard]] SURGE_HD SURGE_INLINE static T shear_damping(const PairT<T>& p, T un) {
    return pick(un > 0, p.ct * sqrt_of(sqrt_of(un)), T{});
  }
  // The Rayleigh time of the sphere.
  static Real time_scale(const Material& m, Real r, Real mass) {
    (void)mass;
    const double g = m.young / (2 * (1 + static_cast<double>(m.nu)));
    return static_cast<Real>(pi * r * std::sqrt(m.density / g) / (0.1631 * m.nu + 0.8766));
  }
};

} // namespace surge::dem
