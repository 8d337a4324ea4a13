#include "surge/sph/solver_config.hpp"

namespace surge::sph {

SolverConfig solver_config(const Case& c) {
  SolverConfig s;
  WcsphParams& p = s.prm;
  p.kernel = WendlandC2(static_cast<Real>(c.h()));
  p.eos = TaitEos(static_cast<Real>(c.sph.rho0), static_cast<Real>(c.sound_speed()));
  p.mass = static_cast<Real>(c.sph.rho0 * c.dp * c.dp * c.dp);
  p.dp = static_cast<Real>(c.dp);
  p.alpha = static_cast<Real>(c.sph.alpha);
  p.viscosity = c.sph.viscosity == "laminar"       ? Viscosity::Laminar
                : c.sph.viscosity == "laminar_sps" ? Viscosity::LaminarSps
                                                   : Viscosity::Artificial;
  s.sps = {static_cast<Real>(c.sph.sps_smagorinsky), static_cast<Real>(c.sph.sps_blin), p.dp};
  p.nu = static_cast<Real>(c.sph.nu);
  if (c.sph.shifting != "none") p.shift.coefficient = static_cast<Real>(c.sph.shifting_coefficient);
  if (c.sph.shifting == "delta_plus") { // Sun et al. 2017: CFL Ma (2h)^2 = 4 h (Ma c0) dt
    p.shift.speed = static_cast<Real>(c.sph.shifting_mach) * p.eos.c0;
    p.shift.clump = Real(0.2);
    p.shift.inv_w_dp = 1 / p.kernel.w(p.dp);
  }
  p.shift.surface = static_cast<Real>(c.sph.free_surface);
  p.delta = static_cast<Real>(c.sph.delta);
  p.gravity = Vec3(c.gravity);
  p.fourtakas = c.sph.diffusion == "fourtakas";
  s.integrator = c.sph.integrator == "symplectic" ? Integrator::Symplectic : Integrator::Verlet;
  s.boundary = &boundary_model(c.sph.boundary);
  s.no_penetration = c.sph.no_penetration;
  s.cfl = c.sph.cfl;
  s.euler_every = c.sph.euler_every;
  s.rho_min = static_cast<Real>(c.sph.rho_min * c.sph.rho0);
  s.rho_max = static_cast<Real>(c.sph.rho_max * c.sph.rho0);
  for (const DampingSpec& d : c.damping) {
    DampingZone& z = s.damping.zone[s.damping.n++];
    const int f = static_cast<int>(d.face);
    z.axis = f / 2;
    const double extent = c.domain.max[z.axis] - c.domain.min[z.axis];
    const bool hi = f % 2 == 1; // xmax, ymax, zmax: the zone lies below the face
    z.inner = static_cast<Real>(hi ? extent - d.length : d.length);
    z.length = static_cast<Real>(hi ? d.length : -d.length);
    z.rate = static_cast<Real>(d.rate);
  }
  return s;
}

} // namespace surge::sph
