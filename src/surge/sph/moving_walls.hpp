// Walls that move (issue 34): the particles of each moving wall follow their body's rigid
// state exactly, as body particles follow their spheres (coupling/): r = x + R(q) r0,
// v = v_x + w x (r - x), nothing integrated. Their velocity is what the pair terms read
// (continuity, viscosity) and what the no-penetration condition holds water against;
// with mDBC their ghost offsets turn with them.
#pragma once
#include "surge/core/distribution.hpp"
#include "surge/core/rigid_state.hpp"
#include "surge/par/parallel.hpp"
#include "surge/particles/particle_store.hpp"
#include "surge/sph/initial_state.hpp"

#include <cstdint>
#include <vector>

namespace surge::sph {

// A moving wall's particles as the placement kernel reads them: ids [first, last), their
// body-frame arms from `base` on (arm0[base + id - first]).
struct MovingRange {
  std::uint32_t first = 0, last = 0, base = 0;
};

class MovingWalls {
public:
  MovingWalls() = default; // nothing moves
  // ghosts: the wall model keeps ghost offsets (mDBC), which turn with the walls.
  MovingWalls(const InitialState& init, bool ghosts);
  [[nodiscard]] bool any() const { return !ranges_host_.empty(); }
  [[nodiscard]] int bodies() const { return static_cast<int>(ranges_host_.size()); }
  // Places every moving wall's particles (owned and halo copies) from its body's state
  // (states[k] for InitialState::moving[k]); with `ghost_out` (by id - first_boundary) their
  // ghost offsets turned.
  void place(const particles::ParticleView& p, const std::vector<RigidState>& states, Vec3* ghost_out,
             std::uint32_t first_boundary);
  // The water's force on body k's particles and its moment about centre[k] (local), for
  // the bodies with wanted[k]: sums of m a over the particles in id order, in double (each
  // particle's owner contributes it), the same on any number of threads or processes.
  struct Load {
    Vec3d force{}, moment{};
  };
  std::vector<Load> loads(const particles::ParticleView& p, const std::vector<bool>& wanted,
                          const std::vector<Vec3d>& centre, Real mass, const Distribution& dist);
  [[nodiscard]] std::size_t bytes() const {
    return ranges_.bytes() + arm0_.bytes() + ghost0_.bytes() + states_.bytes() + acc_.bytes() + pos_.bytes();
  }

private:
  std::vector<MovingRange> ranges_host_;
  par::Buffer<MovingRange> ranges_;
  par::Buffer<Vec3> arm0_, ghost0_; // per moving wall particle: r0 - pivot0, the ghost offset as placed
  par::Buffer<RigidState> states_;
  par::Buffer<Vec3> acc_, pos_; // loads: each moving wall particle's acceleration and position
};

} // namespace surge::sph
