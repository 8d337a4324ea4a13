#include "surge/geometry/mass_properties.hpp"

#include <cmath>

namespace surge::geometry {

MassProperties box_mass_properties(const Box& b) {
  const Vec3d e = b.max - b.min;
  MassProperties p;
  p.volume = e.x * e.y * e.z;
  p.centroid = (b.min + b.max) * 0.5;
  p.inertia[0][0] = p.volume * (e.y * e.y + e.z * e.z) / 12;
  p.inertia[1][1] = p.volume * (e.x * e.x + e.z * e.z) / 12;
  p.inertia[2][2] = p.volume * (e.x * e.x + e.y * e.y) / 12;
  return p;
}

// For each triangle (a, b, c), the tetrahedron (0, a, b, c) of signed volume det/6 adds
// det/6 (a + b + c)/4 to the first moment and det/120 (sum v v^T + s s^T), s = a + b + c, to
// the second moment C; about the centroid C - V x x^T, and I = tr(C) 1 - C.
MassProperties mesh_mass_properties(const Mesh& m) {
  double vol = 0;
  Vec3d first{};
  double c2[3][3] = {};
  for (const auto& t : m.tris) {
    const double det = dot(t.a, cross(t.b, t.c));
    vol += det / 6;
    const Vec3d s = t.a + t.b + t.c;
    first += s * (det / 24);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        c2[i][j] += det / 120 * (t.a[i] * t.a[j] + t.b[i] * t.b[j] + t.c[i] * t.c[j] + s[i] * s[j]);
  }
  const double sign = vol < 0 ? -1 : 1; // inward normals: every term changes sign
  MassProperties p;
  p.volume = sign * vol;
  p.centroid = first * (1 / vol);
  double c[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) c[i][j] = sign * c2[i][j] - p.volume * p.centroid[i] * p.centroid[j];
  const double tr = c[0][0] + c[1][1] + c[2][2];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) p.inertia[i][j] = (i == j ? tr : 0) - c[i][j];
  return p;
}

} // namespace surge::geometry
