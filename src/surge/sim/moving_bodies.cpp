#include "surge/sim/moving_bodies.hpp"

#include "surge/core/error.hpp"
#include "surge/geometry/mass_properties.hpp"
#include "surge/geometry/particle_generators.hpp"
#include "surge/geometry/terrain.hpp"
#include "surge/motion/body_reading.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

namespace surge::sim {

namespace {
// A moving wall's particles as placed (absolute): a free body's points that bound it
// wherever it turns (for a DEM wall, its mesh's vertices), and a law's box (bounds).
std::vector<Vec3d> wall_points(const sph::InitialState& init, const sph::MovingWall& m) {
  std::vector<Vec3d> p;
  for (std::uint32_t id = m.first; id < m.last; ++id) p.push_back(Vec3d(init.particles.pos[id]) + init.origin);
  return p;
}

// The bounding box of points.
Box bounds(const std::vector<Vec3d>& points) {
  Box b{{1e300, 1e300, 1e300}, {-1e300, -1e300, -1e300}};
  for (const Vec3d& x : points) {
    for (int k = 0; k < 3; ++k) {
      b.min[k] = std::min(b.min[k], x[k]);
      b.max[k] = std::max(b.max[k], x[k]);
    }
  }
  return b;
}

// Where a moving wall's motion is checked: its name, the key of its motion, the pivot and
// the box it fills as placed, and the region it must stay in.
struct Extent {
  std::string name, key;
  int line = 0;
  Vec3d pivot{};
  Box placed, region;
};

// Where the point x lies outside `region` (beyond it the grid clamps and nothing is
// tested): "AXIS in [LO, HI] m ... AXIS = X m"; empty if inside.
std::string outside(const Vec3d& x, const Box& region) {
  const char* axes = "xyz";
  for (int k = 0; k < 3; ++k) {
    if (x[k] >= region.min[k] - 1e-9 && x[k] <= region.max[k] + 1e-9) continue;
    char b[160];
    std::snprintf(b, sizeof b, "%c in [%.4g, %.4g] m, where a point of it reaches %c = %.4g m", axes[k], region.min[k],
                  region.max[k], axes[k], x[k]);
    return b;
  }
  return {};
}

// Refuses a motion that takes any corner of the wall's box out of its region at one of
// 2,000 times from 0 to `end` or at `end`.
void check_stays_inside(const Case& c, const motion::Motion& mo, const Extent& e) {
  const int n = 2000;
  for (int s = 0; s <= n; ++s) {
    const double t = c.time.end * s / n;
    const motion::Pose p = mo.at(t);
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3d x0{corner & 1 ? e.placed.max.x : e.placed.min.x, corner & 2 ? e.placed.max.y : e.placed.min.y,
                     corner & 4 ? e.placed.max.z : e.placed.min.z};
      const std::string where = outside(p.place(e.pivot, x0), e.region);
      if (where.empty()) continue;
      char b[160];
      std::snprintf(b, sizeof b, "drives the wall '%s' out of the domain at t = %.4g s (", e.name.c_str(), t);
      throw InputError(c.source, e.line, e.key, b + where + "); enlarge the domain or let the motion end sooner");
    }
  }
}

// A free body: its mass (given, or density x volume) and inertia about its centre of mass
// (given principal moments, or the shape's at uniform density).
std::unique_ptr<motion::FreeBody> make_free_body(const Case& c, const BodySpec& spec,
                                                 const geometry::MassProperties& mp, const std::string& key) {
  if (!(mp.volume > 0))
    throw InputError(c.source, spec.line, key, "the mesh encloses no volume: a free body needs a closed mesh");
  const double mass = spec.mass > 0 ? spec.mass : spec.density * mp.volume;
  motion::Matrix3 inertia{};
  if (norm(spec.inertia) > 0) {
    for (int k = 0; k < 3; ++k) inertia[k][k] = spec.inertia[k];
  } else {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) inertia[i][j] = mp.inertia[i][j] * mass / mp.volume;
  }
  return std::make_unique<motion::FreeBody>(spec, mass, mp.centroid, inertia, c.gravity);
}

bool owns_body(const DemWallSpec& w) { return w.motion.moves() || w.body.free; }
} // namespace

int dem_wall_body(const Case& c, std::size_t w) {
  const DemWallSpec& d = c.dem.walls[w];
  if (!d.moves()) return -1;
  int sph = 0, k = -1;
  for (const auto& s : c.walls) {
    if (!s.moves()) continue;
    if (!d.follows.empty() && s.name == d.follows) k = sph;
    ++sph;
  }
  if (!d.follows.empty()) return k;
  int n = sph;
  for (std::size_t j = 0; j < w; ++j) n += owns_body(c.dem.walls[j]) ? 1 : 0;
  return n;
}

MovingBodies::MovingBodies(const Case& c, const sph::InitialState* init) : origin_(init ? init->origin : c.domain.min) {
  if (init) {
    moving_ = init->moving;
    const Box region{Vec3d(init->fluid_lo) + init->origin, Vec3d(init->fluid_hi) + init->origin};
    for (const auto& m : moving_) {
      const WallSpec& w = c.walls[m.wall];
      const std::string key = "walls." + std::to_string(m.wall);
      Body b;
      b.name = w.name;
      b.pivot = m.pivot;
      if (w.body.free) {
        const geometry::MassProperties mp =
            w.is_mesh ? geometry::mesh_mass_properties(geometry::load_surface(w.mesh_path, false, c.domain))
                      : geometry::box_mass_properties(w.box);
        b.free = make_free_body(c, w.body, mp, key + ".body");
        b.volume = mp.volume;
        b.points = wall_points(*init, m);
        b.region = region;
      } else {
        b.law = std::make_unique<motion::Motion>(w.motion, motion::MotionContext{c.g(), c.source, key + ".motion"});
        check_stays_inside(c, *b.law,
                           {w.name, key + ".motion", w.motion.line, m.pivot, bounds(wall_points(*init, m)), region});
      }
      bodies_.push_back(std::move(b));
    }
  }
  for (std::size_t w = 0; w < c.dem.walls.size(); ++w) {
    const DemWallSpec& d = c.dem.walls[w];
    if (!d.moves() || !c.dem.active()) continue; // (without spheres no DEM runs)
    dem_walls_ = true;
    const int k = dem_wall_body(c, w);
    if (!owns_body(d)) { // follows an SPH wall
      if (k >= 0 && static_cast<std::size_t>(k) < bodies_.size()) bodies_[static_cast<std::size_t>(k)].touched = true;
      continue;
    }
    const std::string key = "dem.walls." + std::to_string(w);
    Body b;
    b.name = d.name;
    b.touched = true;
    std::optional<geometry::Mesh> mesh;
    if (d.is_mesh) mesh = geometry::load_surface(d.mesh_path, false, c.domain);
    if (d.body.free) {
      const geometry::MassProperties mp = geometry::mesh_mass_properties(*mesh);
      b.pivot = mp.centroid;
      b.free = make_free_body(c, d.body, mp, key + ".body");
      b.volume = mp.volume;
      for (const auto& tri : mesh->tris) b.points.insert(b.points.end(), {tri.a, tri.b, tri.c});
      b.region = c.domain;
    } else {
      const Box placed = mesh ? geometry::bounds(*mesh) : Box{d.point, d.point};
      b.pivot = motion::law_pivot(d.motion, placed);
      b.law = std::make_unique<motion::Motion>(d.motion, motion::MotionContext{c.g(), c.source, key + ".motion"});
      if (mesh) check_stays_inside(c, *b.law, {d.name, key + ".motion", d.motion.line, b.pivot, placed, c.domain});
    }
    bodies_.push_back(std::move(b));
  }
  dem_load_.assign(bodies_.size(), dem::WallLoadD{});
}

std::string MovingBodies::escaped() const {
  for (const auto& b : bodies_) {
    if (!b.free) continue;
    const motion::Pose p = b.free->pose();
    for (const Vec3d& x0 : b.points) {
      const std::string where = outside(p.place(b.pivot, x0), b.region);
      if (where.empty()) continue;
      return "the free body '" + b.name + "' left the domain (" + where +
             "; bodies do not meet walls yet: one heavier than water sinks through the floor)";
    }
  }
  return {};
}

bool MovingBodies::any_free() const {
  return std::any_of(bodies_.begin(), bodies_.end(), [](const Body& b) { return b.free != nullptr; });
}

motion::Pose MovingBodies::pose(std::size_t k, double t) const {
  return bodies_[k].law ? bodies_[k].law->at(t) : bodies_[k].free->pose();
}

std::vector<RigidState> MovingBodies::states(double t) const {
  std::vector<RigidState> s;
  for (std::size_t k = 0; k < bodies_.size(); ++k)
    s.push_back(motion::rigid_state(pose(k, t), bodies_[k].pivot - origin_));
  return s;
}

void MovingBodies::place(sph::WcsphSolver& solver, double t) const {
  if (moving_.empty()) return;
  std::vector<RigidState> s = states(t);
  s.resize(moving_.size());
  solver.move_walls(s);
}

void MovingBodies::advance(sph::WcsphSolver& solver, double dt) {
  std::vector<bool> wanted;
  std::vector<Vec3d> centre;
  bool any = false;
  for (std::size_t k = 0; k < moving_.size(); ++k) {
    const Body& b = bodies_[k];
    wanted.push_back(b.free != nullptr);
    centre.push_back(b.free ? b.free->centre() - origin_ : Vec3d{});
    any = any || b.free != nullptr;
  }
  if (!any) return;
  const auto loads = solver.moving_loads(wanted, centre);
  for (std::size_t k = 0; k < moving_.size(); ++k) {
    Body& b = bodies_[k];
    if (!b.free) continue;
    if (b.touched) { // held over the DEM steps of the next SPH step
      b.water_force = loads[k].force;
      b.water_moment = loads[k].moment;
    } else {
      b.free->advance(loads[k].force, loads[k].moment, dt);
    }
  }
}

void MovingBodies::attach(dem::DemSolver& dem, double t) const {
  if (!dem_walls_) return;
  std::vector<RigidState> placed;
  for (const auto& b : bodies_) placed.push_back(motion::rigid_state(motion::Pose{}, b.pivot - origin_));
  dem.set_wall_bodies(placed);
  place(dem, t);
}

void MovingBodies::place(dem::DemSolver& dem, double t) const {
  if (dem_walls_) dem.move_walls(states(t));
}

void MovingBodies::advance(dem::DemSolver& dem, double dt, double t) {
  if (!dem_walls_) return;
  dem_load_ = dem.body_loads();
  for (std::size_t k = 0; k < bodies_.size(); ++k) {
    Body& b = bodies_[k];
    if (!b.free || !b.touched) continue;
    // The spheres' moment is about the pivot the walls were placed with: the centre of
    // mass at this step's start, about which the free body takes its moment.
    b.free->advance(b.water_force + dem_load_[k].force, b.water_moment + dem_load_[k].moment, dt);
  }
  place(dem, t);
}

std::string MovingBodies::save() const {
  std::string s;
  for (const auto& b : bodies_)
    if (b.free) s += b.free->save();
  return s;
}

void MovingBodies::restore(const std::string& bytes, const std::string& path) {
  const std::size_t each = motion::FreeBody::state_bytes;
  std::size_t n = 0;
  for (const auto& b : bodies_) n += b.free ? 1 : 0;
  if (bytes.size() != n * each)
    throw InputError(path, 0, "walls",
                     "the checkpoint's free bodies differ from the case's; restart with the case.yaml of that run");
  std::size_t at = 0;
  for (auto& b : bodies_)
    if (b.free) {
      b.free->restore(bytes.substr(at, each));
      at += each;
    }
}

int MovingBodies::body_named(const std::string& name) const {
  for (std::size_t k = 0; k < bodies_.size(); ++k)
    if (bodies_[k].name == name) return static_cast<int>(k);
  return -1;
}

double MovingBodies::dem_gauge_value(const GaugeSpec& g, double t) const {
  const int k = body_named(g.wall);
  if (k < 0) return 0;
  const auto kk = static_cast<std::size_t>(k);
  const dem::WallLoadD& l = dem_load_[kk];
  return motion::body_reading(g.component, motion::rigid_state(pose(kk, t), bodies_[kk].pivot - origin_), origin_,
                              l.force, l.moment);
}

void print_moving_walls(const Case& c, const MovingBodies& bodies) {
  for (std::size_t k = 0; k < bodies.sph_count(); ++k) {
    const auto& m = bodies.wall(k);
    if (const motion::FreeBody* f = bodies.free_body(k)) {
      const WallSpec& w = c.walls[m.wall];
      const bool rail = w.body.constraint == "line";
      std::printf("moving      wall '%s' (%u particles): a free body of %.4g kg (%s), centre of mass [%g, %g, %g] m\n",
                  w.name.c_str(), m.last - m.first, f->mass(), rail ? "along a line" : "6 degrees of freedom",
                  m.pivot.x, m.pivot.y, m.pivot.z);
      if (!rail && bodies.mean_density(k) > c.sph.rho0)
        std::printf("warning     the free body '%s' (%.4g kg/m^3) is denser than the water (%.4g kg/m^3) and bodies do "
                    "not meet walls yet: it will sink through the floor, and the run stops when it leaves the domain\n",
                    w.name.c_str(), bodies.mean_density(k), c.sph.rho0);
      continue;
    }
    const motion::Pose end = bodies.pose(k, c.time.end);
    std::printf(
        "moving      wall '%s' (%u particles): %s from t = %g s, pivot [%g, %g, %g] m, at t = %g s moved by [%.4g, "
        "%.4g, %.4g] m, speed %.4g m/s\n",
        c.walls[m.wall].name.c_str(), m.last - m.first, c.walls[m.wall].motion.law.c_str(),
        c.walls[m.wall].motion.start, m.pivot.x, m.pivot.y, m.pivot.z, c.time.end, end.shift.x, end.shift.y,
        end.shift.z, norm(end.vel));
  }
  for (std::size_t w = 0; w < c.dem.walls.size(); ++w) {
    const DemWallSpec& d = c.dem.walls[w];
    if (!d.moves() || !c.dem.active()) continue;
    const auto k = static_cast<std::size_t>(dem_wall_body(c, w));
    const std::string name = d.name.empty() ? "dem.walls." + std::to_string(w) : "'" + d.name + "'";
    if (!d.follows.empty()) {
      std::printf("moving      DEM wall %s: with the wall '%s'\n", name.c_str(), d.follows.c_str());
    } else if (const motion::FreeBody* f = bodies.free_body(k)) {
      const Vec3d x = f->centre();
      std::printf("moving      DEM wall %s: a free body of %.4g kg (%s), centre of mass [%g, %g, %g] m\n", name.c_str(),
                  f->mass(), d.body.constraint == "line" ? "along a line" : "6 degrees of freedom", x.x, x.y, x.z);
    } else {
      const motion::Pose end = bodies.pose(k, c.time.end);
      std::printf(
          "moving      DEM wall %s: %s from t = %g s, at t = %g s moved by [%.4g, %.4g, %.4g] m, speed %.4g m/s\n",
          name.c_str(), d.motion.law.c_str(), d.motion.start, c.time.end, end.shift.x, end.shift.y, end.shift.z,
          norm(end.vel));
    }
  }
}

} // namespace surge::sim
