#include "surge/coupling/body_particles.hpp"

#include "surge/dem/rigid_state.hpp"
#include "surge/domain/periodic.hpp"
#include "surge/geometry/sphere_index.hpp"
#include "surge/sph/eos_tait.hpp"

#include <algorithm>
#include <cmath>

namespace surge::coupling {

int default_layers(double h, double dp) { return std::max(1, static_cast<int>(std::ceil(2 * h / dp - 1e-9))); }

std::vector<Vec3d> body_offsets(double radius, double dp, int layers) {
  std::vector<Vec3d> out;
  const double golden = dem::pi * (3.0 - std::sqrt(5.0));
  for (int k = 0; k < layers; ++k) {
    const double rk = radius - (k + 0.5) * dp;
    if (rk <= 0.5 * dp + 1e-12 * dp) {
      out.push_back({0, 0, 0});
      break;
    }
    const int n = std::max(4, static_cast<int>(std::lround(4 * dem::pi * rk * rk / (dp * dp))));
    for (int i = 0; i < n; ++i) {
      const double z = 1.0 - (2.0 * i + 1.0) / n;
      const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
      const double phi = golden * i;
      out.push_back(Vec3d{s * std::cos(phi), s * std::sin(phi), z} * rk);
    }
  }
  return out;
}

BodySetup add_body_particles(const Case& c, const std::vector<dem::Sphere>& spheres, int layers,
                             sph::InitialState& init) {
  BodySetup out;
  auto& hp = init.particles;
  // 1. Water out of the spheres: fluid centres inside a sphere are removed, so the
  // water starts with the sphere's volume excluded (one fluid particle per dp^3 cell).
  double rmax = 0;
  for (const auto& s : spheres) rmax = std::max(rmax, static_cast<double>(s.radius));
  geometry::SphereIndex index(std::max(2 * rmax, 1e-9));
  for (std::size_t k = 0; k < spheres.size(); ++k) index.add(static_cast<int>(k), Vec3d(spheres[k].pos));
  // (On periodic axes a sphere at one face holds water at the other: each point is
  // tested with its images a period away too.)
  const domain::PeriodicAxes per = domain::periodic_axes(c);
  auto inside_at = [&](const Vec3d& x) {
    return index.any_near(x, [&](int s) {
      const Vec3d d = x - Vec3d(spheres[static_cast<std::size_t>(s)].pos);
      const double r = spheres[static_cast<std::size_t>(s)].radius;
      return dot(d, d) < r * r;
    });
  };
  auto inside = [&](const Vec3& p) {
    bool in = false;
    for (int sz = -per.on[2]; sz <= per.on[2]; ++sz)
      for (int sy = -per.on[1]; sy <= per.on[1]; ++sy)
        for (int sx = -per.on[0]; sx <= per.on[0]; ++sx)
          in =
              in || inside_at(Vec3d(p) + Vec3d(sx * static_cast<double>(per.len.x), sy * static_cast<double>(per.len.y),
                                               sz * static_cast<double>(per.len.z)));
    return in;
  };
  particles::HostParticles kept;
  const auto fluid = static_cast<std::uint8_t>(Kind::Fluid);
  for (std::size_t i = 0; i < hp.size(); ++i) {
    if (hp.kind[i] == fluid && inside(hp.pos[i])) {
      ++out.fluid_removed;
      continue;
    }
    kept.push(hp.pos[i], hp.vel[i], hp.rho[i], static_cast<Kind>(hp.kind[i]), hp.id[i]);
  }
  init.n_fluid -= out.fluid_removed;
  hp = std::move(kept);

  // 2. Body particles, ids after every existing one: the boundary ids continue.
  auto next_id = static_cast<std::uint32_t>(init.first_boundary_id + init.boundary_ghost.size());
  for (auto id : hp.id) next_id = std::max(next_id, id + 1);
  BodyLayout& L = out.layout;
  L.first_id = next_id;
  const sph::TaitEos eos(static_cast<Real>(c.sph.rho0), static_cast<Real>(c.sound_speed()));
  for (std::size_t k = 0; k < spheres.size(); ++k) {
    L.start.push_back(static_cast<std::uint32_t>(L.offset.size()));
    dem::RigidState st;
    st.pos = spheres[k].pos;
    st.vel = spheres[k].vel;
    st.omega = spheres[k].omega;
    for (const auto& o : body_offsets(spheres[k].radius, c.dp, layers)) {
      const Vec3 off(o);
      dem::RigidPoint p = dem::rigid_point(st, off);
      per.wrap(p.pos); // in the domain, as SphDemCoupling::place_bodies puts it
      const Vec3d abs = Vec3d(p.pos) + init.origin;
      auto rho = static_cast<Real>(c.sph.rho0);
      for (const auto& f : c.fluid)
        if (f.box.contains(abs)) rho = sph::still_water_density(c, eos, f, abs);
      hp.push(p.pos, p.vel, rho, Kind::Body, next_id++);
      L.offset.push_back(off);
      // mDBC ghost node: mirrored through the sphere's surface, r -> 2R - r along the offset.
      const double r = norm(o);
      const Vec3 ghost = r > 0 ? Vec3(o * (2 * (static_cast<double>(spheres[k].radius) - r) / r)) : Vec3{};
      L.ghost.push_back(ghost);
      init.boundary_ghost.push_back(dem::rotate(st.q, ghost));
      L.owner.push_back(static_cast<std::uint32_t>(k));
    }
  }
  L.start.push_back(static_cast<std::uint32_t>(L.offset.size()));
  return out;
}

} // namespace surge::coupling
