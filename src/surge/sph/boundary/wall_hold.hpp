// The no-penetration condition (no_penetration.hpp) with any wall model
// (sph.no_penetration): what the wall particles hold (their faces, from their ghost
// offsets, and reach) and, from each rates pass, which plane every fluid particle would
// reach first, which the update keeps it dp/4 in front of.
#pragma once
#include "surge/core/rigid_state.hpp"
#include "surge/par/parallel.hpp"
#include "surge/sph/boundary/no_penetration.hpp"
#include "surge/sph/initial_state.hpp"

namespace surge::sph {

class WallHold {
public:
  WallHold() = default; // off
  // On: `shared`, the wall model's ghost offsets if it keeps them (wall particles first),
  // else null and the wall particles' own are kept here, in their rows.
  WallHold(const InitialState& init, const Vec3* shared);
  // Turns the faces of moving walls with their bodies (states[k] for InitialState::moving[k]):
  // the rows' offsets (unless the wall model keeps them) and the extra faces. Rows are never
  // shared between bodies, so each turns with its own.
  void turn(const std::vector<RigidState>& states);
  [[nodiscard]] bool on() const { return on_; }
  // What the rates kernel reads (hold false when off); built on each call, so that it
  // never outlives a buffer.
  [[nodiscard]] WallHoldView view() const {
    return {on_, first_id_, shared_, row_.data(), rows_.data(), extra_faces_.data()};
  }
  // One wall choice per particle (no_penetration.hpp), written by the rates pass: null when off.
  [[nodiscard]] WallChoice* choices(int n);
  [[nodiscard]] const WallChoice* choices() const { return on_ ? choices_.data() : nullptr; }
  [[nodiscard]] std::size_t bytes() const {
    return row_.bytes() + rows_.bytes() + extra_faces_.bytes() + choices_.bytes();
  }

private:
  bool on_ = false;
  std::uint32_t first_id_ = 0;
  const Vec3* shared_ = nullptr;    // the wall model's ghost offsets, if it keeps them
  par::Buffer<std::uint32_t> row_;  // 4 B per wall particle: its row of rows_
  par::Buffer<WallRow> rows_;       // the distinct (offset, reach) of the walls
  par::Buffer<Vec3> extra_faces_;   // 12 B per extra face of a solid box's or mesh's edge particle
  par::Buffer<WallChoice> choices_; // 4 B per particle
  // Moving walls: each row's and extra face's body (-1: still) and their offsets as placed.
  std::vector<int> row_body_, extra_body_;
  std::vector<WallRow> rows0_;
  std::vector<Vec3> extra0_;
  bool turned_ = false; // some body has turned (the buffers differ from rows0_, extra0_)
};

} // namespace surge::sph
