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
  // A moving wall's rows are its own (the body index is part of the key), so that they can
  // turn with it.
  std::map<std::pair<int, std::array<unsigned char, sizeof(WallRow)>>, std::uint32_t> seen;
  std::vector<WallRow> rows;
  std::vector<std::uint32_t> row(init.wall_reach.size());
  extra_body_.assign(init.extra_faces.size(), -1);
  for (std::size_t b = 0; b < row.size(); ++b) {
    WallRow r{}; // zeroed, padding included: rows compare by their bytes
    r.offset = shared ? Vec3{} : init.boundary_ghost[b];
    r.reach = init.wall_reach[b];
    const int body = init.body_of(first_id_ + static_cast<std::uint32_t>(b));
    std::array<unsigned char, sizeof(WallRow)> key{};
    std::memcpy(key.data(), &r, sizeof r);
    const auto [it, fresh] = seen.try_emplace({body, key}, static_cast<std::uint32_t>(rows.size()));
    if (fresh) {
      rows.push_back(r);
      row_body_.push_back(body);
    }
    row[b] = it->second;
    if (r.reach.extra >= 0) {
      const auto first_extra = static_cast<std::size_t>(r.reach.extra >> 2);
      for (int e = 0; e < (r.reach.extra & 3); ++e) extra_body_[first_extra + static_cast<std::size_t>(e)] = body;
    }
  }
  par::upload(row_, row);
  par::upload(rows_, rows);
  par::upload(extra_faces_, init.extra_faces);
  if (!init.moving.empty()) {
    rows0_ = rows;
    extra0_ = init.extra_faces;
  }
}

void WallHold::turn(const std::vector<RigidState>& states) {
  if (!on_ || rows0_.empty()) return;
  const auto turned = [](const RigidState& s) { return s.q[1] != 0 || s.q[2] != 0 || s.q[3] != 0; };
  bool any = false;
  for (const auto& s : states) any = any || turned(s);
  if (!any && !turned_) return; // nothing turned, nor ever has: the rows are as placed
  std::vector<WallRow> rows = rows0_;
  for (std::size_t k = 0; k < rows.size(); ++k)
    if (row_body_[k] >= 0) rows[k].offset = rotate(states[static_cast<std::size_t>(row_body_[k])].q, rows0_[k].offset);
  std::vector<Vec3> extra = extra0_;
  for (std::size_t k = 0; k < extra.size(); ++k)
    if (extra_body_[k] >= 0) extra[k] = rotate(states[static_cast<std::size_t>(extra_body_[k])].q, extra0_[k]);
  par::upload(rows_, rows);
  par::upload(extra_faces_, extra);
  turned_ = any;
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
