#include "surge/sph/moving_walls.hpp"

#include <algorithm>
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
// acc[a], pos[a] of every owned moving wall particle (a = its arm's index).
void collect_moving(const particles::ParticleView& p, const MovingRange* ranges, int n_ranges, Vec3* acc, Vec3* pos) {
  const auto wall = static_cast<std::uint8_t>(Kind::Wall);
  par::parallel_for(
      p.n, SURGE_LAMBDA(int i) {
        if (p.kind[i] != wall || !p.owned(i)) return;
        const std::uint32_t id = p.id[i];
        for (int k = 0; k < n_ranges; ++k) {
          const MovingRange r = ranges[k];
          if (id < r.first || id >= r.last) continue;
          acc[r.base + (id - r.first)] = p.acc[i];
          pos[r.base + (id - r.first)] = p.pos[i];
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

std::vector<MovingWalls::Load> MovingWalls::loads(const particles::ParticleView& p, const std::vector<bool>& wanted,
                                                  const std::vector<Vec3d>& centre, Real mass,
                                                  const Distribution& dist) {
  std::vector<Load> out(ranges_host_.size());
  if (std::none_of(wanted.begin(), wanted.end(), [](bool w) { return w; })) return out;
  acc_.resize(arm0_.size());
  pos_.resize(arm0_.size());
  par::fill(acc_, Vec3{});
  par::fill(pos_, Vec3{});
  detail::collect_moving(p, ranges_.data(), bodies(), acc_.data(), pos_.data());
  std::vector<Vec3> acc, pos;
  par::download(acc, acc_, acc_.size());
  par::download(pos, pos_, pos_.size());
  dist.sum(reinterpret_cast<Real*>(acc.data()), 3 * acc.size());
  dist.sum(reinterpret_cast<Real*>(pos.data()), 3 * pos.size());
  for (std::size_t k = 0; k < ranges_host_.size(); ++k) {
    if (!wanted[k]) continue;
    const MovingRange& r = ranges_host_[k];
    Vec3d f{}, m{};
    for (std::uint32_t a = r.base; a < r.base + (r.last - r.first); ++a) {
      f += Vec3d(acc[a]);
      m += cross(Vec3d(pos[a]) - centre[k], Vec3d(acc[a]));
    }
    out[k] = {f * static_cast<double>(mass), m * static_cast<double>(mass)};
  }
  return out;
}

} // namespace surge::sph
