// Closest point on a triangle (Ericson, Real-Time Collision Detection, sect. 5.1.5),
// with the region it lies in; host/device, any precision.
#pragma once
#include "surge/core/types.hpp"

namespace surge::geometry {

enum class Region : int { Face = 0, Edge = 1, Vertex = 2 };

template <class T>
struct ClosestPoint {
  Vec3T<T> point;
  Region region;
};

template <class T>
SURGE_HD inline ClosestPoint<T> closest_point_on_triangle(const Vec3T<T>& a, const Vec3T<T>& b, const Vec3T<T>& c,
                                                          const Vec3T<T>& p) {
  const Vec3T<T> ab = b - a, ac = c - a, ap = p - a;
  const T d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return {a, Region::Vertex};
  const Vec3T<T> bp = p - b;
  const T d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return {b, Region::Vertex};
  const T vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return {a + ab * (d1 / (d1 - d3)), Region::Edge};
  const Vec3T<T> cp = p - c;
  const T d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return {c, Region::Vertex};
  const T vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return {a + ac * (d2 / (d2 - d6)), Region::Edge};
  const T va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return {b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))), Region::Edge};
  const T denom = T(1) / (va + vb + vc);
  return {a + ab * (vb * denom) + ac * (vc * denom), Region::Face};
}

} // namespace surge::geometry
