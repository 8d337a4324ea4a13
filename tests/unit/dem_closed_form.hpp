// Closed forms for DEM tests.
#pragma once
#include "surge/dem/contact_linear_spring.hpp"

#include <cmath>

namespace surge::test {

// The tests' granular material: rho = 2500 kg/m^3, friction angle 30 degrees, the given
// Young's modulus, nu and restitution.
inline dem::Material grains(Real young, Real nu, Real e) {
  dem::Material m;
  m.density = 2500;
  m.young = young;
  m.nu = nu;
  m.tan_phi = std::tan(Real(30 * dem::pi / 180));
  m.restitution = e;
  return m;
}

struct Impact {
  double duration = 0, restitution = 0, momentum_error = 0, max_overlap = 0;
};

// Head-on impact of two equal spheres (r = 1 cm, rho = 2500, E = 1 MPa, so
// k_n = E r / 2 by the two-spring formula) at relative speed v0.
// Closed form for the clipped linear spring-dashpot: the force vanishes at t* with
// tan(w_d t*) = -2 beta sqrt(1 - beta^2) / (1 - 2 beta^2); after that the spheres move
// apart at constant speed until the overlap is gone.
inline Impact closed_form(double e, double v0) {
  const double r = 0.01, rho = 2500, E = 1.0e6;
  const double m = rho * 4.0 / 3.0 * dem::pi * r * r * r;
  const double kn = E * r / 2, mstar = m / 2;
  const double w0 = std::sqrt(kn / mstar);
  const double beta = e >= 1 ? 0 : -std::log(e) / std::sqrt(dem::pi * dem::pi + std::log(e) * std::log(e));
  const double wd = w0 * std::sqrt(1 - beta * beta);
  double phase = dem::pi; // w_d t*
  if (beta > 0) phase = dem::pi - std::atan(2 * beta * std::sqrt(1 - beta * beta) / (1 - 2 * beta * beta));
  const double ts = phase / wd;
  const double decay = std::exp(-beta * w0 * ts);
  const double u = v0 / wd * decay * std::sin(phase);
  const double du = v0 * decay * (std::cos(phase) - beta * w0 / wd * std::sin(phase));
  Impact c;
  c.restitution = -du / v0;
  c.duration = ts + (u > 0 ? u / -du : 0);
  return c;
}

} // namespace surge::test
