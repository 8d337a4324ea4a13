#include "surge/sph/boundary/wall_hold.hpp"

#include <stdexcept>
#include <string>

namespace surge::sph {

WallHold::WallHold(const InitialState& init, const Vec3* shared)
    : on_(true), first_id_(init.first_boundary_id), shared_(shared) {
  if (!shared) {
    // Wall ids come before body ids: the first n_wall offsets are the walls'.
    const std::vector<Vec3> walls(init.boundary_ghost.begin(),
                                  init.boundary_ghost.begin() + static_cast<std::ptrdiff_t>(init.n_wall));
    par::upload(offset_, walls);
  }
  par::upload(reach_, init.wall_reach);
  par::upload(extra_faces_, init.extra_faces);
}

WallChoice* WallHold::choices(int n) {
  if (!on_) return nullptr;
  if (n >= max_held_particles)
    throw std::runtime_error("the no-penetration condition (sph.no_penetration) handles at most " +
                             std::to_string(max_held_particles) + " particles in one process; this one holds " +
                             std::to_string(n) + ": run on more processes or turn it off");
  choices_.resize(static_cast<std::size_t>(n));
  return choices_.data();
}

} // namespace surge::sph
