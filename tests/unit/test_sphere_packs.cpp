// Sphere packs: inside a closed mesh (ray parity), random loose packs without overlap.
#include "surge/geometry/sphere_packs.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace surge;
using namespace surge::geometry;

namespace {
// The octahedron |x| + |y| + |z| <= a, outward normals.
Mesh octahedron(double a) {
  Mesh m;
  for (int sx : {-1, 1})
    for (int sy : {-1, 1})
      for (int sz : {-1, 1}) {
        Vec3d x{sx * a, 0, 0}, y{0, sy * a, 0}, z{0, 0, sz * a};
        // Winding so that the normal points away from the origin.
        if (sx * sy * sz > 0)
          m.tris.push_back({x, y, z});
        else
          m.tris.push_back({x, z, y});
      }
  return m;
}
} // namespace

TEST(SpherePacks, InsideMeshByRayParity) {
  const Mesh m = octahedron(1.0);
  for (const auto& t : m.tris) EXPECT_GT(dot(t.normal(), t.a + t.b + t.c), 0.0); // outward
  EXPECT_TRUE(inside_mesh(m, {0, 0, 0}));
  EXPECT_TRUE(inside_mesh(m, {0.3, -0.3, 0.3}));
  EXPECT_FALSE(inside_mesh(m, {0.5, 0.5, 0.5}));
  EXPECT_FALSE(inside_mesh(m, {2, 0, 0}));
  EXPECT_NEAR(distance_to_mesh(m, {0, 0, 0}), 1 / std::sqrt(3.0), 1e-12);
}

// Every sphere of a lattice pack in the octahedron lies wholly inside it: its distance to
// each face plane, (a - |c|_1) / sqrt(3), is at least r (exact up to 1e-12); and the
// pack is not empty.
TEST(SpherePacks, LatticePackInsideAClosedMesh) {
  const Mesh m = octahedron(1.0);
  const PackRegion region{{{-1, -1, -1}, {1, 1, 1}}, &m};
  const double r = 0.05;
  const auto pack = lattice_pack(region, r, 0.0);
  ASSERT_GT(pack.size(), 100U);
  for (const auto& s : pack) {
    const double l1 = std::fabs(s.centre.x) + std::fabs(s.centre.y) + std::fabs(s.centre.z);
    EXPECT_GE((1.0 - l1) / std::sqrt(3.0), r - 1e-12);
  }
  // The box pack holds more: the mesh really cut it.
  EXPECT_GT(lattice_pack(region.box, r, 0.0).size(), pack.size());
}

// Random sequential addition: the requested count, no two spheres overlapping (brute
// force), all inside the box; when asked for more than fit, it returns fewer.
TEST(SpherePacks, RandomLoosePackWithoutOverlaps) {
  const PackRegion region{{{0, 0, 0}, {0.2, 0.2, 0.2}}, nullptr};
  const double r = 0.01;
  const auto pack = random_pack(region, r, 300);
  ASSERT_EQ(pack.size(), 300U);
  for (std::size_t i = 0; i < pack.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(pack[i].centre[k], r - 1e-12);
      EXPECT_LE(pack[i].centre[k], 0.2 - r + 1e-12);
    }
    for (std::size_t j = i + 1; j < pack.size(); ++j) EXPECT_GE(norm(pack[i].centre - pack[j].centre), 2 * r);
  }
  // 10^4 spheres of r = 0.01 cannot fit in 0.008 m^3 (solid fraction would be 0.52 > RSA's 0.38).
  EXPECT_LT(random_pack(region, r, 10000).size(), 10000U);
}
