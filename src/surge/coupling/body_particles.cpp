#include "surge/coupling/body_particles.hpp"

#include "surge/dem/rigid_state.hpp"
#include "surge/sph/eos_tait.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

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

namespace {
// Spheres by coarse cell, to find the spheres near a fluid particle quickly.
struct SphereHash {
  double cell;
  std::unordered_map<long long, std::vector<int>> cells;
  static long long key(long long i, long long j, long long k) {
    return (i * 73856093LL) ^ (j * 19349663LL) ^ (k * 83492791LL);
  }
  [[nodiscard]] long long idx(double v) const { return static_cast<long long>(std::floor(v / cell)); }
};
} // namespace

BodySetup add_body_particles(const Case& c, const std::vector<dem::Sphere>& spheres, int layers,
                             sph::InitialState& init) {
  BodySetup out;
  auto& hp = init.particles;
  // 1. Water out of the spheres: fluid centres inside a sphere are removed, so the
  // water starts with the sphere's volume excluded (one fluid particle per dp^3 cell).
  double rmax = 0;
  for (const auto& s : spheres) rmax = std::max(rmax, static_cast<double>(s.radius));
  SphereHash hash{std::max(2 * rmax, 1e-9), {}};
  for (std::size_t k = 0; k < spheres.size(); ++k) {
    const Vec3d x(spheres[k].pos);
    hash.cells[SphereHash::key(hash.idx(x.x), hash.idx(x.y), hash.idx(x.z))].push_back(static_cast<int>(k));
  }
  auto inside = [&](const Vec3& p) {
    const Vec3d x(p);
    const long long i0 = hash.idx(x.x), j0 = hash.idx(x.y), k0 = hash.idx(x.z);
    for (long long i = i0 - 1; i <= i0 + 1; ++i)
      for (long long j = j0 - 1; j <= j0 + 1; ++j)
        for (long long k = k0 - 1; k <= k0 + 1; ++k) {
          const auto it = hash.cells.find(SphereHash::key(i, j, k));
          if (it == hash.cells.end()) continue;
          for (int s : it->second) {
            const Vec3d d = x - Vec3d(spheres[static_cast<std::size_t>(s)].pos);
            const double r = spheres[static_cast<std::size_t>(s)].radius;
            if (dot(d, d) < r * r) return true;
          }
        }
    return false;
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

  // 2. Body particles, ids after every existing one.
  std::uint32_t next_id = 0;
  for (auto id : hp.id) next_id = std::max(next_id, id + 1);
  BodyLayout& L = out.layout;
  L.first_id = next_id;
  const double rho0 = c.sph.rho0, g = c.g();
  const sph::TaitEos eos(static_cast<Real>(rho0), static_cast<Real>(c.sound_speed()));
  for (std::size_t k = 0; k < spheres.size(); ++k) {
    L.start.push_back(static_cast<std::uint32_t>(L.offset.size()));
    dem::RigidState st;
    st.pos = spheres[k].pos;
    st.vel = spheres[k].vel;
    st.omega = spheres[k].omega;
    for (const auto& o : body_offsets(spheres[k].radius, c.dp, layers)) {
      const Vec3 off(o);
      const dem::RigidPoint p = dem::rigid_point(st, off);
      const Vec3d abs = Vec3d(p.pos) + init.origin;
      auto rho = static_cast<Real>(rho0);
      if (c.sph.hydrostatic_init)
        for (const auto& f : c.fluid)
          if (f.box.contains(abs)) rho = eos.density(static_cast<Real>(rho0 * g * (f.box.max.z - abs.z)));
      hp.push(p.pos, p.vel, rho, Kind::Body, next_id++);
      L.offset.push_back(off);
      L.owner.push_back(static_cast<std::uint32_t>(k));
    }
  }
  L.start.push_back(static_cast<std::uint32_t>(L.offset.size()));
  return out;
}

} // namespace surge::coupling
