// STL reading (ascii and binary give the same triangles) and closest points.
#include "surge/core/error.hpp"
#include "surge/geometry/particle_generators.hpp"
#include "surge/geometry/sphere_packs.hpp"
#include "surge/geometry/stl_mesh.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>

using namespace surge;
using namespace surge::geometry;

namespace {
const char* ascii_two =
    "solid quad\n"
    " facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 1 1 0\n  endloop\n endfacet\n"
    " facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 1 0\n   vertex 0 1 0\n  endloop\n endfacet\n"
    "endsolid quad\n";

std::string to_binary(const Mesh& m) {
  std::string s(80, ' ');
  const auto n = static_cast<std::uint32_t>(m.tris.size());
  s.append(reinterpret_cast<const char*>(&n), 4);
  for (const auto& t : m.tris) {
    float v[12] = {0, 0, 0};
    int k = 3;
    for (const Vec3d& p : {t.a, t.b, t.c})
      for (int c = 0; c < 3; ++c) v[k++] = static_cast<float>(p[c]);
    s.append(reinterpret_cast<const char*>(v), sizeof v);
    s.append(2, '\0');
  }
  return s;
}
} // namespace

TEST(Stl, AsciiAndBinaryAgree) {
  const Mesh a = parse_stl(ascii_two, "a.stl");
  ASSERT_EQ(a.tris.size(), 2U);
  EXPECT_DOUBLE_EQ(a.tris[0].normal().z, 1.0);
  const Mesh b = parse_stl(to_binary(a), "b.stl");
  ASSERT_EQ(b.tris.size(), 2U);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_DOUBLE_EQ(a.tris[i].c.x, b.tris[i].c.x);
    EXPECT_DOUBLE_EQ(a.tris[i].c.y, b.tris[i].c.y);
  }
}

TEST(Stl, ErrorsNameTheLine) {
  std::string bad = ascii_two;
  bad.replace(bad.find("vertex 1 0 0"), 12, "vertex 1 x 0");
  try {
    (void)parse_stl(bad, "bad.stl");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 5);
    EXPECT_EQ(e.file(), "bad.stl");
  }
  EXPECT_THROW((void)parse_stl("garbage", "g.stl"), InputError);
  EXPECT_THROW((void)parse_stl("solid empty\nendsolid empty\n", "e.stl"), InputError);
}

TEST(Stl, ClosestPointRegions) {
  const Triangle t{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const Vec3d face = closest_point(t, {0.2, 0.2, 1});
  EXPECT_NEAR(face.x, 0.2, 1e-15);
  EXPECT_NEAR(face.y, 0.2, 1e-15);
  EXPECT_NEAR(face.z, 0, 1e-15);
  const Vec3d edge = closest_point(t, {0.5, -1, 0.3});
  EXPECT_NEAR(edge.x, 0.5, 1e-15);
  EXPECT_NEAR(edge.y, 0, 1e-15);
  const Vec3d hyp = closest_point(t, {1, 1, 0});
  EXPECT_NEAR(hyp.x, 0.5, 1e-15);
  EXPECT_NEAR(hyp.y, 0.5, 1e-15);
  const Vec3d vertex = closest_point(t, {-1, -1, 0});
  EXPECT_NEAR(vertex.x, 0, 1e-15);
  EXPECT_NEAR(vertex.y, 0, 1e-15);
}

TEST(SpherePacks, CsvErrorsNameTheLineAndLatticeFillsTheBox) {
  const std::string path = ::testing::TempDir() + "/spheres_test.csv";
  {
    std::ofstream f(path);
    f << "x, y, z, r\n0.1, 0.2, 0.3, 0.01\n# a comment\n0.1 0.2 oops 0.01\n";
  }
  try {
    (void)read_sphere_csv(path);
    FAIL() << "no error";
  } catch (const InputError& e) { EXPECT_EQ(e.line(), 4); }
  {
    std::ofstream f(path);
    f << "0.1, 0.2, 0.3, 0.01\n0.2, 0.2, 0.3, 0.02 # second\n";
  }
  const auto ok = read_sphere_csv(path);
  ASSERT_EQ(ok.size(), 2U);
  EXPECT_DOUBLE_EQ(ok[1].radius, 0.02);
  // 0.1 x 0.06 x 0.04 box, r = 0.01: 5 x 3 x 2 touching spheres, all inside the box.
  const auto pack = lattice_pack({{0, 0, 0}, {0.1, 0.06, 0.04}}, 0.01, 0.0);
  ASSERT_EQ(pack.size(), 30U);
  for (const auto& s : pack) EXPECT_TRUE((Box{{0.01, 0.01, 0.01}, {0.09, 0.05, 0.03}}.contains(s.centre, 1e-12)));
}

namespace {
// A closed UV sphere (radius R about c), wound outwards; `drop` leaves out a triangle.
geometry::Mesh uv_sphere(const Vec3d& c, double R, int n, bool drop = false, bool inward = false) {
  auto v = [&](int i, int j) { // the poles and the seam exactly shared, as an STL file's text repeats them
    if (i == 0 || i == n) return c + Vec3d{0, 0, i == 0 ? R : -R};
    const double th = M_PI * i / n, ph = 2 * M_PI * (j % n) / n;
    return c + Vec3d{R * std::sin(th) * std::cos(ph), R * std::sin(th) * std::sin(ph), R * std::cos(th)};
  };
  geometry::Mesh m;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const Vec3d a = v(i, j), b = v(i + 1, j), cc = v(i + 1, j + 1), d = v(i, j + 1);
      if (i > 0) m.tris.push_back(inward ? geometry::Triangle{a, d, b} : geometry::Triangle{a, b, d});
      if (i < n - 1) m.tris.push_back(inward ? geometry::Triangle{b, d, cc} : geometry::Triangle{b, cc, d});
    }
  if (drop) m.tris.pop_back();
  geometry::finish_mesh(m, "sphere");
  return m;
}
} // namespace

// A mesh is closed when watertight and wound outwards; a closed solid's far inside and
// outside (found by a ray's crossings, and by its bounding box) agree with the sphere's
// own, for lattice points on the mesh's vertices' planes too (rays that graze edges).
TEST(Stl, FarInsideAndOutsideOfAClosedSolid) {
  const Vec3d c{0.5, 0.5, 0.5};
  const double R = 0.3;
  EXPECT_TRUE(uv_sphere(c, R, 24).closed);
  EXPECT_FALSE(uv_sphere(c, R, 24, true).closed);
  EXPECT_FALSE(uv_sphere(c, R, 24, false, true).closed);
  const geometry::Mesh m = uv_sphere(c, R, 24);
  WallSpec w;
  w.is_mesh = true;
  w.solid = true;
  const double band = 0.02, dp = 0.01;
  int checked = 0;
  for (int i = 0; i <= 50; ++i)
    for (int j = 0; j <= 50; j += 5)
      for (int k = 0; k <= 50; k += 5) {
        const Vec3d p{i * 0.02, j * 0.02, k * 0.02}; // includes the centre's planes (x, y = 0.5)
        const double r = norm(p - c);
        // the facets lie between R cos(pi / 24) and R: keep clear of that shell by 4 dp
        if (r > R * std::cos(M_PI / 24) - 4 * dp - 0.01 && r < R + 4 * dp + 0.01) continue;
        EXPECT_EQ(geometry::behind_wall(w, &m, p, band), r < R) << p.x << " " << p.y << " " << p.z;
        EXPECT_EQ(geometry::blocked_by(w, &m, p, dp), r < R) << p.x << " " << p.y << " " << p.z;
        ++checked;
      }
  EXPECT_GT(checked, 4000);
}
