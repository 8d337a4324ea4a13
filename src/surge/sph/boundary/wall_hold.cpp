#include "surge/sph/boundary/wall_hold.hpp"

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

WallPlane* WallHold::planes(int n) {
  if (!on_) return nullptr;
  planes_.resize(static_cast<std::size_t>(n));
  return planes_.data();
}

} // namespace surge::sph
