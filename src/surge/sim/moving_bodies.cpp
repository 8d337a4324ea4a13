#include "surge/sim/moving_bodies.hpp"

#include "surge/core/error.hpp"
#include "surge/geometry/mass_properties.hpp"
#include "surge/geometry/terrain.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace surge::sim {

namespace {
// The bounding box of a moving wall's particles as placed (absolute).
Box particle_bounds(const sph::InitialState& init, const sph::MovingWall& m) {
  Box b{{1e300, 1e300, 1e300}, {-1e300, -1e300, -1e300}};
  for (std::uint32_t id = m.first; id < m.last; ++id) {
    const Vec3d x = Vec3d(init.particles.pos[id]) + init.origin;
    for (int k = 0; k < 3; ++k) {
      b.min[k] = std::min(b.min[k], x[k]);
      b.max[k] = std::max(b.max[k], x[k]);
    }
  }
  return b;
}

// Refuses a motion that takes any corner of the wall's particle box out of `region` (the
// domain grown by the wall layers: beyond it the grid clamps and nothing is tested) at one
// of 2,000 times from 0 to `end` or at `end`.
void check_stays_inside(const Case& c, const motion::Motion& mo, const sph::MovingWall& m, const Box& placed,
                        const Box& region) {
  const int n = 2000;
  const char* axes = "xyz";
  for (int s = 0; s <= n; ++s) {
    const double t = c.time.end * s / n;
    const motion::Pose p = mo.at(t);
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3d x0{corner & 1 ? placed.max.x : placed.min.x, corner & 2 ? placed.max.y : placed.min.y,
                     corner & 4 ? placed.max.z : placed.min.z};
      const Vec3d x = p.place(m.pivot, x0);
      for (int k = 0; k < 3; ++k) {
        if (x[k] >= region.min[k] - 1e-9 && x[k] <= region.max[k] + 1e-9) continue;
        char b[320];
        std::snprintf(b, sizeof b,
                      "drives the wall '%s' out of the domain (grown by its wall layers to %c in [%.4g, %.4g] m) at "
                      "t = %.4g s, where a corner of its particles reaches %c = %.4g m; enlarge the domain or let the "
                      "motion end sooner",
                      c.walls[m.wall].name.c_str(), axes[k], region.min[k], region.max[k], t, axes[k], x[k]);
        throw InputError(c.source, c.walls[m.wall].motion.line, "walls." + std::to_string(m.wall) + ".motion", b);
      }
    }
  }
}

// A free body of wall w: its mass (given, or density x volume) and inertia about its
// centre of mass (given principal moments, or the shape's at uniform density).
std::unique_ptr<motion::FreeBody> make_free_body(const Case& c, const WallSpec& w, const sph::MovingWall& m) {
  const geometry::MassProperties mp =
      w.is_mesh ? geometry::mesh_mass_properties(geometry::load_surface(w.mesh_path, false, c.domain))
                : geometry::box_mass_properties(w.box);
  const std::string key = "walls." + std::to_string(m.wall) + ".body";
  if (!(mp.volume > 0))
    throw InputError(c.source, w.body.line, key, "the mesh encloses no volume: a free body needs a closed mesh");
  const double mass = w.body.mass > 0 ? w.body.mass : w.body.density * mp.volume;
  motion::Matrix3 inertia{};
  if (norm(w.body.inertia) > 0) {
    for (int k = 0; k < 3; ++k) inertia[k][k] = w.body.inertia[k];
  } else {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) inertia[i][j] = mp.inertia[i][j] * mass / mp.volume;
  }
  return std::make_unique<motion::FreeBody>(w.body, mass, m.pivot, inertia, c.gravity);
}
} // namespace

MovingBodies::MovingBodies(const Case& c, const sph::InitialState& init) : moving_(init.moving), origin_(init.origin) {
  const Box region{Vec3d(init.fluid_lo) + init.origin, Vec3d(init.fluid_hi) + init.origin};
  for (const auto& m : moving_) {
    const WallSpec& w = c.walls[m.wall];
    Body b;
    if (w.body.free) {
      b.free = make_free_body(c, w, m);
    } else {
      b.law = std::make_unique<motion::Motion>(
          w.motion, motion::MotionContext{c.g(), c.source, "walls." + std::to_string(m.wall) + ".motion"});
      check_stays_inside(c, *b.law, m, particle_bounds(init, m), region);
    }
    bodies_.push_back(std::move(b));
  }
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
    s.push_back(motion::rigid_state(pose(k, t), moving_[k].pivot - origin_));
  return s;
}

void MovingBodies::advance(sph::WcsphSolver& solver, double dt) {
  if (!any_free()) return;
  std::vector<bool> wanted;
  std::vector<Vec3d> centre;
  for (const auto& b : bodies_) {
    wanted.push_back(b.free != nullptr);
    centre.push_back(b.free ? b.free->centre() - origin_ : Vec3d{});
  }
  const auto loads = solver.moving_loads(wanted, centre);
  for (std::size_t k = 0; k < bodies_.size(); ++k)
    if (bodies_[k].free) bodies_[k].free->advance(loads[k].force, loads[k].moment, dt);
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

void MovingBodies::place(sph::WcsphSolver& solver, double t) const {
  if (any()) solver.move_walls(states(t));
}

int MovingBodies::body_of_wall(std::size_t w) const {
  for (std::size_t k = 0; k < moving_.size(); ++k)
    if (moving_[k].wall == w) return static_cast<int>(k);
  return -1;
}

} // namespace surge::sim
