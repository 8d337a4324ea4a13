#include "surge/sph/initial_state.hpp"
#include "surge/motion/motion_law.hpp"

#include "surge/core/error.hpp"
#include "surge/geometry/mass_properties.hpp"
#include "surge/geometry/particle_generators.hpp"
#include "surge/geometry/reservoir.hpp"
#include "surge/geometry/terrain.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <tuple>

namespace surge::sph {

Real still_water_density(const Case& c, const TaitEos& eos, const FluidRegion& f, const Vec3d& p) {
  // Hydrostatic start: pressure from the depth below this region's top.
  if (!c.sph.hydrostatic_init) return static_cast<Real>(c.sph.rho0);
  return eos.density(static_cast<Real>(c.sph.rho0 * c.g() * (f.box.max.z - p.z)));
}

namespace {
// InitialState::fluid_lo / fluid_hi.
std::pair<Vec3, Vec3> fluid_region(const Case& c, const InitialState& init) {
  Vec3 lo{}, hi = Vec3(c.domain.max - c.domain.min);
  const auto half = static_cast<Real>(c.dp / 2);
  for (std::size_t i = 0; i < init.particles.size(); ++i) {
    if (init.particles.kind[i] != static_cast<std::uint8_t>(Kind::Wall)) continue;
    const Vec3 p = init.particles.pos[i];
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::fmin(lo[k], p[k] - half);
      hi[k] = std::fmax(hi[k], p[k] + half);
    }
  }
  return {lo, hi};
}
using Meshes = std::vector<std::unique_ptr<geometry::Mesh>>;

// A moving wall's pivot: a free body's centre of mass; as given; else the centre of its
// box or of its mesh's bounds.
Vec3d wall_pivot(const WallSpec& w, const geometry::Mesh* mesh) {
  if (w.body.free)
    return (mesh ? geometry::mesh_mass_properties(*mesh) : geometry::box_mass_properties(w.box)).centroid;
  return motion::law_pivot(w.motion, mesh ? geometry::bounds(*mesh) : w.box);
}

// True when pred(wall, its mesh) holds for some wall of the case.
template <class P>
bool any_wall(const Case& c, const Meshes& meshes, P&& pred) {
  for (std::size_t w = 0; w < c.walls.size(); ++w)
    if (pred(c.walls[w], meshes[w].get())) return true;
  return false;
}

// The water of region f: a box's lattice less the points a wall blocks (counted in s), or
// a reservoir filled from its seed; what was asked for is added to s.
std::vector<Vec3d> fluid_points(const Case& c, const FluidRegion& f, const Meshes& meshes, const Vec3d& lattice,
                                InitialState& s) {
  if (f.reservoir) {
    auto fill = geometry::fill_reservoir(f, c.domain, lattice, c.dp, [&](const Vec3d& p) {
      return any_wall(c, meshes, [&](const WallSpec& w, const geometry::Mesh* m) {
        return geometry::keeps_water_out(w, m, p, c.dp);
      });
    });
    if (!fill.seed_problem.empty()) throw InputError(c.source, f.line, "fluid.reservoir.seed", fill.seed_problem);
    s.reservoir_columns += fill.columns;
    s.reservoir_near_shore += fill.near_shore;
    s.fluid_volume_asked += static_cast<double>(fill.points.size()) * c.dp * c.dp * c.dp;
    s.fluid_volume_placed += static_cast<double>(fill.points.size()) * c.dp * c.dp * c.dp;
    return std::move(fill.points);
  }
  // exact: the box's own volume; lattice: centred, a box that is not a whole number of
  // spacings keeps its water in the middle (surge check reports the volume placed
  // against the volume asked for).
  s.fluid_volume_asked += f.box.volume();
  const bool exact = f.fill == "exact";
  std::vector<Vec3d> pts;
  for (const auto& p :
       geometry::fill_box(f.box, c.dp, exact ? geometry::BoxFill::Stretched : geometry::BoxFill::Centred)) {
    if (any_wall(c, meshes,
                 [&](const WallSpec& w, const geometry::Mesh* m) { return geometry::blocked_by(w, m, p, c.dp); }))
      ++s.fluid_dropped_by_walls;
    else
      pts.push_back(p);
  }
  const double cell = exact ? geometry::stretched_cell_volume(f.box, c.dp) : c.dp * c.dp * c.dp;
  s.fluid_volume_placed += static_cast<double>(pts.size()) * cell;
  return pts;
}
} // namespace

InitialState build_initial_state(const Case& c) {
  InitialState s;
  s.origin = c.domain.min;
  const int layers = geometry::wall_layers(c);
  Meshes meshes;
  for (const auto& w : c.walls)
    meshes.push_back(w.is_mesh
                         ? std::make_unique<geometry::Mesh>(geometry::load_surface(w.mesh_path, w.terrain, c.domain))
                         : nullptr);

  const double rho0 = c.sph.rho0;
  const TaitEos eos(static_cast<Real>(rho0), static_cast<Real>(c.sound_speed()));
  std::uint32_t next_id = 0;
  auto local = [&](const Vec3d& p) { return Vec3(p - s.origin); };
  const Vec3d lattice = geometry::lattice_origin(c); // the domain's corner without reservoirs
  for (const auto& f : c.fluid) {
    if (f.given()) { // as given: no wall test (the table is the user's state)
      for (std::size_t k = 0; k < f.given_pos.size(); ++k) {
        const Vec3d& p = f.given_pos[k];
        const Real rho = f.given_rho[k] > 0 ? static_cast<Real>(f.given_rho[k]) : still_water_density(c, eos, f, p);
        s.particles.push(local(p), Vec3(f.given_vel[k]), rho, Kind::Fluid, next_id++);
      }
      s.n_fluid += f.given_pos.size();
      s.fluid_volume_asked += static_cast<double>(f.given_pos.size()) * c.dp * c.dp * c.dp;
      s.fluid_volume_placed += static_cast<double>(f.given_pos.size()) * c.dp * c.dp * c.dp;
      continue;
    }
    for (const auto& p : fluid_points(c, f, meshes, lattice, s)) {
      s.particles.push(local(p), Vec3(f.velocity), still_water_density(c, eos, f, p), Kind::Fluid, next_id++);
      ++s.n_fluid;
    }
  }
  // One mass for every SPH particle: the water placed over the fluid particles (a single
  // exact box: its stretched cell exactly; boxes of several spacings: their mean).
  const bool exact = std::any_of(c.fluid.begin(), c.fluid.end(),
                                 [](const FluidRegion& f) { return !f.reservoir && !f.given() && f.fill == "exact"; });
  if (exact && s.n_fluid > 0) s.particle_mass = rho0 * s.fluid_volume_placed / static_cast<double>(s.n_fluid);
  s.first_boundary_id = next_id;
  for (std::size_t w = 0; w < c.walls.size(); ++w) {
    const auto& ws = c.walls[w];
    // The dynamic boundary keeps the solid box's unstretched lattice: with the stretched one
    // SPHERIC at 3 cm lost 193 particles for density at 0.95-1.0 s (none before,
    // docs/validation.md).
    const bool fit = c.sph.boundary == "mdbc";
    // A terrain's layers under the domain only: its hills may rise far above it.
    Box under = c.domain;
    under.min.z -= layers * c.dp;
    const auto pts = ws.is_mesh ? geometry::mesh_wall(*meshes[w], lattice, c.dp, layers, ws.terrain ? &under : nullptr)
                                : geometry::box_wall(ws, c.dp, layers, fit);
    const std::uint32_t first = next_id;
    for (const auto& p : pts) {
      s.particles.push(local(p), Vec3{}, static_cast<Real>(rho0), Kind::Wall, next_id++);
      const Vec3d mirror = geometry::ghost_point(ws, meshes[w].get(), p) - p;
      s.boundary_ghost.push_back(Vec3(mirror));
      const auto reach = geometry::wall_reach(ws, meshes[w].get(), p, mirror, c.dp, fit);
      std::int32_t extra = -1;
      if (!reach.faces.empty()) {
        extra = static_cast<std::int32_t>(4 * s.extra_faces.size() + reach.faces.size());
        for (const auto& o : reach.faces) s.extra_faces.push_back(Vec3(o));
      }
      s.wall_reach.push_back({static_cast<Real>(reach.patch), static_cast<Real>(reach.sphere), extra});
    }
    s.wall_ids.emplace_back(first, next_id);
    if (ws.moves()) s.moving.push_back({first, next_id, w, wall_pivot(ws, meshes[w].get())});
    s.n_wall += pts.size();
  }
  if (c.fluid.size() > 0 && s.n_fluid == 0)
    throw InputError(c.source, c.fluid.front().line, "fluid",
                     "every fluid particle lies inside a wall; check the walls and the fluid boxes");
  if (s.particles.size() > 2'000'000'000ULL)
    throw InputError(c.source, 0, "dp", "more than 2e9 particles; increase dp");
  std::tie(s.fluid_lo, s.fluid_hi) = fluid_region(c, s);
  s.domain_hi = Vec3(c.domain.max - c.domain.min);
  for (std::size_t k = 0; k < 3; ++k) s.periodic[k] = c.periodic[k] ? 1 : 0;
  for (std::size_t f = 0; f < 6; ++f) s.symmetry[f] = c.symmetry[f] ? 1 : 0;
  return s;
}

} // namespace surge::sph
