#include "surge/geometry/terrain.hpp"

namespace surge::geometry {

Mesh terrain_mesh(const Raster& r) {
  Mesh m;
  m.tris.reserve(static_cast<std::size_t>(2 * (r.nx - 1) * (r.ny - 1)));
  auto node = [&](long i, long j) { return Vec3d{r.x(i), r.y(j), r.at(i, j)}; };
  for (long j = 0; j + 1 < r.ny; ++j)
    for (long i = 0; i + 1 < r.nx; ++i) {
      // Counter-clockwise seen from above: the normals point up, to the water.
      m.tris.push_back({node(i, j), node(i + 1, j), node(i + 1, j + 1)});
      m.tris.push_back({node(i, j), node(i + 1, j + 1), node(i, j + 1)});
    }
  finish_mesh(m, r.path);
  m.heights = std::make_shared<const Raster>(r);
  return m;
}

Raster read_terrain(const std::string& path, const Box& domain) {
  return crop(read_raster(path), domain.min.x, domain.min.y, domain.max.x, domain.max.y, "terrain");
}

Mesh load_surface(const std::string& path, bool terrain, const Box& domain) {
  return terrain ? terrain_mesh(read_terrain(path, domain)) : read_stl(path);
}

} // namespace surge::geometry
