#include "surge/geometry/stl_mesh.hpp"

#include "surge/core/error.hpp"
#include "surge/geometry/closest_point.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

namespace surge::geometry {

Vec3d Triangle::normal() const {
  const Vec3d n = cross(b - a, c - a);
  const double l = norm(n);
  return l > 0 ? n * (1.0 / l) : Vec3d{};
}

namespace {

bool finite(const Vec3d& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

Mesh parse_binary(const std::string& s, const std::string& name) {
  std::uint32_t n = 0;
  std::memcpy(&n, s.data() + 80, 4);
  Mesh m;
  m.tris.reserve(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    const char* rec = s.data() + 84 + 50 * static_cast<std::size_t>(i);
    float v[12];
    std::memcpy(v, rec, sizeof v);
    Triangle t{{v[3], v[4], v[5]}, {v[6], v[7], v[8]}, {v[9], v[10], v[11]}};
    if (!finite(t.a) || !finite(t.b) || !finite(t.c))
      throw InputError(name, 0, "", "triangle " + std::to_string(i) + " has a non-finite coordinate");
    m.tris.push_back(t);
  }
  return m;
}

Mesh parse_ascii(const std::string& s, const std::string& name) {
  std::istringstream in(s);
  std::string line;
  int lineno = 0;
  Mesh m;
  std::vector<Vec3d> verts;
  bool in_facet = false;
  while (std::getline(in, line)) {
    ++lineno;
    std::istringstream ls(line);
    std::string word;
    if (!(ls >> word)) continue;
    if (word == "solid" || word == "endsolid" || word == "outer" || word == "endloop") continue;
    if (word == "facet") {
      if (in_facet) throw InputError(name, lineno, "", "'facet' inside a facet (missing 'endfacet')");
      in_facet = true;
      verts.clear();
    } else if (word == "vertex") {
      if (!in_facet) throw InputError(name, lineno, "", "'vertex' outside a facet");
      Vec3d v;
      if (!(ls >> v.x >> v.y >> v.z) || !finite(v))
        throw InputError(name, lineno, "", "expected 'vertex x y z' with three finite numbers");
      verts.push_back(v);
    } else if (word == "endfacet") {
      if (!in_facet || verts.size() != 3)
        throw InputError(name, lineno, "", "a facet must have exactly three vertices");
      m.tris.push_back({verts[0], verts[1], verts[2]});
      in_facet = false;
    } else {
      throw InputError(name, lineno, "", "unexpected word '" + word.substr(0, 40) + "' in ascii STL");
    }
  }
  if (in_facet) throw InputError(name, lineno, "", "file ends inside a facet");
  return m;
}

} // namespace

Mesh parse_stl(const std::string& s, const std::string& name) {
  Mesh m;
  bool binary = false;
  if (s.size() >= 84) {
    std::uint32_t n = 0;
    std::memcpy(&n, s.data() + 80, 4);
    binary = s.size() == 84 + 50 * static_cast<std::size_t>(n);
  }
  if (binary)
    m = parse_binary(s, name);
  else if (s.compare(0, 5, "solid") == 0)
    m = parse_ascii(s, name);
  else
    throw InputError(name, 0, "", "not an STL file (neither ascii 'solid ...' nor a binary STL of consistent size)");
  finish_mesh(m, name);
  return m;
}

void finish_mesh(Mesh& m, const std::string& name) {
  if (m.tris.empty()) throw InputError(name, 0, "", "the mesh has no triangles");
  for (std::size_t i = 0; i < m.tris.size(); ++i)
    if (norm(cross(m.tris[i].b - m.tris[i].a, m.tris[i].c - m.tris[i].a)) <= 0)
      throw InputError(name, 0, "", "triangle " + std::to_string(i) + " is degenerate (zero area)");
  m.index = std::make_shared<const TriangleIndex>(m.tris);
  // Closed: every directed edge a -> b has exactly one b -> a (vertices compared exactly:
  // STL repeats their coordinates), and the signed volume is positive.
  std::map<std::array<double, 6>, int> edges;
  double volume = 0;
  for (const Triangle& t : m.tris) {
    const Vec3d v[3] = {t.a, t.b, t.c};
    for (int k = 0; k < 3; ++k) {
      const Vec3d &a = v[k], &b = v[(k + 1) % 3];
      const bool fwd = std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
      const Vec3d &lo = fwd ? a : b, &hi = fwd ? b : a;
      edges[{lo.x, lo.y, lo.z, hi.x, hi.y, hi.z}] += fwd ? 1 : 16;
    }
    volume += dot(t.a, cross(t.b, t.c)) / 6;
  }
  m.closed = volume > 0 && std::all_of(edges.begin(), edges.end(), [](const auto& e) { return e.second == 17; });
}

void triangles_near(const Mesh& m, const Vec3d& lo, const Vec3d& hi, std::vector<std::uint32_t>& out) {
  if (m.index) {
    m.index->overlapping(lo, hi, out);
    return;
  }
  out.resize(m.tris.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<std::uint32_t>(i);
}

Mesh read_stl(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "", "cannot open the mesh file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_stl(ss.str(), path);
}

Vec3d closest_point(const Triangle& t, const Vec3d& p) { return closest_point_on_triangle(t.a, t.b, t.c, p).point; }

} // namespace surge::geometry
