// The particles a case starts with: fluid lattices, wall layers from boxes and meshes,
// the mDBC ghost offsets and no-penetration reach of the wall particles, and the region
// fluid may occupy.
#pragma once
#include "surge/core/case.hpp"
#include "surge/particles/particle_store.hpp"
#include "surge/sph/boundary/no_penetration.hpp"
#include "surge/sph/eos_tait.hpp"

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace surge::sph {

// A wall that moves (WallSpec::motion): its particle ids [first, last) and its pivot as
// placed (absolute), the point its body's rigid state follows.
struct MovingWall {
  std::uint32_t first = 0, last = 0;
  std::size_t wall = 0; // index into Case::walls
  Vec3d pivot{};
};

// The particles a case starts with, in local coordinates (absolute - origin).
struct InitialState {
  particles::HostParticles particles;
  Vec3d origin{}; // case domain.min; local = absolute - origin
  std::size_t n_fluid = 0, n_wall = 0;
  // Wall particle ids of each case wall: [first, last) (ids are assigned in order).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> wall_ids;
  std::vector<MovingWall> moving; // the walls with a motion, in case order
  // The body (index into `moving`) of a wall particle by id, or -1 for a still wall.
  [[nodiscard]] int body_of(std::uint32_t id) const {
    for (std::size_t k = 0; k < moving.size(); ++k)
      if (id >= moving[k].first && id < moving[k].last) return static_cast<int>(k);
    return -1;
  }
  std::size_t fluid_dropped_by_walls = 0;
  double fluid_volume_asked = 0;  // sum of the fluid boxes' volumes
  double fluid_volume_placed = 0; // what the particles placed stand for (each its lattice cell)
  // The SPH particles' mass when a box is filled exactly (rho0 times the volume placed per
  // fluid particle); 0: rho0 dp^3 (solver_config's).
  double particle_mass = 0;
  long reservoir_columns = 0;    // lattice columns with reservoir water: its surface area / dp^2
  long reservoir_near_shore = 0; // of these, those within 2 dp of the shore
  // Ghost nodes of the boundary (wall, then body) particles for sph.boundary: mdbc, as
  // ghost - position, indexed by id - first_boundary_id (fluid ids come first).
  std::uint32_t first_boundary_id = 0;
  std::vector<Vec3> boundary_ghost;
  std::vector<WallReach> wall_reach; // per wall particle (id - first_boundary_id < n_wall)
  std::vector<Vec3> extra_faces;     // the faces of WallReach::extra
  // Where fluid may be (local coordinates): the case's domain, grown to hold every wall
  // particle's cell. Fluid beyond it is removed as having left the domain; fluid that went
  // into a wall's layers stays and is counted as a leak (sim::WallLeaks), not deleted.
  Vec3 fluid_lo{}, fluid_hi{};
  // The domain's periodic axes (Case::periodic), symmetry faces (Case::symmetry, by Face)
  // and its faces (local: 0 and max - min).
  std::array<int, 3> periodic{};
  std::array<int, 6> symmetry{};
  Vec3 domain_hi{};
};

// Density of still water at p in fluid region f: Tait density of rho0 g (top of f - z)
// with sph.hydrostatic_init, rho0 otherwise (the start of every fluid and submerged
// body particle).
[[nodiscard]] Real still_water_density(const Case& c, const TaitEos& eos, const FluidRegion& f, const Vec3d& p);

// Builds fluid and wall particles from the case (meshes are read here).
InitialState build_initial_state(const Case& c);

} // namespace surge::sph
