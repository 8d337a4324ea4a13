// Tait equation of state (Monaghan 1994; SPEC §2.2):
// p = B ((rho/rho0)^gamma - 1), B = c0^2 rho0 / gamma, c0 = eta sqrt(g Hmax).
#pragma once
#include "surge/core/types.hpp"

namespace surge::sph {

struct TaitEos {
  Real rho0 = 1000;
  Real c0 = 1;
  Real b = 0; // c0^2 rho0 / gamma, gamma = 7

  SURGE_HD TaitEos() = default;
  SURGE_HD TaitEos(Real rho0_, Real c0_) : rho0(rho0_), c0(c0_), b(c0_ * c0_ * rho0_ / 7) {}

  [[nodiscard]] SURGE_HD Real pressure(Real rho) const {
    const Real x = rho / rho0;
    const Real x2 = x * x;
    return b * (x2 * x2 * x2 * x - 1);
  }
  // Inverse, used to start a water column in hydrostatic balance.
  [[nodiscard]] SURGE_HD Real density(Real p) const { return rho0 * std::pow(1 + p / b, Real(1.0 / 7.0)); }
};

} // namespace surge::sph
