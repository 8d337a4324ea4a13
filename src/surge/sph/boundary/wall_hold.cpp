#include "surge/sph/boundary/wall_hold.hpp"

#include <array>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace surge::sph {

WallHold::WallHold(const InitialState& init, const Vec3* shared)
    : on_(true), first_id_(init.first_boundary_id), shared_(shared) {
  // Each wall particle's (offset, reach), the distinct ones kept once, compared bit for bit
  // (the same values whichever particle's row is read). Wall ids come before body ids: the
  // first n_wall offsets are the walls'.
  std::map<std::array<unsigned char, sizeof(WallRow)>, std::uint32_t> seen;
  std::vector<WallRow> rows;
  std::vector<std::uint32_t> row(init.wall_reach.size());
  for (std::size_t b = 0; b < row.size(); ++b) {
    WallRow r{}; // zeroed, padding included: rows compare by their bytes
    r.offset = shared ? Vec3{} : init.boundary_ghost[b];
    r.reach = init.wall_reach[b];
    std::array<unsigned char, sizeof(WallRow)> key{};
    std::memcpy(key.data(), &r, sizeof r);
    const auto [it, fresh] = seen.try_emplace(key, static_cast<std::uint32_t>(rows.size()));
    if (fresh) rows.push_back(r);
    row[b] = it->second;
  }
  par::upload(row_, row);
  par::upload(rows_, rows);
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
