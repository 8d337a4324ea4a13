#include "surge/sim/dem_setup.hpp"
#include "surge/sim/moving_bodies.hpp"

#include "surge/core/error.hpp"
#include "surge/geometry/slide_body.hpp"
#include "surge/geometry/sphere_packs.hpp"
#include "surge/geometry/stl_mesh.hpp"
#include "surge/geometry/terrain.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace surge::sim {

namespace {
// A DEM solver for the case's walls, periodic and symmetry faces, with the given local
// damping and spheres; a sphere set the faces cannot take (a period too short for it, a
// sphere across a symmetry face) is an input error at `line` and `key`.
dem::DemSolver solver_for(const Case& c, const DemSetup& s, Real damping, const std::vector<dem::Sphere>& spheres,
                          int line, const char* key) {
  const Vec3 hi(c.domain.max - c.domain.min);
  dem::DemSolver solver(s.materials, s.planes, Vec3(c.gravity), Vec3{}, hi, s.contact_law);
  solver.set_periodic(domain::periodic_axes(c));
  solver.set_symmetry(c.symmetry);
  solver.set_wall_triangles(s.triangles);
  solver.set_local_damping(damping);
  try {
    solver.set_spheres(spheres);
  } catch (const std::invalid_argument& e) { throw InputError(c.source, line, key, e.what()); }
  return solver;
}

// Lets a pack fall and come to rest under gravity against the case's DEM walls (its own
// spheres only, Cundall local damping 0.7) for pk.settle seconds (SPEC §3: local damping
// "useful to settle a pack"). Returns the settled centres (absolute).
std::vector<geometry::SphereSpec> settle_pack(const Case& c, const DemSetup& s, const DemPackSpec& pk,
                                              const std::vector<geometry::SphereSpec>& list) {
  if (list.empty()) return list;
  std::vector<dem::Sphere> spheres;
  spheres.reserve(list.size());
  for (const auto& sp : list)
    spheres.push_back({Vec3(sp.centre - s.origin), Vec3{}, Vec3{}, static_cast<Real>(sp.radius), pk.material, false});
  dem::DemSolver solver = solver_for(c, s, Real(0.7), spheres, pk.line, "dem.packs");
  const Real dt = solver.critical_dt(static_cast<Real>(c.dem.dt_factor));
  const long steps = static_cast<long>(std::ceil(pk.settle / static_cast<double>(dt)));
  for (long k = 0; k < steps; ++k) solver.step(dt);
  std::vector<geometry::SphereSpec> out;
  for (const auto& sp : solver.spheres()) {
    const Vec3d x = Vec3d(sp.pos) + s.origin;
    if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z))
      throw InputError(c.source, pk.line, "dem.packs.settle",
                       "settling the pack diverged; check its walls and dt_factor");
    out.push_back({x, static_cast<double>(sp.radius)});
  }
  return out;
}
// The slide's spheres must lie above the ground of every DEM terrain wall: the walls must
// be the ground beneath the slide; spheres under a terrain wall (the pre-failure ground
// given as the wall) would be thrown out of it at the first step.
void check_slide_above_walls(const Case& c, const DemPackSpec& pk, const std::vector<geometry::SphereSpec>& list) {
  for (const auto& w : c.dem.walls) {
    if (!w.terrain) continue;
    const auto ground = geometry::read_terrain(w.mesh_path, c.domain);
    long under = 0;
    for (const auto& sp : list)
      under += sp.centre.z < geometry::surface_height(ground, sp.centre.x, sp.centre.y) ? 1 : 0;
    if (under > 0)
      throw InputError(c.source, pk.line, "dem.packs.between",
                       std::to_string(under) + " of the slide's spheres lie under the ground of the DEM wall '" +
                           w.mesh_path +
                           "': the walls must be the ground beneath the slide (its sliding surface), not the "
                           "pre-failure ground");
  }
}
// A lattice pack of the region, or a random one of pk.random_count spheres (all of them
// placed, or an error).
std::vector<geometry::SphereSpec> region_pack(const Case& c, const DemPackSpec& pk,
                                              const geometry::PackRegion& region) {
  if (pk.random_count == 0) return geometry::lattice_pack(region, pk.radius, pk.jitter);
  auto list = geometry::random_pack(region, pk.radius, pk.random_count);
  if (static_cast<long>(list.size()) < pk.random_count)
    throw InputError(c.source, pk.line, "dem.packs",
                     "only " + std::to_string(list.size()) + " of " + std::to_string(pk.random_count) +
                         " spheres of radius " + std::to_string(pk.radius) +
                         " fit in the pack's region at random; lower 'random' or enlarge the region");
  return list;
}
// A slide body between two grids (geometry/slide_body.hpp): columns of the lattice, or a
// random pack of the space between.
geometry::SlideBody slide_pack(const Case& c, const DemPackSpec& pk) {
  const auto top = geometry::read_terrain(pk.top_path, c.domain),
             bottom = geometry::read_terrain(pk.bottom_path, c.domain);
  geometry::SlideBody body;
  if (pk.random_count > 0) {
    body.volume = geometry::slide_volume(top, bottom, pk.bottom_path);
    body.spheres = region_pack(c, pk, geometry::slide_region(top, bottom));
  } else {
    // Bonded: columns on the lattice's levels, so that neighbours touch and bond (SPEC 3.4).
    const bool aligned = c.dem.materials[static_cast<std::size_t>(pk.material)].bonded;
    body = geometry::fill_slide(top, bottom, pk.radius, c.domain.min, pk.bottom_path, pk.jitter, aligned);
  }
  if (body.spheres.empty())
    throw InputError(c.source, pk.line, "dem.packs.between",
                     "no sphere of this radius fits between the surfaces; use smaller spheres");
  check_slide_above_walls(c, pk, body.spheres);
  return body;
}
// The spheres of pack pk (absolute centres), radii drawn and settled as it asks; a slide's
// report goes to s.slides.
std::vector<geometry::SphereSpec> pack_spheres(const Case& c, const DemPackSpec& pk, DemSetup& s) {
  std::vector<geometry::SphereSpec> list;
  double slide_volume = -1;
  if (pk.from_csv) {
    list = geometry::read_sphere_csv(pk.csv);
  } else if (!pk.bottom_path.empty()) {
    auto body = slide_pack(c, pk);
    list = std::move(body.spheres);
    slide_volume = body.volume;
  } else if (!pk.mesh_path.empty()) {
    const geometry::Mesh mesh = geometry::read_stl(pk.mesh_path);
    if (mesh.tris.empty()) throw InputError(pk.mesh_path, 0, "", "the mesh has no triangles");
    geometry::PackRegion region{{mesh.tris[0].a, mesh.tris[0].a}, &mesh};
    for (const auto& t : mesh.tris)
      for (const Vec3d& v : {t.a, t.b, t.c})
        for (int k = 0; k < 3; ++k) {
          region.box.min[k] = std::min(region.box.min[k], v[k]);
          region.box.max[k] = std::max(region.box.max[k], v[k]);
        }
    list = region_pack(c, pk, region);
  } else {
    list = region_pack(c, pk, geometry::PackRegion{pk.box, nullptr});
  }
  if (pk.radius_range()) geometry::draw_radii(list, pk.radius_min, pk.radius);
  if (slide_volume >= 0)
    s.slides.push_back({static_cast<int>(&pk - c.dem.packs.data()), slide_volume, list.size(), pk.radius,
                        geometry::solid_volume(list)});
  if (pk.settle > 0) list = settle_pack(c, s, pk, list);
  return list;
}
// The case's contact law, and every material suits it (Hertz-Mindlin: Poisson's ratio
// below 0.5, no bonds; the linear spring: a positive stiffness ratio).
void check_contact_law(const Case& c, DemSetup& s) {
  s.contact_law = dem::contact_law_index(c.dem.contact);
  if (s.contact_law < 0) throw InputError(c.source, 0, "dem.contact", "unknown contact law '" + c.dem.contact + "'");
  for (std::size_t k = 0; k < s.materials.size(); ++k) {
    const char* key = "";
    if (const char* why = dem::unsuitable_material(s.contact_law, s.materials[k], &key))
      throw InputError(c.source, c.dem.materials[k].line, "dem.materials." + std::to_string(k) + "." + key, why);
  }
}
} // namespace

DemSetup dem_setup(const Case& c) {
  DemSetup s;
  s.origin = c.domain.min;
  auto local = [&](const Vec3d& p) { return Vec3(p - s.origin); };
  for (const auto& m : c.dem.materials) {
    dem::Material mt;
    mt.density = static_cast<Real>(m.density);
    mt.young = static_cast<Real>(m.young);
    mt.nu = static_cast<Real>(m.nu);
    mt.tan_phi = static_cast<Real>(std::tan(m.phi_deg * dem::pi / 180.0));
    mt.restitution = static_cast<Real>(m.restitution);
    mt.k_roll = static_cast<Real>(m.k_roll);
    mt.k_roll_max = static_cast<Real>(m.k_roll_max);
    mt.k_twist = static_cast<Real>(m.k_twist);
    mt.k_twist_max = static_cast<Real>(m.k_twist_max);
    mt.bonded = m.bonded;
    mt.bond_cn = static_cast<Real>(m.bond_cn);
    mt.bond_cs = static_cast<Real>(m.bond_cs);
    s.bonded = s.bonded || m.bonded;
    s.materials.push_back(mt);
  }
  check_contact_law(c, s);
  int mesh_index = 0;
  for (std::size_t k = 0; k < c.dem.walls.size(); ++k) {
    const DemWallSpec& w = c.dem.walls[k];
    const int body = dem_wall_body(c, k); // moving walls: their body (sim/moving_bodies.hpp)
    if (!w.is_mesh) {
      s.wall_index.emplace_back(static_cast<int>(s.planes.size()), -1);
      s.planes.push_back({local(w.point), Vec3(w.normal * (1.0 / norm(w.normal))), w.material, body});
      continue;
    }
    s.wall_index.emplace_back(-1, mesh_index);
    for (const auto& t : geometry::load_surface(w.mesh_path, w.terrain, c.domain).tris)
      s.triangles.push_back({local(t.a), local(t.b), local(t.c), mesh_index, w.material, body});
    ++mesh_index;
  }
  for (const auto& pk : c.dem.packs) {
    const auto list = pack_spheres(c, pk, s);
    for (const auto& sp : list) {
      if (!c.domain.contains(sp.centre))
        throw InputError(c.source, pk.line, "dem.packs",
                         "a sphere at (" + std::to_string(sp.centre.x) + ", " + std::to_string(sp.centre.y) + ", " +
                             std::to_string(sp.centre.z) + ") lies outside the domain");
      s.spheres.push_back(
          {local(sp.centre), Vec3(pk.velocity), Vec3{}, static_cast<Real>(sp.radius), pk.material, pk.fixed});
    }
  }
  if (s.spheres.empty())
    throw InputError(c.source, 0, "dem.packs", "the packs hold no sphere (box smaller than a sphere?)");
  return s;
}

void print_slides(const Case& c, const DemSetup& s) {
  for (const auto& sl : s.slides) {
    const auto& pk = c.dem.packs[static_cast<std::size_t>(sl.pack)];
    const double n = static_cast<double>(sl.spheres), d = 2 * sl.radius;
    const double rho = c.dem.materials[static_cast<std::size_t>(pk.material)].density;
    char sizes[64];
    if (pk.radius_range())
      std::snprintf(sizes, sizeof sizes, "D = %g..%g m", 2 * pk.radius_min, d);
    else
      std::snprintf(sizes, sizeof sizes, "D = %g m", d);
    std::printf("slide       pack %d (line %d): %.6g m^3 between the grids; %zu spheres of %s", sl.pack, pk.line,
                sl.volume, sl.spheres, sizes);
    if (pk.random_count == 0) {
      const double cells = n * d * d * d;
      std::printf(" whose lattice cells hold %.6g m^3 (%.1f %%)", cells, 100 * cells / sl.volume);
    }
    std::printf("; mass %.6g kg (spheres of %g kg/m^3, %.3g of the body's volume)\n", sl.solid * rho, rho,
                sl.solid / sl.volume);
    if (pk.settle > 0) std::printf("            (as placed; settled for %g s before the run)\n", pk.settle);
    if (c.dp > 0 && !c.fluid.empty())
      std::printf("            dp/D = 1/%.3g (the paper's guidance for dense assemblies: dp <= D/6, D/8 better)\n",
                  d / c.dp);
  }
}

std::string no_bonds_warning(const Case& c, const DemSetup& s, long bonds) {
  if (!s.bonded || bonds > 0) return "";
  return "bonded materials, but no two of their spheres touch at the start (within dem.bond_gap = " +
         std::to_string(c.dem.bond_gap) +
         " m): jitter, radius_min or a random pack leave gaps; settle the pack first (a wider bond_gap bonds across "
         "gaps, and such a bond starts in tension)";
}

std::string dem_step_warning(const Case& c, const dem::DemSolver& solver) {
  constexpr double largest_factor = 0.2;
  if (!(c.dem.dt_factor > largest_factor)) return "";
  char b[256];
  std::snprintf(b, sizeof b,
                "dem.dt_factor %g: the DEM step %.3g s is above %.3g s, %g times the contact law's time scale, the "
                "largest its guidance allows",
                c.dem.dt_factor, static_cast<double>(solver.critical_dt(static_cast<Real>(c.dem.dt_factor))),
                static_cast<double>(solver.critical_dt(static_cast<Real>(largest_factor))), largest_factor);
  return b;
}

dem::DemSolver make_dem_solver(const Case& c, const DemSetup& s) {
  return solver_for(c, s, static_cast<Real>(c.dem.local_damping), s.spheres, 0,
                    c.any_symmetry() ? "domain.symmetry" : "domain.periodic");
}

io::SphereFrame sphere_frame(const dem::DemSolver& solver) {
  io::SphereFrame f;
  const auto sp = solver.spheres();
  for (const auto& s : sp) {
    Vec3 x = s.pos;
    solver.periodic().wrap(x); // shown where it is, not up to half a period beyond a face
    f.pos.push_back(x);
    f.vel.push_back(s.vel);
    f.omega.push_back(s.omega);
    f.radius.push_back(s.radius);
    f.material.push_back(static_cast<std::uint8_t>(s.material));
  }
  f.contacts = solver.contact_counts();
  f.bonds = solver.intact_bonds();
  for (std::size_t k = 0; k < sp.size(); ++k) f.id.push_back(static_cast<std::uint32_t>(k));
  return f;
}

void DemWallFrames::write(const dem::DemSolver& solver, int frame, double t, const Vec3d& origin) {
  if (!on_) return;
  io::write_triangles_vtp(series_.path(frame), solver.moving_triangles(), origin);
  series_.add(frame, t);
}

double dem_wall_gauge_value(const GaugeSpec& g, const Case& c, const DemSetup& s, dem::DemSolver& solver) {
  for (std::size_t w = 0; w < c.dem.walls.size(); ++w) {
    if (c.dem.walls[w].name != g.wall) continue;
    const auto [plane, mesh] = s.wall_index[w];
    const dem::WallLoad l = solver.wall_load(plane, mesh, Vec3(g.about - s.origin));
    const int a = g.component[1] == 'x' ? 0 : g.component[1] == 'y' ? 1 : 2;
    return static_cast<double>(g.component[0] == 'f' ? l.force[a] : l.moment[a]);
  }
  return 0.0;
}

void check_sphere_gauges(const Case& c, std::size_t n_spheres) {
  for (const auto& g : c.gauges)
    if (g.type == GaugeType::Sphere && static_cast<std::size_t>(g.sphere) >= n_spheres)
      throw InputError(c.source, g.line, "gauges." + g.name + ".sphere",
                       "sphere " + std::to_string(g.sphere) + " does not exist: the packs hold " +
                           std::to_string(n_spheres) + " spheres (numbered from 0)");
}

double sphere_gauge_value(const GaugeSpec& g, const std::vector<dem::Sphere>& spheres,
                          const std::vector<Vec3>& fluid_force, const std::vector<Vec3>& fluid_moment,
                          const Vec3d& origin) {
  const auto k = static_cast<std::size_t>(g.sphere);
  const char axis = g.component.back();
  const int a = axis == 'x' ? 0 : axis == 'y' ? 1 : 2;
  if (g.component.size() == 1) return origin[a] + static_cast<double>(spheres[k].pos[a]);
  if (g.component[0] == 'v') return spheres[k].vel[a];
  const std::vector<Vec3>& f = g.component[0] == 'f' ? fluid_force : fluid_moment;
  return k < f.size() ? static_cast<double>(f[k][a]) : 0.0;
}

DemGauges::DemGauges(const Case& c, const DemSetup& s, dem::DemSolver& solver, const MovingBodies& bodies, bool water)
    : c_(&c), setup_(&s), solver_(&solver), bodies_(&bodies), spheres_(solver.spheres()) {
  if (!water) return;
  force_ = solver.external_forces();
  moment_ = solver.external_torques();
}

double DemGauges::value(const GaugeSpec& g, double t) const {
  switch (g.type) {
  case GaugeType::DemWall:
    return dem_wall_gauge_value(g, *c_, *setup_, *solver_);
  case GaugeType::Body:
    return bodies_->dem_gauge_value(g, t);
  default:
    return sphere_gauge_value(g, spheres_, force_, moment_, setup_->origin);
  }
}

CoupledParts::CoupledParts(const Case& c, sph::InitialState& init) : setup(dem_setup(c)) {
  check_sphere_gauges(c, setup.spheres.size());
  layers = c.coupling.body_layers > 0 ? c.coupling.body_layers : coupling::default_layers(c.h(), c.dp);
  auto body = coupling::add_body_particles(c, setup.spheres, layers, init);
  fluid_removed = body.fluid_removed;
  dem = std::make_unique<dem::DemSolver>(make_dem_solver(c, setup));
  if (setup.bonded) bonds = dem->bond_touching(static_cast<Real>(c.dem.bond_gap));
  const Real dt_dem = dem->critical_dt(static_cast<Real>(c.dem.dt_factor));
  coupling = std::make_unique<coupling::SphDemCoupling>(body.layout, static_cast<int>(setup.spheres.size()), dt_dem);
}

} // namespace surge::sim
