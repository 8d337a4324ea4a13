// Triangle meshes from STL files (ascii and binary).
#pragma once
#include "surge/core/types.hpp"

#include <string>
#include <vector>

namespace surge::geometry {

struct Triangle {
  Vec3d a, b, c;
  [[nodiscard]] Vec3d normal() const; // unit, from the winding (right-hand rule)
};

struct Mesh {
  std::vector<Triangle> tris;
};

// Reads an STL file; throws InputError naming the file (and line for ascii).
Mesh read_stl(const std::string& path);
// Parses STL bytes; `name` is used in messages.
Mesh parse_stl(const std::string& bytes, const std::string& name);

// Closest point on triangle t to p (geometry/closest_point.hpp).
Vec3d closest_point(const Triangle& t, const Vec3d& p);

} // namespace surge::geometry
