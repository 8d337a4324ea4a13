#include "surge/geometry/bed.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace surge::geometry {
namespace {
// Height where the vertical line through (x, y) crosses triangle t (edges included: a line
// on an edge shared by two triangles meets both at the same height); none if it misses
// or the triangle is vertical.
std::optional<double> crossing_height(const Triangle& t, double x, double y) {
  const double ux = t.b.x - t.a.x, uy = t.b.y - t.a.y, vx = t.c.x - t.a.x, vy = t.c.y - t.a.y;
  const double det = ux * vy - uy * vx;
  const double scale = std::max({std::fabs(ux), std::fabs(uy), std::fabs(vx), std::fabs(vy)});
  if (std::fabs(det) <= 1e-12 * scale * scale) return std::nullopt;
  const double px = x - t.a.x, py = y - t.a.y;
  const double s = (px * vy - py * vx) / det, r = (ux * py - uy * px) / det;
  constexpr double tol = 1e-9;
  if (s < -tol || r < -tol || s + r > 1 + tol) return std::nullopt;
  return t.a.z + s * (t.b.z - t.a.z) + r * (t.c.z - t.a.z);
}
bool open_face(const WallSpec& w, Face f) { return std::find(w.open.begin(), w.open.end(), f) != w.open.end(); }
} // namespace

std::optional<double> bed_below(const WallSpec& w, const Mesh* mesh, double x, double y) {
  if (w.is_mesh) {
    std::optional<double> top;
    std::vector<std::uint32_t> near;
    // A margin for crossing_height's tolerance at the triangles' edges.
    const double e = mesh->index ? 1e-8 * mesh->index->cell() : 0;
    triangles_near(*mesh, {x - e, y - e, -1e300}, {x + e, y + e, 1e300}, near);
    for (const std::uint32_t i : near) {
      const Triangle& t = mesh->tris[i];
      if (!(t.normal().z > 0)) continue; // facing down or sideways: a ceiling or a side wall
      if (const auto z = crossing_height(t, x, y); z && (!top || *z > *top)) top = z;
    }
    return top;
  }
  const Box& b = w.box;
  if (x < b.min.x || x > b.max.x || y < b.min.y || y > b.max.y) return std::nullopt;
  if (w.solid) return b.max.z;                                             // the obstacle's top
  return open_face(w, Face::ZMin) ? std::nullopt : std::optional(b.min.z); // the tank's floor
}

} // namespace surge::geometry
