#include "surge/sph/moving_walls.hpp"

#include <stdexcept>

namespace surge::sph {

namespace detail {
// A free function: nvcc's extended lambdas may not live in member functions.
void place_moving(const particles::ParticleView& p, const MovingRange* ranges, int n_ranges, const Vec3* arm0,
                  const RigidState* states, const Vec3* ghost0, Vec3* ghost_out, std::uint32_t first_boundary) {
  const auto wall = static_cast<std::uint8_t>(Kind::Wall);
  par::parallel_for(
      p.n, SURGE_LAMBDA(int i) {
        if (p.kind[i] != wall) return;
        const std::uint32_t id = p.id[i];
        for (int k = 0; k < n_ranges; ++k) {
          const MovingRange r = ranges[k];
          if (id < r.first || id >= r.last) continue;
          const std::uint32_t a = r.base + (id - r.first);
          const RigidPoint x = rigid_point(states[k], arm0[a]);
          p.pos[i] = x.pos;
          p.vel[i] = x.vel;
          if (ghost_out) ghost_out[id - first_boundary] = rotate(states[k].q, ghost0[a]);
          return;
        }
      });
}
} // namespace detail

MovingWalls::MovingWalls(const InitialState& init, bool ghosts) {
  std::vector<Vec3> arm, ghost;
  for (const auto& m : init.moving) {
    ranges_host_.push_back({m.first, m.last, static_cast<std::uint32_t>(arm.size())});
    const Vec3d pivot = m.pivot - init.origin;
    // The initial state holds its particles in id order.
    for (std::uint32_t id = m.first; id < m.last; ++id) {
      arm.push_back(Vec3(Vec3d(init.particles.pos[id]) - pivot));
      if (ghosts) ghost.push_back(init.boundary_ghost[id - init.first_boundary_id]);
    }
  }
  par::upload(ranges_, ranges_host_);
  par::upload(arm0_, arm);
  par::upload(ghost0_, ghost);
}

void MovingWalls::place(const particles::ParticleView& p, const std::vector<RigidState>& states, Vec3* ghost_out,
                        std::uint32_t first_boundary) {
  if (states.size() != ranges_host_.size()) throw std::invalid_argument("one rigid state per moving wall expected");
  if (!any()) return;
  par::upload(states_, states);
  detail::place_moving(p, ranges_.data(), bodies(), arm0_.data(), states_.data(),
                       ghost0_.size() ? ghost0_.data() : nullptr, ghost0_.size() ? ghost_out : nullptr, first_boundary);
}

} // namespace surge::sph
