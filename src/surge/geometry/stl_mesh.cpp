#include "surge/geometry/stl_mesh.hpp"

#include "surge/core/error.hpp"

#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

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
  if (m.tris.empty()) throw InputError(name, 0, "", "the mesh has no triangles");
  for (std::size_t i = 0; i < m.tris.size(); ++i)
    if (norm(cross(m.tris[i].b - m.tris[i].a, m.tris[i].c - m.tris[i].a)) <= 0)
      throw InputError(name, 0, "", "triangle " + std::to_string(i) + " is degenerate (zero area)");
  return m;
}

Mesh read_stl(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "", "cannot open the mesh file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_stl(ss.str(), path);
}

Vec3d closest_point(const Triangle& t, const Vec3d& p) {
  const Vec3d ab = t.b - t.a, ac = t.c - t.a, ap = p - t.a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return t.a;
  const Vec3d bp = p - t.b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return t.b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return t.a + ab * (d1 / (d1 - d3));
  const Vec3d cp = p - t.c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return t.c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return t.a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return t.b + (t.c - t.b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = 1.0 / (va + vb + vc);
  return t.a + ab * (vb * denom) + ac * (vc * denom);
}

} // namespace surge::geometry
