// No penetration through walls (a kinematic safety net, after DualSPHysics's mDBC "no
// penetration" variant, in surge's own geometric form), with either wall model
// (sph.no_penetration, on by default).
//
// With mDBC the water sits half a spacing from each wall face, and a wall particle's
// pressure is the fluid's at its ghost node. Where the fluid there is a thin sheet with a
// slightly negative pressure (a jet running up a wall, a film sliding along it), nothing
// repels it and its pairs with the wall particles pull it through the face; in impacts a
// particle can also be driven through. Each wall particle knows the face it mirrors
// through (its ghost offset o: the face lies at x_b + o/2 with normal o/|o|), so every
// fluid particle finds, among its wall neighbours' faces, the one it would reach first at
// its present velocity (the nearest if it approaches none) and, in the update, is kept at
// least a quarter spacing in front of it (one face per step suffices: a step moves water
// far less than dp/4, so the face it approaches next is the one taken next step): the part of its motion that
// would take it closer is removed (an inelastic normal impact on the wall; the tangential
// motion is kept). Water at its natural distance (dp/2) never feels it. The dynamic
// boundary holds water about a spacing off by its pressure, but where spheres of a slide
// squeeze water against the floor a few particles were pushed up to 2 mm into it (the
// shortened slide at dp = 2.5 cm, docs/validation.md): the same planes hold them there.
#pragma once
#include "surge/core/types.hpp"

namespace surge::sph {

// How far one wall particle holds water off (geometry::wall_reach, from the wall lattice
// around it): the half-width of its patch of face, the radius of its sphere, and the
// faces it holds besides the one it mirrors through (a solid box's edges and corners):
// `extra` = 4 * (index of the first in the extra-face offsets) + how many, or -1.
struct WallReach {
  Real patch = 0, sphere = 0;
  std::int32_t extra = -1;
};

// A wall particle's ghost offset (its face lies at x_b + offset/2) and reach. Walls are
// lattices: their particles share a few of these (a box: one per layer of each face, edge
// and corner), so each particle holds the index of its row (4 B instead of 24).
struct WallRow {
  Vec3 offset; // unused where the wall model keeps the offsets (WallHoldView::offset)
  WallReach reach;
};

// What the rates kernel reads of the wall particles (WallHold owns it), by b = id -
// first_id (wall ids come before body ids): wall_offset and wall_reach.
struct WallHoldView {
  bool hold = false; // the no-penetration condition is on: fluid notes the wall plane it would reach first
  std::uint32_t first_id = 0;
  const Vec3* offset = nullptr;       // the wall model's ghost offsets (mDBC), or null: the rows'
  const std::uint32_t* row = nullptr; // each wall particle's row
  const WallRow* rows = nullptr;
  const Vec3* extra_face = nullptr; // offsets of the faces in WallReach::extra
};

[[nodiscard]] SURGE_HD inline Vec3 wall_offset(const WallHoldView& gh, std::uint32_t b) {
  return gh.offset ? gh.offset[b] : gh.rows[gh.row[b]].offset;
}
[[nodiscard]] SURGE_HD inline WallReach wall_reach(const WallHoldView& gh, std::uint32_t b) {
  return gh.rows[gh.row[b]].reach;
}

// A wall face near a fluid particle: the plane n.x = c, n pointing into the water. The
// default (n = 0) is no face: every point is far in front of it.
// A moving wall's plane moves along n at vn (the wall particle's velocity along n): the
// update holds water in front of where it will be and removes only the motion towards it
// relative to the wall (vn = 0 for a still wall: the plain condition, the same bits).
struct WallPlane {
  Vec3 n{};
  Real c = Real(-1e30);
  Real vn = 0;
  [[nodiscard]] SURGE_HD Real distance(const Vec3& x) const { return dot(n, x) - c; }
  // The plane dt later.
  [[nodiscard]] SURGE_HD WallPlane after(Real dt) const { return vn == 0 ? *this : WallPlane{n, c + vn * dt, vn}; }
};

// The face that wall particle b (ghost offset o) mirrors through, seen from the fluid
// particle at x_b + r (r = x_i - x_b): a candidate only if x_i is in front of it and the
// point of the face below x_i lies within `patch` (0.75 spacings) of b's own point of it.
// A face the particle is behind is not one it faces: a neighbouring face's plane (a box's
// top seen from beside it) or a face that touches another wall (a solid box's bottom on
// the tank's floor, whose plane would otherwise hold the water beside the box below the
// floor).
SURGE_HD inline bool face_below(const Vec3& xb, const Vec3& o, const Vec3& r, Real patch, WallPlane& out, Real& dist) {
  const Real len2 = dot(o, o);
  if (!(len2 > 0)) return false;
  const Vec3 n = o * (1 / std::sqrt(len2));
  const Vec3 rs = r - o * Real(0.5); // x_i - (face point of b)
  const Real d = dot(rs, n);
  if (d < 0) return false;
  const Real lateral2 = dot(rs, rs) - d * d;
  if (lateral2 > patch * patch) return false;
  out = WallPlane{n, dot(n, xb + o * Real(0.5))};
  dist = d;
  return true;
}

// Which plane holds a fluid particle off, as the rates pass chose it: wall particle j's own
// face (what 0), one of its extra faces (what 1 to 3) or its sphere (what 4), coded as
// j << 3 | what; no_wall when none. 4 B per particle where the plane itself is 16: the
// update rebuilds the plane from it (held_plane, wcsph_rates.hpp) from the inputs the rates
// pass used, so with the same bits.
using WallChoice = std::uint32_t;
inline constexpr WallChoice no_wall = ~WallChoice{0};
inline constexpr int own_face = 0, sphere_of_wall = 4;
[[nodiscard]] SURGE_HD inline WallChoice wall_choice(int j, int what) {
  return static_cast<WallChoice>(j) << 3 | static_cast<WallChoice>(what);
}
// The wall particle and the what of a choice (not no_wall).
[[nodiscard]] SURGE_HD inline int chosen_wall(WallChoice c) { return static_cast<int>(c >> 3); }
[[nodiscard]] SURGE_HD inline int chosen_what(WallChoice c) { return static_cast<int>(c & 7); }
// The most particles one process can hold with the no-penetration condition on.
inline constexpr long long max_held_particles = 1LL << 29;

// The offset of face `what` (own_face, or 1 to 3: the extra faces) of a wall particle.
[[nodiscard]] SURGE_HD inline Vec3 face_offset(const WallReach& reach, const Vec3& own, const Vec3* extra, int what) {
  return what == own_face ? own : extra[(reach.extra >> 2) + what - 1];
}

// Calls f(plane, what) for each face wall particle b (at xb, ghost offset `own`, reach
// `reach`, extra-face offsets `extra`) holds the fluid particle at xb + r off: its own face
// (what = own_face), then its extra ones (1 to 3), each where face_below finds the particle
// in front of it within the patch (the rates kernel and the coverage tests share this).
template <class F>
SURGE_HD void for_each_held_face(const Vec3& xb, const Vec3& r, const WallReach& reach, const Vec3& own,
                                 const Vec3* extra, F&& f) {
  WallPlane w;
  Real d;
  const int faces = 1 + (reach.extra >= 0 ? reach.extra & 3 : 0);
  for (int what = own_face; what < faces; ++what)
    if (face_below(xb, face_offset(reach, own, extra, what), r, reach.patch, w, d)) f(w, what);
}

// How far in front of a wall face fluid is kept.
[[nodiscard]] SURGE_HD inline Real keep_off_distance(Real dp) { return dp / 4; }

// The sphere of radius `radius` around a wall particle, as the plane tangent to it facing
// the fluid particle (r = x_i - x_b, |r| = dist), moved back by dmin: keeping the fluid
// particle dmin in front of that plane keeps it outside the sphere. Faces alone leave
// holes where a wall particle mirrors through another face (next to a solid box's edges
// the strip of each face beside the edge has no particle of its own): the spheres cover
// every wall particle (a face's at 0.75 spacings, dp/4 in front of the face above it; an
// edge's or a corner's past the edge line), the faces keep water a quarter spacing off
// flat walls between the particles.
[[nodiscard]] SURGE_HD inline WallPlane sphere_plane(const Vec3& xb, const Vec3& r, Real dist, Real radius, Real dmin) {
  const Vec3 n = r * (1 / dist);
  return WallPlane{n, dot(n, xb) + radius - dmin};
}

// Of the planes seen so far, the one to hold the particle at x (moving at v) off in this
// step, dmin in front: the most violated one if any is (it was pushed past one last step
// while another was held) or one it touches, else the one it would reach first at its
// velocity, else the nearest. Touching counts as violated: water held at a face has lost
// its velocity into it, so that face ranks last by contact time, and water running fast
// along a flat wall then chose the sphere of a wall particle ahead of it and was pushed
// into the face's dmin by the step's forces (by up to 1.2 um at dp = 1 cm, every other
// step: test_walls_hold_water with laminar viscosity, 2026-12-06).
struct FirstContact {
  WallChoice choice = no_wall;
  int tier = 3;
  Real key = Real(1e30);
  // A particle less than touching * dmin beyond dmin from a plane touches it: the hold
  // leaves it at dmin up to the rounding of its position (about 1e-7 of dmin in float).
  static constexpr Real touching = Real(1e-4);
  SURGE_HD void consider(const WallPlane& w, WallChoice c, const Vec3& x, const Vec3& v, Real dmin) {
    const Real d = w.distance(x) - dmin;
    const Real vn = dot(v, w.n);
    const int t = d < touching * dmin ? 0 : (vn < 0 ? 1 : 2);
    const Real k = t == 0 ? d : (t == 1 ? d / -vn : d);
    if (t < tier || (t == tier && k < key)) {
      choice = c;
      tier = t;
      key = k;
    }
  }
};

// Keeps the particle at x (moving at v) at least dmin in front of face w: moves it back
// to dmin and removes the normal velocity towards the face, relative to the face's own
// (also from v_prev, the leap-frog's other velocity, when given). Returns true if it acted.
SURGE_HD inline bool keep_off_face(const WallPlane& w, Real dmin, Vec3& x, Vec3& v, Vec3* v_prev = nullptr) {
  const Real d = w.distance(x);
  if (!(d < dmin)) return false;
  x += w.n * (dmin - d);
  const Real vn = dot(v, w.n) - w.vn; // towards the face, relative to it
  if (vn < 0) v -= w.n * vn;
  if (v_prev) {
    const Real pn = dot(*v_prev, w.n) - w.vn;
    if (pn < 0) *v_prev -= w.n * pn;
  }
  return true;
}

} // namespace surge::sph
