#include "surge/geometry/sphere_packs.hpp"

#include "surge/core/error.hpp"
#include "surge/core/number_rows.hpp"
#include "surge/geometry/sphere_index.hpp"

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

namespace surge::geometry {

std::vector<SphereSpec> lattice_pack(const Box& box, double radius, double jitter, unsigned seed) {
  std::vector<SphereSpec> out;
  const double d = 2 * radius;
  long n[3];
  for (int k = 0; k < 3; ++k) n[k] = static_cast<long>(std::floor((box.max[k] - box.min[k]) / d + 1e-9));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter * radius, jitter * radius);
  for (long k = 0; k < n[2]; ++k)
    for (long j = 0; j < n[1]; ++j)
      for (long i = 0; i < n[0]; ++i) {
        const Vec3d c{box.min.x + (static_cast<double>(i) + 0.5) * d, box.min.y + (static_cast<double>(j) + 0.5) * d,
                      box.min.z + (static_cast<double>(k) + 0.5) * d};
        out.push_back({c + Vec3d{u(rng), u(rng), u(rng)}, radius});
      }
  return out;
}

bool inside_mesh(const Mesh& m, const Vec3d& p) {
  // Moller-Trumbore ray-triangle tests along an oblique direction (no axis-aligned edge is
  // hit edge-on by accident); odd crossings: inside.
  const Vec3d dir{0.5773502691896258, 0.5773502691896258 * 1.0001, 0.5773502691896258 * 0.9998};
  int crossings = 0;
  for (const auto& t : m.tris) {
    const Vec3d e1 = t.b - t.a, e2 = t.c - t.a;
    const Vec3d pv = cross(dir, e2);
    const double det = dot(e1, pv);
    if (std::fabs(det) < 1e-18) continue;
    const double inv = 1.0 / det;
    const Vec3d tv = p - t.a;
    const double u = dot(tv, pv) * inv;
    if (u < 0 || u > 1) continue;
    const Vec3d qv = cross(tv, e1);
    const double v = dot(dir, qv) * inv;
    if (v < 0 || u + v > 1) continue;
    if (dot(e2, qv) * inv > 0) ++crossings;
  }
  return crossings % 2 == 1;
}

double distance_to_mesh(const Mesh& m, const Vec3d& p) {
  double best = 1e300;
  for (const auto& t : m.tris) best = std::min(best, norm(p - closest_point(t, p)));
  return best;
}

bool PackRegion::holds(const Vec3d& c, double r) const {
  for (int k = 0; k < 3; ++k)
    if (c[k] - r < box.min[k] - 1e-12 || c[k] + r > box.max[k] + 1e-12) return false;
  if (top != nullptr && bottom != nullptr) {
    // Comparisons written so that NaN (off either grid) rejects the sphere.
    if (!(c.z <= surface_height(*top, c.x, c.y))) return false;
    if (!(c.z - r >= highest_under(*bottom, c.x, c.y, r))) return false;
  }
  return mesh == nullptr || (inside_mesh(*mesh, c) && distance_to_mesh(*mesh, c) >= r);
}

void draw_radii(std::vector<SphereSpec>& list, double radius_min, double radius_max, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(radius_min, radius_max);
  for (auto& s : list) s.radius = u(rng);
}

double solid_volume(const std::vector<SphereSpec>& list) {
  double v = 0;
  for (const auto& s : list) v += 4.0 / 3.0 * M_PI * s.radius * s.radius * s.radius;
  return v;
}

std::vector<SphereSpec> lattice_pack(const PackRegion& region, double radius, double jitter, unsigned seed) {
  std::vector<SphereSpec> out;
  for (const auto& s : lattice_pack(region.box, radius, jitter, seed))
    if ((region.mesh == nullptr && region.top == nullptr) || region.holds(s.centre, radius)) out.push_back(s);
  return out;
}

std::vector<SphereSpec> random_pack(const PackRegion& region, double radius, long count, unsigned seed) {
  std::vector<SphereSpec> out;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  SphereIndex index(2 * radius); // a new sphere checks the spheres in the 27 cells around it
  const long attempts = 200 * count + 10000;
  for (long a = 0; a < attempts && static_cast<long>(out.size()) < count; ++a) {
    Vec3d c;
    for (int k = 0; k < 3; ++k)
      c[k] = region.box.min[k] + radius + u(rng) * (region.box.max[k] - region.box.min[k] - 2 * radius);
    const bool taken =
        index.any_near(c, [&](int s) { return norm(out[static_cast<std::size_t>(s)].centre - c) < 2 * radius; });
    if (taken || !region.holds(c, radius)) continue;
    index.add(static_cast<int>(out.size()), c);
    out.push_back({c, radius});
  }
  return out;
}

std::vector<SphereSpec> read_sphere_csv(const std::string& path) {
  std::vector<SphereSpec> out;
  for (const NumberRow& row : read_number_rows(path, 4, 4, "x, y, z, r", "sphere list")) {
    const SphereSpec s{{row.v[0], row.v[1], row.v[2]}, row.v[3]};
    if (!(s.radius > 0)) throw InputError(path, row.line, "", "radius must be positive");
    out.push_back(s);
  }
  return out;
}

} // namespace surge::geometry
