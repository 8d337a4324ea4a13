// Triangle meshes from STL files (ascii and binary).
#pragma once
#include "surge/core/types.hpp"
#include "surge/geometry/triangle_index.hpp"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace surge::geometry {

struct Raster;

struct Triangle {
  Vec3d a, b, c;
  [[nodiscard]] Vec3d normal() const; // unit, from the winding (right-hand rule)
};

struct Mesh {
  std::vector<Triangle> tris;
  std::shared_ptr<const TriangleIndex> index; // set by finish_mesh
  std::shared_ptr<const Raster> heights;      // a terrain's grid (the mesh is its surface), else null
  // Watertight (each edge shared by two triangles, once each way) and wound outwards
  // (positive volume): its inside is where a ray crosses it an odd number of times.
  bool closed = false;
};

// Checks the triangles (some, none degenerate; `name` in messages) and indexes them:
// every mesh a case uses passes here (STL files, terrain grids).
void finish_mesh(Mesh& m, const std::string& name);
// Indices of the triangles whose bounding boxes meet the box [lo, hi], ascending (all of
// them for a mesh without index).
void triangles_near(const Mesh& m, const Vec3d& lo, const Vec3d& hi, std::vector<std::uint32_t>& out);

// Reads an STL file; throws InputError naming the file (and line for ascii).
Mesh read_stl(const std::string& path);
// Parses STL bytes; `name` is used in messages.
Mesh parse_stl(const std::string& bytes, const std::string& name);

// Closest point on triangle t to p (geometry/closest_point.hpp).
Vec3d closest_point(const Triangle& t, const Vec3d& p);

} // namespace surge::geometry
