#include "surge/sim/moving_bodies.hpp"

#include "surge/core/error.hpp"

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
} // namespace

MovingBodies::MovingBodies(const Case& c, const sph::InitialState& init) : moving_(init.moving), origin_(init.origin) {
  const Box region{Vec3d(init.fluid_lo) + init.origin, Vec3d(init.fluid_hi) + init.origin};
  for (const auto& m : moving_) {
    const MotionSpec& spec = c.walls[m.wall].motion;
    motions_.emplace_back(spec, motion::MotionContext{c.g(), c.source, "walls." + std::to_string(m.wall) + ".motion"});
    check_stays_inside(c, motions_.back(), m, particle_bounds(init, m), region);
  }
}

std::vector<RigidState> MovingBodies::states(double t) const {
  std::vector<RigidState> s;
  for (std::size_t k = 0; k < motions_.size(); ++k)
    s.push_back(motion::rigid_state(motions_[k].at(t), moving_[k].pivot - origin_));
  return s;
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
