#include "surge/geometry/particle_generators.hpp"

#include "surge/geometry/raster.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace surge::geometry {

int wall_layers(const Case& c) { return static_cast<int>(std::ceil(2.0 * c.sph.h_over_dp - 1e-9)); }

namespace {
// Coordinates (i + 1/2) dp from lo up to hi. A region short of a whole number of
// spacings by less than 1e-3 dp (a rounded dp in a case file) still gets its last layer.
std::vector<double> lattice(double lo, double hi, double dp) {
  std::vector<double> v;
  const auto n = static_cast<long>(std::floor((hi - lo) / dp + 1e-3));
  for (long i = 0; i < n; ++i) v.push_back(lo + (static_cast<double>(i) + 0.5) * dp);
  return v;
}
// The same number of coordinates, the lattice centred in [lo, hi]: the shortfall of a
// region that is not a whole number of spacings (under one spacing) is split between
// both ends instead of all of it at hi.
std::vector<double> lattice_centred(double lo, double hi, double dp) {
  std::vector<double> v = lattice(lo, hi, dp);
  const double shift = std::max(0.0, (hi - lo - static_cast<double>(v.size()) * dp) / 2);
  for (double& x : v) x += shift;
  return v;
}
// n = round((hi - lo) / dp) coordinates (i + 1/2) s from lo, the spacing s stretched so
// that they fill [lo, hi] exactly: the first and last lie s/2 from the ends.
long stretched_count(double lo, double hi, double dp) { return std::max(1L, std::lround((hi - lo) / dp)); }
double stretched_spacing(double lo, double hi, double dp) {
  return (hi - lo) / static_cast<double>(stretched_count(lo, hi, dp));
}
std::vector<double> lattice_stretched(double lo, double hi, double dp) {
  const long n = stretched_count(lo, hi, dp);
  const double s = stretched_spacing(lo, hi, dp);
  std::vector<double> v;
  for (long i = 0; i < n; ++i) v.push_back(lo + (static_cast<double>(i) + 0.5) * s);
  return v;
}
// The distance from the face at `f` (lo or hi) to the nearest coordinate of the lattice
// laid in [lo, hi] (lattice_stretched when `fit`, else lattice; the same expressions), without
// building it: one of its ends. Infinite for an empty lattice.
double first_layer(double lo, double hi, double dp, bool fit, double f) {
  const long n = fit ? stretched_count(lo, hi, dp) : static_cast<long>(std::floor((hi - lo) / dp + 1e-3));
  if (n < 1) return 1e300;
  const double s = fit ? stretched_spacing(lo, hi, dp) : dp;
  const double front = lo + 0.5 * s, back = lo + (static_cast<double>(n - 1) + 0.5) * s;
  return std::min(std::fabs(front - f), std::fabs(back - f));
}
bool is_open(const WallSpec& w, Face f) { return std::find(w.open.begin(), w.open.end(), f) != w.open.end(); }

// Signed distance to the closest triangle, positive on the side the normals point to;
// `at` receives the closest point. The search box grows until a triangle lies within it:
// every closer triangle then meets the box, and the candidates come in the mesh's order,
// so the result (ties included) is that of a loop over all triangles.
// Beyond `limit` a caller needs the side only: a terrain (a height field) gives it from its
// height at p, far cheaper than the growing search (other meshes search on).
// Whether p lies inside the closed mesh m (1) or outside (0), from the parity of the
// crossings of a vertical ray up from p; -1 when every try grazes an edge or vertex. For
// points farther than `nudge` x 1e6 from every triangle: a try that grazes is moved aside
// by a fraction of `nudge`, which does not take it across the surface.
int inside_closed(const Mesh& m, const Vec3d& p, double nudge) {
  thread_local std::vector<std::uint32_t> column;
  constexpr double e = 1e-9; // barycentric margin: closer to an edge is a graze
  for (int attempt = 0; attempt < 4; ++attempt) {
    const Vec3d q = p + Vec3d{0.3719 * attempt, 0.6173 * attempt, 0} * nudge;
    triangles_near(m, q, {q.x, q.y, 1e300}, column);
    int crossings = 0;
    bool grazed = false;
    for (const std::uint32_t i : column) {
      const Triangle& t = m.tris[i];
      const double det = (t.b.y - t.c.y) * (t.a.x - t.c.x) + (t.c.x - t.b.x) * (t.a.y - t.c.y);
      if (std::fabs(det) <= 1e-14 * (norm(t.b - t.a) * norm(t.c - t.a))) continue; // vertical: the ray runs past it
      const double l1 = ((t.b.y - t.c.y) * (q.x - t.c.x) + (t.c.x - t.b.x) * (q.y - t.c.y)) / det;
      const double l2 = ((t.c.y - t.a.y) * (q.x - t.c.x) + (t.a.x - t.c.x) * (q.y - t.c.y)) / det;
      const double l3 = 1 - l1 - l2;
      if (l1 < -e || l2 < -e || l3 < -e) continue;
      if (l1 < e || l2 < e || l3 < e) {
        grazed = true;
        break;
      }
      if (l1 * t.a.z + l2 * t.b.z + l3 * t.c.z > q.z) ++crossings;
    }
    if (!grazed) return crossings % 2;
  }
  return -1;
}

double signed_distance(const Mesh& m, const Vec3d& p, Vec3d* at = nullptr, double limit = 1e300) {
  // Beyond `limit` from the box around the triangles: no triangle is within limit, and the
  // point is outside (of a closed mesh; an open one's far side matters to no caller). The
  // lattice around a small detailed body is mostly such points: they cost no triangle
  // (the search below grows its box until it holds every triangle).
  if (!at && m.index && !m.heights && limit < 1e300) {
    const double d2 = m.index->box_distance2(p);
    if (d2 > limit * limit) return std::sqrt(d2);
  }
  thread_local std::vector<std::uint32_t> near;
  double best = 1e300, best_sign = 1;
  Vec3d best_point = p;
  for (double r = m.index ? m.index->cell() : 1e300;; r *= 2) {
    triangles_near(m, p - Vec3d{r, r, r}, p + Vec3d{r, r, r}, near);
    double best_align = -1;
    best = 1e300;
    for (const std::uint32_t i : near) {
      const Triangle& t = m.tris[i];
      const Vec3d c = closest_point(t, p);
      const Vec3d d = p - c;
      const double dist = norm(d);
      const double side = dot(d, t.normal());
      // Several triangles can share the closest point (an edge or vertex): take the one
      // whose normal is best aligned with p - c, which decides the side correctly.
      const double align = dist > 0 ? std::fabs(side) / dist : 1;
      if (dist < best - 1e-12 || (std::fabs(dist - best) <= 1e-12 && align > best_align)) {
        best = dist;
        best_sign = side < 0 ? -1 : 1;
        best_align = align;
        best_point = c;
      }
    }
    const bool all = !m.index || near.size() == m.tris.size();
    if (all || best + 1e-9 * r <= r) break;
    // No triangle within r >= limit: |d| > r, and the side is what the caller needs: under
    // a terrain or not, inside a closed mesh or not (the search would grow its box until
    // the nearest triangle, many of a detailed body, for every point deep inside it or in
    // its bounding box).
    if (r >= limit && m.heights && !at) {
      const double z = surface_height(*m.heights, p.x, p.y);
      if (!std::isnan(z)) return p.z >= z ? r : -r;
    }
    if (r >= limit && m.closed && !at)
      if (const int in = inside_closed(m, p, 1e-6 * limit); in >= 0) return in ? -r : r;
  }
  if (at) *at = best_point;
  return best * best_sign;
}
} // namespace

double stretched_cell_volume(const Box& b, double dp) {
  double v = 1;
  for (int k = 0; k < 3; ++k) v *= stretched_spacing(b.min[k], b.max[k], dp);
  return v;
}

std::vector<Vec3d> fill_box(const Box& b, double dp, BoxFill fill) {
  std::vector<Vec3d> pts;
  const auto axis =
      fill == BoxFill::Stretched ? lattice_stretched : (fill == BoxFill::Centred ? lattice_centred : lattice);
  const auto xs = axis(b.min.x, b.max.x, dp), ys = axis(b.min.y, b.max.y, dp), zs = axis(b.min.z, b.max.z, dp);
  pts.reserve(xs.size() * ys.size() * zs.size());
  for (double z : zs)
    for (double y : ys)
      for (double x : xs) pts.push_back({x, y, z});
  return pts;
}

std::vector<Vec3d> box_wall(const WallSpec& w, double dp, int layers, bool fit) {
  std::vector<Vec3d> pts;
  const Box& b = w.box;
  if (w.solid) {
    // The lattice stretched per axis to fit the box exactly (as a tank's interior), so that
    // every face lies half a spacing in front of its first layer: a box that is not a whole
    // number of spacings otherwise kept its far faces up to 1.5 dp in front of the wall
    // particles, a strip water could enter before any wall particle stopped it.
    const double band = layers * dp;
    const auto axis = fit ? lattice_stretched : lattice;
    const auto xs = axis(b.min.x, b.max.x, dp), ys = axis(b.min.y, b.max.y, dp), zs = axis(b.min.z, b.max.z, dp);
    for (double z : zs)
      for (double y : ys)
        for (double x : xs) {
          const double d = std::min({x - b.min.x, b.max.x - x, y - b.min.y, b.max.y - y, z - b.min.z, b.max.z - z});
          if (d < band) pts.push_back({x, y, z});
        }
    return pts;
  }
  // Per axis: layers below, the interior (spacing stretched to fit exactly), layers above.
  // Each coordinate carries -1 (below), 0 (inside) or +1 (above).
  struct C {
    double v;
    int side;
  };
  auto axis = [&](double lo, double hi) {
    std::vector<C> v;
    for (int k = layers - 1; k >= 0; --k) v.push_back({lo - (k + 0.5) * dp, -1});
    for (double x : lattice_stretched(lo, hi, dp)) v.push_back({x, 0});
    for (int k = 0; k < layers; ++k) v.push_back({hi + (k + 0.5) * dp, 1});
    return v;
  };
  const auto xs = axis(b.min.x, b.max.x), ys = axis(b.min.y, b.max.y), zs = axis(b.min.z, b.max.z);
  const Face lowf[3] = {Face::XMin, Face::YMin, Face::ZMin}, highf[3] = {Face::XMax, Face::YMax, Face::ZMax};
  for (const auto& z : zs)
    for (const auto& y : ys)
      for (const auto& x : xs) {
        const int side[3] = {x.side, y.side, z.side};
        if (side[0] == 0 && side[1] == 0 && side[2] == 0) continue;
        bool skip = false;
        for (int k = 0; k < 3; ++k)
          if ((side[k] < 0 && is_open(w, lowf[k])) || (side[k] > 0 && is_open(w, highf[k]))) skip = true;
        if (!skip) pts.push_back({x.v, y.v, z.v});
      }
  return pts;
}

Box bounds(const Mesh& m) {
  Box b{{1e300, 1e300, 1e300}, {-1e300, -1e300, -1e300}};
  for (const auto& t : m.tris)
    for (const Vec3d& v : {t.a, t.b, t.c})
      for (int k = 0; k < 3; ++k) {
        b.min[k] = std::min(b.min[k], v[k]);
        b.max[k] = std::max(b.max[k], v[k]);
      }
  return b;
}

std::vector<Vec3d> mesh_wall(const Mesh& m, const Vec3d& origin, double dp, int layers, const Box* clip) {
  const Box box = bounds(m);
  const double band = layers * dp;
  Vec3d lo = box.min - Vec3d{band, band, band}, hi = box.max + Vec3d{band, band, band};
  if (clip)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::max(lo[k], clip->min[k]);
      hi[k] = std::min(hi[k], clip->max[k]);
    }
  long i0[3], i1[3];
  for (int k = 0; k < 3; ++k) {
    // Without a clip box, a spacing beyond the band (as before clip boxes existed); with
    // one, the lattice points inside it.
    i0[k] = clip ? static_cast<long>(std::ceil((lo[k] - origin[k]) / dp - 0.5))
                 : static_cast<long>(std::floor((lo[k] - origin[k]) / dp - 0.5));
    i1[k] = clip ? static_cast<long>(std::floor((hi[k] - origin[k]) / dp - 0.5))
                 : static_cast<long>(std::ceil((hi[k] - origin[k]) / dp - 0.5));
  }
  std::vector<Vec3d> pts;
  for (long iz = i0[2]; iz <= i1[2]; ++iz)
    for (long iy = i0[1]; iy <= i1[1]; ++iy)
      for (long ix = i0[0]; ix <= i1[0]; ++ix) {
        const Vec3d p{origin.x + (static_cast<double>(ix) + 0.5) * dp, origin.y + (static_cast<double>(iy) + 0.5) * dp,
                      origin.z + (static_cast<double>(iz) + 0.5) * dp};
        const double d = signed_distance(m, p, nullptr, band);
        if (d <= 0 && d > -band) pts.push_back(p);
      }
  return pts;
}

Vec3d ghost_point(const WallSpec& w, const Mesh* mesh, const Vec3d& p) {
  Vec3d s = p;
  if (w.is_mesh) {
    (void)signed_distance(*mesh, p, &s);
  } else if (!w.solid) {
    // Outside a tank box: the closest point of the box is p clamped to it (a face, an
    // edge or a corner), so corner particles mirror diagonally into the water.
    for (int k = 0; k < 3; ++k) s[k] = std::clamp(p[k], w.box.min[k], w.box.max[k]);
  } else {
    // Inside a solid box: the nearest face.
    double best = 1e300;
    for (int k = 0; k < 3; ++k)
      for (const double f : {w.box.min[k], w.box.max[k]})
        if (std::fabs(p[k] - f) < best) {
          best = std::fabs(p[k] - f);
          s = p;
          s[k] = f;
        }
  }
  return s * 2.0 - p;
}

Reach wall_reach(const WallSpec& w, const Mesh* mesh, const Vec3d& p, const Vec3d& mirror, double dp, bool fit) {
  Reach r;
  if (w.is_mesh) {
    // The sphere reaches dp/4 in front of the particle's face and no further, as a box's
    // (a lattice point just behind the surface otherwise bulged 0.7 dp out of it).
    r.patch = 0.75 * dp;
    r.sphere = std::min(0.75 * dp, 0.5 * norm(mirror) + 0.25 * dp);
    // Near a convex edge the particle mirrors through its closest point (on the edge,
    // diagonally) or through one face; it also holds each other face whose triangles
    // lie within a spacing of it (its first layer; up to three faces, coplanar triangles
    // once).
    const Vec3d mirror_dir = norm(mirror) > 0 ? mirror * (1 / norm(mirror)) : Vec3d{};
    thread_local std::vector<std::uint32_t> near;
    triangles_near(*mesh, p - Vec3d{dp, dp, dp}, p + Vec3d{dp, dp, dp}, near);
    for (const std::uint32_t i : near) {
      const Triangle& t = mesh->tris[i];
      const Vec3d n = t.normal();
      const double behind = dot(t.a - p, n); // > 0: p behind the triangle's plane
      if (!(behind > 0) || norm(closest_point(t, p) - p) >= dp) continue;
      const Vec3d o = n * (2 * behind);
      bool known = norm(n - mirror_dir) < 1e-6;
      for (const auto& f : r.faces) known = known || norm(f - o) < 1e-9 * dp;
      if (!known && r.faces.size() < 3) r.faces.push_back(o);
    }
    return r;
  }
  const Box& b = w.box;
  // The spacing of the lattice laid in the box: stretched to fit it, or dp (a solid box of
  // the dynamic boundary, box_wall's `fit` off); a tank's layers lie dp apart across its faces.
  auto spacing = [&](int k) { return fit ? stretched_spacing(b.min[k], b.max[k], dp) : dp; };
  double s = w.solid ? 0.0 : dp;
  for (int k = 0; k < 3; ++k) s = std::max(s, spacing(k));
  // 0.75 s: the patches of a face's particles overlap (a point of the face is at most
  // s/sqrt(2) from the nearest one).
  r.patch = 0.75 * s;
  r.sphere = 0.75 * s;
  if (!w.solid) return r;
  // A solid box's particle in the first layer of two or three faces (an edge, a corner)
  // mirrors through one of them; without the others the strips of those faces beside the
  // edge, a quarter spacing wide, have no patch of their own and water enters there. The
  // first layer is the lattice coordinate nearest the face: half a spacing behind it on a
  // fitted lattice, between half and one and a half on the case's (at the box's far faces).
  double nearest = 1e300;
  for (int k = 0; k < 3; ++k) {
    for (const double f : {b.min[k], b.max[k]}) {
      const double d = std::fabs(p[k] - f);
      nearest = std::min(nearest, d);
      if (!(d < first_layer(b.min[k], b.max[k], dp, fit, f) + 1e-6 * dp)) continue;
      Vec3d o{};
      o[k] = 2 * (f - p[k]);
      if (norm(o - mirror) > 1e-9 * dp) r.faces.push_back(o);
    }
  }
  // The sphere reaches dp/4 in front of the particle's face, never beyond the faces' own
  // hold (a sphere bulging past it deflects the water running along the face).
  r.sphere = std::min(r.sphere, nearest + 0.25 * dp);
  return r;
}

bool blocked_by(const WallSpec& w, const Mesh* mesh, const Vec3d& p, double dp, double mesh_clearance) {
  if (w.is_mesh) {
    const double d = signed_distance(*mesh, p, nullptr, 4 * dp);
    return d < mesh_clearance * dp + (mesh_clearance > 0 ? 0.0 : 1e-12) && (w.solid || d > -4 * dp);
  }
  // Water dp/2 from a solid box's face is where it belongs (as at a tank's faces): only
  // closer than that is blocked (1e-6 dp of slack, so that a lattice point on dp/2 stays).
  return w.solid && w.box.contains(p, 0.5 * dp * (1 - 1e-6));
}

bool behind_wall(const WallSpec& w, const Mesh* mesh, const Vec3d& p, double band) {
  if (w.is_mesh) {
    const double d = signed_distance(*mesh, p, nullptr, band);
    return d < 0 && (w.solid || d > -band);
  }
  const Box& b = w.box;
  if (w.solid) return b.contains(p, -1e-12); // strictly inside
  // A tank: outside its interior, inside the layers around its closed faces.
  const Face lowf[3] = {Face::XMin, Face::YMin, Face::ZMin}, highf[3] = {Face::XMax, Face::YMax, Face::ZMax};
  bool outside = false;
  for (int k = 0; k < 3; ++k) {
    const double lo = b.min[k] - (is_open(w, lowf[k]) ? 0 : band), hi = b.max[k] + (is_open(w, highf[k]) ? 0 : band);
    if (p[k] < lo || p[k] > hi) return false; // beyond the layers, or through an open face
    outside = outside || p[k] < b.min[k] || p[k] > b.max[k];
  }
  return outside;
}

} // namespace surge::geometry
