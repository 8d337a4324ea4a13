// What the SPH solver needs of a case, typed: the case file's words become enums and
// model entries here, once, and the solver never sees the Case.
#pragma once
#include "surge/core/case.hpp"
#include "surge/sph/boundary/boundary_model.hpp"
#include "surge/sph/damping.hpp"
#include "surge/sph/sps_turbulence.hpp"
#include "surge/sph/wcsph_rates.hpp"

namespace surge::sph {

enum class Integrator { Verlet, Symplectic };

struct SolverConfig {
  WcsphParams prm; // kernel, EOS, particle mass, dp, viscosity, diffusion (and its variant), gravity
  Integrator integrator = Integrator::Verlet;
  const BoundaryModelInfo* boundary = nullptr; // sph.boundary (never null after solver_config)
  bool no_penetration = true;                  // sph.no_penetration
  double cfl = 0.2;
  int euler_every = 10;          // Verlet: an Euler step every this many steps
  Real rho_min = 0, rho_max = 0; // removal bounds [kg/m^3]
  DampingZones damping;          // case damping, in local coordinates (domain min at 0)
  SpsParams sps;                 // prm.viscosity LaminarSps: the SPS pass's constants
};

// The solver's configuration of case c (SPEC §2: h, c0, m = rho0 dp^3, ...).
SolverConfig solver_config(const Case& c);

} // namespace surge::sph
