// The bed under a vertical line: the highest wall surface there that faces up, with the
// water above it (a tank's floor, a solid box's top, an upward-facing mesh triangle;
// mesh normals point to the water). Wave gauges read the water standing on it.
#pragma once
#include "surge/core/case.hpp"
#include "surge/geometry/stl_mesh.hpp"

#include <optional>

namespace surge::geometry {

// The highest upward-facing surface of wall w crossed by the vertical line through (x, y);
// none when the line misses it. `mesh` is w's mesh (null for boxes).
std::optional<double> bed_below(const WallSpec& w, const Mesh* mesh, double x, double y);

} // namespace surge::geometry
