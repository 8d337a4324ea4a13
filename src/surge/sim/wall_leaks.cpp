#include "surge/sim/wall_leaks.hpp"

#include "surge/geometry/particle_generators.hpp"
#include "surge/geometry/terrain.hpp"

#include <algorithm>
#include <sstream>

namespace surge::sim {

WallLeaks::WallLeaks(const Case& c) : walls_(c.walls) {
  band_ = geometry::wall_layers(c) * c.dp;
  for (const auto& w : walls_) {
    meshes_.push_back(w.is_mesh
                          ? std::make_unique<geometry::Mesh>(geometry::load_surface(w.mesh_path, w.terrain, c.domain))
                          : nullptr);
    Box r = w.is_mesh ? geometry::bounds(*meshes_.back()) : w.box;
    // A solid mesh has no water behind it at any depth: its reach extends down without bound.
    const double below = w.is_mesh && w.solid ? 1e300 : band_;
    for (int k = 0; k < 3; ++k) {
      r.min[k] -= k == 2 ? below : band_;
      r.max[k] += band_;
    }
    reach_.push_back(r);
  }
}

LeakCount WallLeaks::count(const particles::HostParticles& host, const Vec3d& origin) const {
  LeakCount n;
  for (std::size_t i = 0; i < host.size(); ++i) {
    if (host.kind[i] != static_cast<std::uint8_t>(Kind::Fluid)) continue;
    const Vec3d x = Vec3d(host.pos[i]) + origin;
    for (std::size_t w = 0; w < walls_.size(); ++w) {
      const bool moved = w < moved_.size() && moved_[w].moved;
      const Vec3d xw = moved ? moved_[w].pose.unplace(moved_[w].pivot, x) : x; // where the wall was placed
      if (!reach_[w].contains(xw) || !geometry::behind_wall(walls_[w], meshes_[w].get(), xw, band_)) continue;
      if (n.count++ == 0) n.wall = walls_[w].name;
      for (int k = 0; k < 3; ++k) {
        n.lo[k] = std::min(n.lo[k], x[k]);
        n.hi[k] = std::max(n.hi[k], x[k]);
      }
      break;
    }
  }
  return n;
}

void LeakRecord::add(const LeakCount& n, double t) {
  if (n.count == 0) return;
  if (first_time < 0) {
    first_time = t;
    first = n;
  }
  if (n.count > max_count) {
    max_count = n.count;
    max_time = t;
  }
}

std::string LeakRecord::json() const {
  std::ostringstream j;
  j.precision(10);
  j << "{\"max_at_an_output\": " << max_count;
  if (max_count > 0)
    j << ", \"max_time\": " << max_time << ", \"first_time\": " << first_time << ", \"first_wall\": \"" << first.wall
      << "\", \"first_where\": {\"min\": [" << first.lo.x << ", " << first.lo.y << ", " << first.lo.z << "], \"max\": ["
      << first.hi.x << ", " << first.hi.y << ", " << first.hi.z << "]}";
  j << "}";
  return j.str();
}

} // namespace surge::sim
