#include "surge/dem/dem_solver.hpp"
#include "surge/dem/integration.hpp"
#include "surge/dem/pair_terms.hpp"
#if defined(SURGE_SIMD)
#include "surge/dem/dem_simd.hpp"
#include "surge/par/simd_isa.hpp"
#endif

#include "surge/algo/algo.hpp"

#include "surge/geometry/box_buckets.hpp"
#include "surge/geometry/closest_point.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace surge::dem {
namespace detail {

// The wall triangles sphere (x, r) touches, one per point of contact: face contacts
// first; an edge or vertex contact is dropped when an accepted triangle already
// contains its point (the sphere is over that triangle's face, or the same edge or
// vertex was accepted from a neighbouring triangle). Returns the count.
struct WallCandidate {
  int tri;
  Vec3 point;
  Real dist;
  bool face;
};
// Candidates: the triangles items[begin, end) within r of x (up to max_wall_candidates).
SURGE_HD inline void add_candidates(const WallTriangle* tris, const std::uint32_t* items, std::uint32_t begin,
                                    std::uint32_t end, const Vec3& x, Real r, WallCandidate* cand, int& nc) {
  for (std::uint32_t k = begin; k < end && nc < max_wall_candidates; ++k) {
    const int t = static_cast<int>(items[k]);
    const WallTriangle& tr = tris[t];
    const auto cp = geometry::closest_point_on_triangle(tr.a, tr.b, tr.c, x);
    const Real d = norm(x - cp.point);
    if (!(d < r) || d <= 0) continue;
    cand[nc++] = {t, cp.point, d, cp.region == geometry::Region::Face};
  }
}
// The contacts among nc candidates (faces first, then edges and vertices not on an
// accepted triangle of the same mesh), into out; returns their count.
SURGE_HD inline int distinct_contacts(const WallTriangle* tris, const WallCandidate* cand, int nc, Real r,
                                      WallCandidate* out) {
  const Real tol = Real(1e-4) * r;
  int n = 0;
  for (int pass = 0; pass < 2; ++pass) { // faces, then edges and vertices
    for (int k = 0; k < nc; ++k) {
      if (cand[k].face != (pass == 0)) continue;
      bool keep = true;
      for (int a = 0; a < n && keep; ++a) {
        if (tris[out[a].tri].mesh != tris[cand[k].tri].mesh) continue;
        const WallTriangle& ta = tris[out[a].tri];
        const Vec3 on_a = geometry::closest_point_on_triangle(ta.a, ta.b, ta.c, cand[k].point).point;
        if (norm(on_a - cand[k].point) < tol) keep = false; // same point, or on an accepted triangle
      }
      if (keep) out[n++] = cand[k];
    }
  }
  return n;
}

// The wall triangles sphere (x, r) touches, one per point of contact: the still ones of
// its grid cell and those of the moving bodies it is near.
SURGE_HD inline int wall_contacts(const WallTriangle* tris, const TriangleGridView& grid, const WallBodiesView& bodies,
                                  const Vec3& x, Real r, WallCandidate* out) {
  WallCandidate cand[max_wall_candidates];
  int nc = 0;
  std::uint32_t begin = 0, end = 0;
  if (grid.start) grid.range(x, begin, end);
  add_candidates(tris, grid.items, begin, end, x, r, cand, nc);
  for (int b = 0; b < bodies.n; ++b)
    if (bodies.near(b, x, r)) add_candidates(tris, bodies.items, bodies.start[b], bodies.start[b + 1], x, r, cand, nc);
  return distinct_contacts(tris, cand, nc, r, out);
}

// A wall's velocity at a contact point and its angular velocity: zero for a still wall
// (body < 0, or any wall before set_wall_bodies: a pack settling against a moving wall's
// placement), else those of its body's rigid motion.
struct WallMotion {
  Vec3 vel{}, omega{};
};
SURGE_HD inline WallMotion wall_motion(const WallBodiesView& b, int body, const Vec3& at) {
  if (body < 0 || body >= b.n || !b.state) return {};
  const RigidState& s = b.state[body];
  return {s.vel + cross(s.omega, at - s.pos), s.omega};
}

// The pair input of sphere i against a wall (a plane or triangle of infinite mass, never
// bonded; the law says how the wall mixes), and the law's constants for it.
template <class L>
struct WallPair {
  PairInput in;
  typename L::Pair law;
};
template <class L>
SURGE_HD inline WallPair<L> wall_pair_input(const DemView& v, const Material* mats, int i, int wall_material,
                                            const Vec3& n, Real un, const WallMotion& wall) {
  PairInput in;
  in.n = n;
  in.un = un;
  in.ra = v.radius[i];
  in.rb = 0;
  in.va = v.vel[i];
  in.wa = v.omega[i];
  in.vb = wall.vel;
  in.wb = wall.omega;
  Material unbondable = mats[wall_material];
  unbondable.bonded = false;
  const typename L::Pair law = L::wall(mats[v.material[i]], unbondable, in.ra, v.mass[i]);
  MixedPair mixed = v.mixed[v.material[i] * v.n_materials + wall_material];
  mixed.bond_cn = mixed.bond_cs = 0;  // a wall never bonds
  set_mixed(mixed, in.ra, in.ra, in); // as a sphere of the same radius (SPEC §3)
  return {in, law};
}

// The pair terms of sphere a (the lower id) with b (sorted indices) for pair p: the
// history of the pair and its stored law, the rest from the two spheres and materials.
template <class L>
SURGE_HD inline PairResult sphere_pair(const DemView& v, int a, int b, std::uint32_t p, Real dist, Real dt) {
  const PairInput in = sphere_pair_input(v.rel(a, b), dist, v.radius[a], v.radius[b], v.vel[a], v.omega[a], v.vel[b],
                                         v.omega[b], v.mixed[v.material[a] * v.n_materials + v.material[b]]);
  return pair_terms<L>(in, load_law<typename L::Pair>(v.law[p]), springs_of(v.hist[p]), dt);
}

// The contact law's constants of spheres a and b (L::pair, with their reduced mass).
template <class L>
SURGE_HD inline typename L::Pair sphere_law(const DemView& v, const Material* mats, int a, int b) {
  const Real mstar = v.mass[a] * v.mass[b] / (v.mass[a] + v.mass[b]);
  return L::pair(mats[v.material[a]], mats[v.material[b]], v.radius[a], v.radius[b], mstar);
}

// Each pair's law constants, once per list, written by the pair's A sphere: the step
// reads them instead of mixing the materials again.
template <class L>
void pair_laws(const DemView& v, const Material* mats) {
  par::parallel_for(
      v.n, SURGE_LAMBDA(int a) {
        neighbour::for_each_own_pair(v.list, a, [&](std::uint32_t, int b, std::uint32_t p) {
          store_law(v.law[p], sphere_law<L>(v, mats, a, b));
        });
      });
}

// The points around which a sphere's partners are searched on periodic axes: its centre
// and each of its images (whole periods away, -2 to 2, as spheres lie within half a
// period beyond a face) that reaches the grid [lo, hi). The period being over twice the
// search, each partner is found once, through its nearest image.
struct PeriodicQueries {
  domain::PeriodicAxes per;
  Vec3 lo, hi;
  Real search;
  template <class Query>
  SURGE_HD void operator()(const Vec3& x, Query&& query) const {
    int first[3], last[3];
    for (int k = 0; k < 3; ++k) {
      first[k] = per.on[k] ? -2 : 0;
      last[k] = -first[k];
    }
    for (int sz = first[2]; sz <= last[2]; ++sz)
      for (int sy = first[1]; sy <= last[1]; ++sy)
        for (int sx = first[0]; sx <= last[0]; ++sx) {
          const Vec3 q = x + Vec3(static_cast<Real>(sx) * per.len.x, static_cast<Real>(sy) * per.len.y,
                                  static_cast<Real>(sz) * per.len.z);
          bool reaches = true;
          for (int k = 0; k < 3; ++k) reaches = reaches && q[k] >= lo[k] - search && q[k] < hi[k] + search;
          if (reaches) query(q);
        }
  }
};

// List pass 1 of the DEM: each sphere lists the spheres within r_i + r_j + skin and those
// bonded to it (within the grid's reach `search`); returns the most any sphere wanted.
int list_spheres(const DemView& v, const neighbour::GridView& g, const ContactSlot* old_hist, Real search, Real skin,
                 std::uint32_t* a_count) {
  const auto listed = SURGE_LAMBDA(int i, int j, Real r2, const ContactSlot* old) {
    const Real cut = v.radius[i] + v.radius[j] + skin;
    return r2 < cut * cut || (old != nullptr && old->bonded != 0);
  };
  if (!v.period.any())
    return neighbour::list_partners<max_contacts>(v.list, v.id, v.pos, v.n, g, old_hist, search, a_count, listed);
  const Vec3 ghi =
      g.spec.lo +
      Vec3(static_cast<Real>(g.spec.nx), static_cast<Real>(g.spec.ny), static_cast<Real>(g.spec.nz)) * g.spec.cell;
  return neighbour::list_partners<max_contacts>(v.list, v.id, v.pos, v.n, g, old_hist, search, a_count, listed,
                                                PeriodicQueries{v.period, g.spec.lo, ghi, search});
}

// Pass 1 of a step: each pair once, by its A sphere (lower id), from the history of its
// pair: the history is updated in place and the forces written beside it.
template <class L>
void pair_pass(const DemView& v, Real dt) {
  par::parallel_for_uneven(
      v.n, SURGE_LAMBDA(int i) {
        const Real ri = v.radius[i];
        // The pairs i is A of (the partner evaluates the others).
        neighbour::for_each_own_pair(v.list, i, [&](std::uint32_t, int j, std::uint32_t p) {
          const Real dist = norm(v.rel(i, j));
          const std::uint32_t partner = v.hist[p].partner;
          if (!in_contact(dist, ri + v.radius[j], v.hist[p].bonded != 0)) {
            // Not touching: the contact's history ends (the pair stays listed).
            v.hist[p] = ContactSlot{};
            v.hist[p].partner = partner;
            v.pair[p] = PairForce{};
            return;
          }
          const PairResult r = sphere_pair<L>(v, i, j, p, dist, dt);
          v.hist[p] = slot_of(r.springs, partner);
          v.pair[p] = {r.force_a, r.torque_a, r.torque_b, 1U | (r.broke ? 2U : 0U)};
        });
      });
}

// The wall contacts of sphere i (planes, then mesh triangles), added to its force f,
// torque t and contact count; their histories by partner id in its few wall slots.
struct WallsView {
  const Material* mats;
  const Plane* planes;
  int n_planes;
  const WallTriangle* tris;
  TriangleGridView tri_grid;
  WallBodiesView bodies;
  WallReaction* react;    // max_wall_slots per sphere, by id: with moving walls only, else null
  std::uint32_t* touches; // per sphere (sorted): 1 when a recorded contact is with a moving body; with react
};
template <class L>
SURGE_HD inline void wall_terms(const DemView& v, const WallsView& w, Real dt, int i, Vec3& f, Vec3& t, int& used) {
  const Vec3 xi = v.pos[i];
  const Real ri = v.radius[i];
  const std::size_t row = static_cast<std::size_t>(v.id[i]) * max_wall_slots;
  ContactSlot* wrow = v.wall_hist + row;
  bool near = w.tri_grid.start != nullptr; // most spheres touch no wall: their empty slots stay as they are
  for (int k = 0; k < w.n_planes; ++k) near = near || dot(xi - w.planes[k].point, w.planes[k].normal) < ri;
  for (int b = 0; b < w.bodies.n; ++b) near = near || w.bodies.near(b, xi, ri);
  if (!near) {
    if (wrow[0].partner != no_partner) // (slots are held from the first on)
      for (int k = 0; k < max_wall_slots; ++k) wrow[k] = ContactSlot{};
    if (w.touches) w.touches[i] = 0;
    return;
  }
  ContactSlot old_w[max_wall_slots];
  for (int k = 0; k < max_wall_slots; ++k) old_w[k] = wrow[k];
  int wused = 0;
  std::uint32_t touches = 0;
  auto wall = [&](const Vec3& n, Real un, std::uint32_t partner, int material, int body, const Vec3& at) {
    const WallPair<L> wp = wall_pair_input<L>(v, w.mats, i, material, n, un, wall_motion(w.bodies, body, at));
    ContactSlot s{};
    for (int k = 0; k < max_wall_slots; ++k)
      if (old_w[k].partner == partner) s = old_w[k];
    const PairResult r = pair_terms<L>(wp.in, wp.law, springs_of(s), dt);
    f += r.force_a;
    t += r.torque_a;
    ++used;
    if (wused < max_wall_slots) {
      wrow[wused] = slot_of(r.springs, partner);
      if (w.react) {
        w.react[row + wused] = {r.force_a, r.torque_a};
        touches |= body >= 0 ? 1U : 0U;
      }
      ++wused;
    }
  };
  for (int k = 0; k < w.n_planes; ++k) {
    const Plane pl = w.planes[k];
    const Real dist = dot(xi - pl.point, pl.normal);
    if (dist < ri)
      wall(pl.normal, ri - dist, plane_partner | static_cast<std::uint32_t>(k), pl.material, pl.body,
           xi - pl.normal * dist);
  }
  if (w.tri_grid.start || w.bodies.n > 0) {
    WallCandidate touched[max_wall_candidates];
    const int nt = wall_contacts(w.tris, w.tri_grid, w.bodies, xi, ri, touched);
    for (int k = 0; k < nt; ++k) {
      const WallTriangle& tr = w.tris[touched[k].tri];
      wall((xi - touched[k].point) * (1 / touched[k].dist), ri - touched[k].dist,
           triangle_partner | static_cast<std::uint32_t>(touched[k].tri), tr.material, tr.body, touched[k].point);
    }
  }
  for (int k = wused; k < max_wall_slots; ++k) wrow[k] = ContactSlot{};
  if (w.touches) w.touches[i] = touches;
}

// Symmetry faces: the sphere i, when within the list's reach of one (the frame's band),
// meets the mirror images of the spheres near its own mirror point, itself included.
// The images are not copied: f(j, image, x, u, w) is called for each sphere j the grid
// finds within `search` of that point, with the image's position, velocity and spin (a
// pseudovector: det(R) R w), in the grid's order (the same on any thread count).
struct MirrorSearch {
  neighbour::GridView grid; // the spheres' grid of the last sort; searched within the frame's band
  const Material* mats;
};
SURGE_HD inline bool near_mirror(const DemView& v, const Vec3& x, domain::AxisShifts* shifts) {
  bool near = false;
  for (int k = 0; k < 3; ++k) {
    shifts[k] = domain::axis_shifts(v.mirror, k, x[k]);
    near = near || shifts[k].count > 1;
  }
  return near;
}
template <class F>
SURGE_HD inline void for_each_mirror_partner(const DemView& v, const MirrorSearch& m, int i,
                                             const domain::AxisShifts* sh, F&& f) {
  const Vec3 xi = v.pos[i];
  for (int sz = sh[2].first; sz < sh[2].first + sh[2].count; ++sz)
    for (int sy = sh[1].first; sy < sh[1].first + sh[1].count; ++sy)
      for (int sx = sh[0].first; sx < sh[0].first + sh[0].count; ++sx) {
        if (sx == 0 && sy == 0 && sz == 0) continue;
        const int s[3] = {sx, sy, sz};
        const int image = (sx + 1) + 3 * (sy + 1) + 9 * (sz + 1);
        Vec3 q = xi;
        for (int k = 0; k < 3; ++k) q[k] = domain::shifted(v.mirror, k, xi[k], s[k]);
        const Real search = v.mirror.band.x; // the list's reach, on every axis
        neighbour::for_each_neighbour(m.grid, q, search * search, [&](int j, const Vec3&, Real) {
          Vec3 x = v.pos[j], u = v.vel[j], w = v.omega[j];
          Real det = 1;
          for (int k = 0; k < 3; ++k)
            if (s[k] != 0) {
              x[k] = domain::shifted(v.mirror, k, x[k], s[k]);
              u[k] = -u[k];
              w[k] = -w[k];
              det = -det;
            }
          f(j, image, x, u, w * det);
        });
      }
}

// The contacts and bonds of sphere i with mirror images, added to its force f, torque t,
// contact count and broken bonds; their histories by key in its own mirror slots (the
// image's sphere keeps its own, mirrored: each sphere writes only itself). A broken bond
// with an image counts 2, as a bond between two spheres counts once on each.
template <class L>
SURGE_HD inline void mirror_terms(const DemView& v, const MirrorSearch& m, Real dt, int i, Vec3& f, Vec3& t, int& used,
                                  std::uint32_t& broken) {
  ContactSlot* row = v.mirror_hist + static_cast<std::size_t>(v.id[i]) * max_mirror_slots;
  domain::AxisShifts sh[3];
  if (!near_mirror(v, v.pos[i], sh)) {
    if (row[0].partner != no_partner) // (slots are held from the first on)
      for (int k = 0; k < max_mirror_slots; ++k) row[k] = ContactSlot{};
    return;
  }
  ContactSlot old[max_mirror_slots];
  for (int k = 0; k < max_mirror_slots; ++k) old[k] = row[k];
  const Vec3 xi = v.pos[i];
  const Real ri = v.radius[i];
  int kept = 0;
  for_each_mirror_partner(v, m, i, sh, [&](int j, int image, const Vec3& x, const Vec3& u, const Vec3& w) {
    const std::uint32_t key = mirror_key(image, v.id[j]);
    ContactSlot h{};
    for (int k = 0; k < max_mirror_slots; ++k)
      if (old[k].partner == key) h = old[k];
    const Vec3 d = xi - x;
    const Real dist = norm(d), rj = v.radius[j];
    if (!in_contact(dist, ri + rj, h.bonded != 0)) return;
    const PairInput in = sphere_pair_input(d, dist, ri, rj, v.vel[i], v.omega[i], u, w,
                                           v.mixed[v.material[i] * v.n_materials + v.material[j]]);
    const PairResult r = pair_terms<L>(in, sphere_law<L>(v, m.mats, i, j), springs_of(h), dt);
    f += r.force_a;
    t += r.torque_a;
    ++used;
    broken += r.broke ? 2U : 0U;
    if (kept < max_mirror_slots) row[kept++] = slot_of(r.springs, key);
  });
  for (int k = kept; k < max_mirror_slots; ++k) row[k] = ContactSlot{};
}

// Bonds each sphere of a bonded material near a symmetry face to the mirror images of
// bonded spheres closer than `gap`, in its mirror slots (bond's rule); count[i]: the
// bonds sphere i wanted (more than max_mirror_slots: some were left out).
void bond_mirrors(const DemView& v, const MirrorSearch& m, Real gap, std::uint32_t* count) {
  par::parallel_for(
      v.n, SURGE_LAMBDA(int i) {
        domain::AxisShifts sh[3];
        count[i] = 0;
        if (!m.mats[v.material[i]].bonded || !near_mirror(v, v.pos[i], sh)) return;
        ContactSlot* row = v.mirror_hist + static_cast<std::size_t>(v.id[i]) * max_mirror_slots;
        std::uint32_t bonds = 0;
        for_each_mirror_partner(v, m, i, sh, [&](int j, int image, const Vec3& x, const Vec3&, const Vec3&) {
          if (!m.mats[v.material[j]].bonded || norm(v.pos[i] - x) >= v.radius[i] + v.radius[j] + gap) return;
          if (bonds < max_mirror_slots) {
            row[bonds] = ContactSlot{};
            row[bonds].partner = mirror_key(image, v.id[j]);
            row[bonds].bonded = 1;
          }
          ++bonds;
        });
        count[i] = bonds;
      });
}

// Pass 2: each sphere sums its listed pairs in list order (A-side ones as evaluated,
// B-side ones negated, read at the A side's slot), then its wall contacts, then its
// contacts with mirror images.
template <class L>
void sphere_pass(const DemView& v, const WallsView& walls, const MirrorSearch& mirror, Real dt) {
  par::parallel_for(
      v.n, SURGE_LAMBDA(int i) {
        std::uint32_t flags = 0, broken = 0;
        // Without a branch on the pair (half of a packing's listed pairs touch, half do
        // not): a pair not touching holds +0 forces, and adding +0 or subtracting it (as
        // adding x * -1) leaves a sum's bits as they are. The sums in plain scalars: as
        // Vec3s captured by the lambda they lived in memory.
        Real fx = 0, fy = 0, fz = 0, tx = 0, ty = 0, tz = 0;
        neighbour::for_each_listed<max_contacts>(v.list, v.id, i,
                                                 [&](std::uint32_t, int, std::uint32_t at, bool i_is_a) {
                                                   if (at == neighbour::no_pair) return; // the partner's list was full
                                                   const PairForce& pf = v.pair[at];
                                                   flags += pf.flags & 1U;
                                                   broken += (pf.flags >> 1) & 1U;
                                                   const Real sign = i_is_a ? Real(1) : Real(-1);
                                                   const Vec3& tq = i_is_a ? pf.torque_a : pf.torque_b;
                                                   fx += pf.force_a.x * sign;
                                                   fy += pf.force_a.y * sign;
                                                   fz += pf.force_a.z * sign;
                                                   tx += tq.x;
                                                   ty += tq.y;
                                                   tz += tq.z;
                                                 });
        Vec3 f{fx, fy, fz}, t{tx, ty, tz};
        int used = static_cast<int>(flags);
        wall_terms<L>(v, walls, dt, i, f, t, used);
        if (v.mirror_hist) mirror_terms<L>(v, mirror, dt, i, f, t, used, broken);
        v.force[i] = f;
        v.torque[i] = t;
        v.broken[i] += broken;
        v.ncontact[i] = static_cast<std::uint32_t>(used);
      });
}

// The largest squared displacement of any sphere since the list was built.
Real max_displacement2(const DemView& v) {
  return par::parallel_reduce(
      v.n, Real(0),
      SURGE_LAMBDA(int i) {
        const Vec3 d = v.pos[i] - v.pos_built[i];
        return dot(d, d);
      },
      par::Max{});
}

// Force and moment (about `about`) that the spheres exert on one wall: plane `plane`
// (>= 0) or the triangles of mesh `mesh` (>= 0). Each stored wall contact is evaluated
// again for the current state with a zero time step, which gives the contact force as it
// stands (normal spring and dashpot, stored shear, rolling and twisting moments).
template <class L>
WallLoad wall_load(const DemView& v, const Material* mats, const Plane* planes, const WallTriangle* tris,
                   const WallBodiesView& bodies, int plane, int mesh, Vec3 about) {
  return par::parallel_reduce(
      v.n, WallLoad{},
      SURGE_LAMBDA(int i) {
        WallLoad out;
        const ContactSlot* row = v.wall_hist + static_cast<std::size_t>(v.id[i]) * max_wall_slots;
        const Vec3 xi = v.pos[i];
        const Real ri = v.radius[i];
        for (int k = 0; k < max_wall_slots; ++k) {
          const std::uint32_t partner = row[k].partner;
          if (partner == no_partner) continue;
          Vec3 n{}, at{};
          Real un = 0;
          int material = 0, body = -1;
          if ((partner & plane_partner) != 0) {
            const int pk = static_cast<int>(partner & ~plane_partner);
            if (pk != plane) continue;
            const Plane pl = planes[pk];
            n = pl.normal;
            un = ri - dot(xi - pl.point, pl.normal);
            at = xi - n * (ri - un);
            material = pl.material;
            body = pl.body;
          } else if ((partner & triangle_partner) != 0) {
            const int tk = static_cast<int>(partner & ~triangle_partner);
            const WallTriangle tr = tris[tk];
            if (tr.mesh != mesh) continue;
            at = geometry::closest_point_on_triangle(tr.a, tr.b, tr.c, xi).point;
            const Real d = norm(xi - at);
            if (!(d > 0)) continue;
            n = (xi - at) * (1 / d);
            un = ri - d;
            material = tr.material;
            body = tr.body;
          } else {
            continue;
          }
          if (!(un > 0)) continue;
          const WallPair<L> w = wall_pair_input<L>(v, mats, i, material, n, un, wall_motion(bodies, body, at));
          const PairResult r = pair_terms<L>(w.in, w.law, springs_of(row[k]), Real(0));
          out.force -= r.force_a;
          out.moment -= cross(xi - about, r.force_a) + r.torque_a;
        }
        return out;
      },
      SumWallLoads{});
}

// Bonds each sphere to every listed partner of a bonded material closer than `gap`
// (the list holds every sphere within r_i + r_j + skin, and gap < skin); the bond is
// marked in the A sphere's slot, which holds the pair's history.
void bond(const DemView& v, const Material* mats, Real gap) {
  par::parallel_for(
      v.n, SURGE_LAMBDA(int i) {
        if (!mats[v.material[i]].bonded) return;
        neighbour::for_each_own_pair(v.list, i, [&](std::uint32_t, int j, std::uint32_t p) {
          if (!mats[v.material[j]].bonded) return;
          if (norm(v.rel(i, j)) >= v.radius[i] + v.radius[j] + gap) return;
          v.hist[p].bonded = 1;
        });
      });
}

// Spheres more than half a period beyond a periodic face moved back by a period (at a
// list rebuild: the list's images are found anew).
void wrap_spheres(const DemView& v) {
  par::parallel_for(
      v.n, SURGE_LAMBDA(int i) {
        Vec3 x = v.pos[i];
        v.period.wrap(x, true);
        v.pos[i] = x;
      });
}

// Each sphere's motion over the step (integration.hpp); fixed spheres stay and stop.
void integrate(const DemView& v, Vec3 gravity, Real ad, Real dt) {
  par::parallel_for(
      v.n, SURGE_LAMBDA(int i) {
        if (v.fixed[i]) {
          v.vel[i] = Vec3{};
          v.omega[i] = Vec3{};
          return;
        }
        const std::uint32_t id = v.id[i];
        Real* q = v.quat + 4 * static_cast<std::size_t>(i);
        MotionT<Real> s{v.pos[i], v.vel[i], v.omega[i], {q[0], q[1], q[2], q[3]}};
        advance(s, v.force[i] + v.ext_force[id] + gravity * v.mass[i], v.torque[i] + v.ext_torque[id], v.mass[i],
                v.inertia[i], ad, dt);
        v.pos[i] = s.pos;
        v.vel[i] = s.vel;
        v.omega[i] = s.omega;
        for (int k = 0; k < 4; ++k) q[k] = s.q[k];
      });
}

} // namespace detail

DemSolver::DemSolver(std::vector<Material> materials, std::vector<Plane> planes, Vec3 gravity, Vec3 lo, Vec3 hi,
                     int contact_law)
    : materials_host_(std::move(materials)), gravity_(gravity), law_index_(contact_law), lo_(lo), hi_(hi) {
  if (materials_host_.empty()) throw std::invalid_argument("DEM needs at least one material");
  if (law_index_ < 0 || law_index_ >= static_cast<int>(contact_law_names().size()))
    throw std::invalid_argument("unknown DEM contact law");
  for (auto& m : materials_host_) {
    const char* key = "";
    if (const char* why = unsuitable_material(law_index_, m, &key))
      throw std::invalid_argument(std::string("material ") + key + " " + why);
    with_contact_law(law_index_, [&](auto law) { m.damping = decltype(law)::damping(m.restitution); });
  }
  par::upload(materials_, materials_host_);
  std::vector<MixedPair> mixed;
  for (const auto& a : materials_host_)
    for (const auto& b : materials_host_) {
      mixed.push_back(detail::mix(a, b));
      resists_ = resists_ || mixed.back().k_roll > 0 || mixed.back().k_twist > 0;
    }
  par::upload(mixed_, mixed);
  for (auto& p : planes) p.normal = p.normal * (1 / norm(p.normal));
  n_planes_ = static_cast<int>(planes.size());
  par::upload(planes_, planes);
  planes_host_ = std::move(planes);
#if defined(SURGE_SIMD)
  set_pair_pass(par::simd_isa());
#endif
}

bool DemSolver::set_pair_pass(const char* isa) {
  if (std::strcmp(isa, "off") == 0) {
    batched_ = nullptr;
    batched_motion_ = nullptr;
    pair_pass_name_ = "off";
    return true;
  }
#if defined(SURGE_SIMD)
  if (const PairPassFn f = batched_pair_pass(law_index_, isa)) {
    batched_ = f;
    batched_motion_ = batched_integrate(isa);
    pair_pass_name_ = std::strcmp(isa, "avx2") == 0 ? "avx2" : "sse2";
    return true;
  }
#endif
  return false;
}

void DemSolver::set_wall_triangles(const std::vector<WallTriangle>& t) {
  for (const auto& x : t)
    if (x.material < 0 || x.material >= static_cast<int>(materials_host_.size()))
      throw std::invalid_argument("wall triangle with an unknown material");
  n_triangles_ = static_cast<int>(t.size());
  par::upload(triangles_, t);
  triangles_host_ = t;
  tri_grid_radius_ = -1;
  tri_grid_ = {};
}

void DemSolver::build_triangle_grid() {
  // Each triangle's box grown by the largest radius: a sphere's centre cell lists every
  // triangle the sphere can touch.
  const double r = max_radius_;
  std::vector<Vec3d> blo, bhi;
  std::vector<std::uint32_t> still; // the grid's triangles (moving ones are tested by body)
  for (std::size_t i = 0; i < triangles_host_.size(); ++i) {
    const WallTriangle& t = triangles_host_[i];
    if (t.body >= 0 && has_wall_bodies()) continue; // (before set_wall_bodies every wall stands)
    still.push_back(static_cast<std::uint32_t>(i));
    Vec3d a(t.a), b(t.a);
    for (const Vec3& p : {t.b, t.c})
      for (int k = 0; k < 3; ++k) {
        a[k] = std::min(a[k], static_cast<double>(p[k]));
        b[k] = std::max(b[k], static_cast<double>(p[k]));
      }
    blo.push_back(a - Vec3d{r, r, r});
    bhi.push_back(b + Vec3d{r, r, r});
  }
  tri_grid_radius_ = max_radius_;
  tri_grid_ = {};
  if (still.empty()) return;
  geometry::BoxBuckets g = geometry::bucket_boxes(blo, bhi, 2 * r);
  for (auto& item : g.items) item = still[item]; // bucket k is the k-th still triangle
  par::upload(tri_start_, g.start);
  par::upload(tri_items_, g.items);
  tri_grid_.lo = Vec3(g.lo);
  tri_grid_.inv_cell = static_cast<Real>(1 / g.cell);
  for (int k = 0; k < 3; ++k) tri_grid_.n[k] = static_cast<int>(g.n[k]);
  tri_grid_.start = tri_start_.data();
  tri_grid_.items = tri_items_.data();
  tri_grid_radius_ = max_radius_;
}

namespace {
template <class T>
std::vector<T> by_id(const std::vector<T>& v, const std::vector<std::uint32_t>& id, int block = 1) {
  std::vector<T> out(v.size());
  for (std::size_t i = 0; i < id.size(); ++i)
    for (int b = 0; b < block; ++b) out[id[i] * block + b] = v[i * block + b];
  return out;
}
} // namespace

void DemSolver::set_wall_bodies(const std::vector<RigidState>& placed) {
  body_states_host_ = placed;
  const std::size_t nb = placed.size();
  // Planes: their body-frame point (the arm from the pivot) and normal as placed.
  planes_ref_ = planes_host_;
  for (auto& p : planes_ref_) {
    if (p.body >= static_cast<int>(nb)) throw std::invalid_argument("wall plane of an unknown body");
    if (p.body >= 0) p.point = p.point - placed[static_cast<std::size_t>(p.body)].pos;
  }
  // Triangles: grouped by body (CSR), with their vertices' arms; the reach of each body.
  std::vector<std::uint32_t> start(nb + 1, 0), items;
  std::vector<WallTriangle> ref;
  std::vector<Real> reach(nb, 0);
  for (std::size_t b = 0; b < nb; ++b) {
    start[b] = static_cast<std::uint32_t>(items.size());
    for (std::size_t k = 0; k < triangles_host_.size(); ++k) {
      WallTriangle t = triangles_host_[k];
      if (t.body != static_cast<int>(b)) continue;
      for (Vec3* x : {&t.a, &t.b, &t.c}) {
        *x = *x - placed[b].pos;
        reach[b] = std::max(reach[b], norm(*x));
      }
      items.push_back(static_cast<std::uint32_t>(k));
      ref.push_back(t);
    }
  }
  start[nb] = static_cast<std::uint32_t>(items.size());
  for (const auto& t : triangles_host_)
    if (t.body >= static_cast<int>(nb)) throw std::invalid_argument("wall triangle of an unknown body");
  par::upload(body_start_, start);
  par::upload(body_items_, items);
  par::upload(body_ref_, ref);
  par::upload(body_reach_, reach);
  wall_react_.resize(static_cast<std::size_t>(n_) * max_wall_slots);
  par::fill(wall_react_, WallReaction{});
  body_flag_.resize(static_cast<std::size_t>(n_));
  par::fill(body_flag_, std::uint32_t{0});
  body_loads_.assign(nb, WallLoadD{});
  tri_grid_radius_ = -1; // the grid holds the still triangles only
  move_walls(placed);
}

void DemSolver::move_walls(const std::vector<RigidState>& states) {
  if (states.size() != body_states_host_.size()) throw std::invalid_argument("move_walls: another number of bodies");
  body_states_host_ = states;
  par::upload(body_states_, states);
  bool planes_move = false;
  for (std::size_t k = 0; k < planes_host_.size(); ++k) {
    const Plane& r = planes_ref_[k];
    if (r.body < 0) continue;
    const RigidState& st = states[static_cast<std::size_t>(r.body)];
    planes_host_[k].point = rigid_point(st, r.point).pos;
    planes_host_[k].normal = rotate(st.q, r.normal);
    planes_move = true;
  }
  if (planes_move) par::upload(planes_, planes_host_);
  const auto n = static_cast<int>(body_items_.size());
  if (n == 0) return;
  const WallTriangle* ref = body_ref_.data();
  const std::uint32_t* items = body_items_.data();
  const RigidState* st = body_states_.data();
  WallTriangle* tris = triangles_.data();
  par::parallel_for(
      n, SURGE_LAMBDA(int k) {
        WallTriangle t = ref[k];
        const RigidState& s = st[t.body];
        t.a = rigid_point(s, t.a).pos;
        t.b = rigid_point(s, t.b).pos;
        t.c = rigid_point(s, t.c).pos;
        tris[items[k]] = t;
      });
}

std::vector<std::array<Vec3, 3>> DemSolver::moving_triangles() const {
  std::vector<std::array<Vec3, 3>> out;
  if (!has_wall_bodies()) return out;
  for (const WallTriangle& t : par::download(triangles_))
    if (t.body >= 0) out.push_back({t.a, t.b, t.c});
  return out;
}

WallBodiesView DemSolver::bodies_view() {
  WallBodiesView b;
  if (body_states_host_.empty()) return b;
  b.n = static_cast<int>(body_states_host_.size());
  b.state = body_states_.data();
  b.reach = body_reach_.data();
  b.start = body_start_.data();
  b.items = body_items_.data();
  return b;
}

namespace detail {
// The body a wall contact's partner belongs to, or -1 (a still wall, an empty slot).
SURGE_HD inline int partner_body(std::uint32_t partner, const Plane* planes, const WallTriangle* tris) {
  if (partner == no_partner) return -1;
  if ((partner & plane_partner) != 0) return planes[partner & ~plane_partner].body;
  if ((partner & triangle_partner) != 0) return tris[partner & ~triangle_partner].body;
  return -1;
}

// The spheres the sphere pass flagged as touching a moving body: their contacts, at[i]
// their places (the flags' exclusive scan).
void gather_body_contacts(const DemView& v, const Plane* planes, const WallTriangle* tris, const WallReaction* react,
                          const std::uint32_t* flag, const std::uint32_t* at, BodyContact* out) {
  par::parallel_for(
      v.n, SURGE_LAMBDA(int i) {
        if (!flag[i]) return;
        const std::uint32_t id = v.id[i];
        const ContactSlot* row = v.wall_hist + static_cast<std::size_t>(id) * max_wall_slots;
        BodyContact c{};
        c.id = id;
        c.pos = v.pos[i];
        for (int k = 0; k < max_wall_slots; ++k) {
          c.body[k] = partner_body(row[k].partner, planes, tris);
          c.react[k] = react[static_cast<std::size_t>(id) * max_wall_slots + k];
        }
        out[at[i]] = c;
      });
}
} // namespace detail

// Minus the spheres' wall reactions of this step, per body: in sphere id order and in
// double, at the spheres' positions before they move (those the step's contacts used).
// Only the spheres touching a body are copied to the host (flagged by the sphere pass,
// counted by a scan and gathered on the device): a few among many.
void DemSolver::sum_body_loads() {
  const DemView v = view();
  body_at_.resize(static_cast<std::size_t>(n_));
  const std::uint32_t count = algo::exclusive_scan(body_flag_.data(), body_at_.data(), n_);
  body_contacts_.resize(count);
  detail::gather_body_contacts(v, planes_.data(), triangles_.data(), wall_react_.data(), body_flag_.data(),
                               body_at_.data(), body_contacts_.data());
  std::vector<BodyContact>& list = body_contacts_host_;
  par::download(list, body_contacts_, count);
  std::sort(list.begin(), list.end(), [](const BodyContact& a, const BodyContact& b) { return a.id < b.id; });
  body_loads_.assign(body_states_host_.size(), WallLoadD{});
  for (const BodyContact& c : list)
    for (int k = 0; k < max_wall_slots; ++k) {
      if (c.body[k] < 0) continue;
      WallLoadD& l = body_loads_[static_cast<std::size_t>(c.body[k])];
      const Vec3d f(c.react[k].force);
      l.force -= f;
      l.moment -= cross(Vec3d(c.pos) - Vec3d(body_states_host_[static_cast<std::size_t>(c.body[k])].pos), f) +
                  Vec3d(c.react[k].torque);
    }
}

void DemSolver::set_spheres(const std::vector<Sphere>& s) {
  if (s.size() >= triangle_partner) throw std::invalid_argument("too many spheres");
  n_ = static_cast<int>(s.size());
  std::vector<Vec3> pos, vel, omega;
  std::vector<Real> quat, radius, mass, inertia;
  std::vector<std::uint8_t> mat, fixed;
  std::vector<std::uint32_t> id;
  max_radius_ = 0;
  for (std::size_t k = 0; k < s.size(); ++k) {
    const auto& m = materials_host_.at(static_cast<std::size_t>(s[k].material));
    pos.push_back(s[k].pos);
    vel.push_back(s[k].vel);
    omega.push_back(s[k].omega);
    quat.insert(quat.end(), {1, 0, 0, 0});
    radius.push_back(s[k].radius);
    const Real r = s[k].radius;
    const Real mk = m.density * Real(4.0 / 3.0 * pi) * r * r * r;
    mass.push_back(mk);
    inertia.push_back(Real(0.4) * mk * r * r);
    mat.push_back(static_cast<std::uint8_t>(s[k].material));
    fixed.push_back(s[k].fixed ? 1 : 0);
    id.push_back(static_cast<std::uint32_t>(k));
    max_radius_ = std::max(max_radius_, r);
  }
  // Every per-sphere buffer sized and cleared (a value-initialised element: zero, an
  // empty contact slot), then the given state uploaded and the list marked empty.
  DemView unused{};
  for_each_sphere_field(*this, unused, [&](auto& b, auto&, int block, unsigned) {
    b.resize(s.size() * static_cast<std::size_t>(block));
    par::fill(b, std::remove_reference_t<decltype(*b.data())>{});
  });
  par::upload(pos_, pos);
  par::upload(vel_, vel);
  par::upload(omega_, omega);
  par::upload(quat_, quat);
  par::upload(radius_, radius);
  par::upload(mass_, mass);
  par::upload(inertia_, inertia);
  par::upload(material_, mat);
  par::upload(fixed_, fixed);
  par::upload(id_, id);
  par::fill(nbr_, neighbour::no_pair);
  par::fill(entry_, neighbour::no_pair);
  hist_.resize(0);
  n_pairs_ = 0;
  list_valid_ = false;
  skin_ = Real(0.1) * max_radius_;
  for (int k = 0; k < 3; ++k)
    if (period_.on[k] && !(period_.len[k] > 2 * list_reach() + 2 * max_radius_))
      throw std::invalid_argument(std::string("a periodic length along ") + "xyz"[k] +
                                  " shorter than twice the DEM's search reach plus a sphere diameter (" +
                                  std::to_string(2 * list_reach() + 2 * max_radius_) + " m)");
  check_mirrored(s);
  mirror_hist_.resize(mirrored() ? s.size() * max_mirror_slots : 0);
  par::fill(mirror_hist_, ContactSlot{});
  set_grid();
}

void DemSolver::set_grid() {
  // On periodic axes the spheres lie up to half a period beyond the faces (set_periodic).
  Vec3 glo = lo_, ghi = hi_;
  for (int k = 0; k < 3; ++k)
    if (period_.on[k]) {
      glo[k] -= period_.len[k] / 2;
      ghi[k] += period_.len[k] / 2;
    }
  grid_.set_spec(neighbour::make_grid(glo, ghi, std::max(list_reach(), Real(1e-6))));
}

void DemSolver::set_symmetry(const std::array<bool, 6>& faces) {
  mirror_ = domain::ImageFrame{};
  for (std::size_t k = 0; k < 3; ++k) {
    mirror_.mirror_lo[k] = faces[2 * k] ? 1 : 0;
    mirror_.mirror_hi[k] = faces[2 * k + 1] ? 1 : 0;
  }
  mirror_.lo = lo_;
  mirror_.hi = hi_;
  mirror_.len = hi_ - lo_;
}

void DemSolver::check_mirrored(const std::vector<Sphere>& s) const {
  if (!mirrored()) return;
  if (period_.any())
    throw std::invalid_argument("DEM spheres with both symmetry and periodic faces are not yet possible");
  if (s.size() >= max_mirrored_spheres) throw std::invalid_argument("too many spheres for symmetry faces");
  static const char* const face[6] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  for (std::size_t n = 0; n < s.size(); ++n)
    for (int k = 0; k < 3; ++k) {
      // A sphere may touch its image (0.1 % of its radius of overlap is allowed for
      // rounding), not cross it: the whole would hold two spheres in one place.
      const Real r = s[n].radius * Real(0.999);
      const bool lo = mirror_.mirror_lo[k] && s[n].pos[k] - lo_[k] < r;
      const bool hi = mirror_.mirror_hi[k] && hi_[k] - s[n].pos[k] < r;
      if (lo || hi)
        throw std::invalid_argument(
            "sphere " + std::to_string(n) + " crosses the symmetry face " + face[2 * k + (hi ? 1 : 0)] +
            " (its centre closer to it than its radius): it would overlap its own mirror image");
    }
}

DemView DemSolver::view() {
  DemView v{};
  v.n = n_;
  v.mixed = mixed_.data();
  v.n_materials = static_cast<int>(materials_host_.size());
  v.resists = resists_;
  for_each_sphere_field(*this, v, [](auto& b, auto& ptr, int, unsigned) { ptr = b.data(); });
  v.hist = hist_.data();
  v.pair = pair_.data();
  v.law = law_.data();
  v.list.pair_b = pair_b_.data();
  v.period = period_;
  v.mirror = mirror_;
  v.mirror.band = Vec3(list_reach(), list_reach(), list_reach());
  v.mirror_hist = mirrored() ? mirror_hist_.data() : nullptr;
  return v;
}

Real DemSolver::critical_dt(Real factor) const {
  const auto mass = par::download(mass_), radius = par::download(radius_);
  const auto mat = par::download(material_);
  Real dt = std::numeric_limits<Real>::max();
  with_contact_law(law_index_, [&](auto law) {
    for (std::size_t k = 0; k < mass.size(); ++k)
      dt = std::min(dt, decltype(law)::time_scale(materials_host_[mat[k]], radius[k], mass[k]));
  });
  return factor * dt;
}

void DemSolver::sort_spheres() {
  // The pairs stay where they are; each sphere takes the range of its pairs along (they
  // are found again by partner id). The list's indices do not survive the sort:
  // rebuild_list makes new ones.
  if (period_.any()) detail::wrap_spheres(view());
  grid_.sort(pos_.data(), nullptr, n_);
  const std::uint32_t* perm = grid_.permutation();
  DemView unused{};
  for_each_sphere_field(*this, unused, [&](auto& b, auto&, int block, unsigned use) {
    if (use & kSorted) par::gather(b, scratch_for(b), perm, n_, block);
  });
  grid_.build_cell_start(n_);
}

void DemSolver::rebuild_list() {
  // Memory: a step holds one list's histories and the pairs' forces, a rebuild the last
  // list's histories and the new one's. The forces (written anew every step) are released
  // before a rebuild and the last histories after it: the peak is the larger of the two
  // sets, not their sum (about 130 B per sphere less on a packing).
  pair_ = par::Buffer<PairForce>{};
  sort_spheres();
  // The last list's pairs become the old ones; the new list counts its pairs per A
  // sphere, numbers them (a scan), carries the histories over and links the B sides.
  hist_.swap(hist_old_);
  tmpu_.resize(static_cast<std::size_t>(n_));
  DemView v = view();
  const int wanted = detail::list_spheres(v, grid_.view(v.pos), hist_old_.data(), list_reach(), skin(), tmpu_.data());
  if (wanted > max_contacts)
    throw std::runtime_error("DEM: a sphere has " + std::to_string(wanted) +
                             " neighbours within r_i + r_j + skin, more than the " + std::to_string(max_contacts) +
                             " a sphere can list (spheres much larger than their neighbours, or overlapping); contacts "
                             "would be missed");
  par::copy(pair_count_, tmpu_);
  n_pairs_ = algo::exclusive_scan(pair_count_.data(), pair_begin_.data(), n_);
  hist_.resize(n_pairs_);
  law_.resize(n_pairs_);
  pair_b_.resize(n_pairs_);
  v = view();
  neighbour::fill_pairs<max_contacts>(v.list, v.id, n_, hist_old_.data(), hist_.data());
  neighbour::link_pairs<max_contacts>(v.list, v.id, n_);
  neighbour::pair_partners<max_contacts>(v.list, v.id, n_);
  with_contact_law(law_index_, [&](auto law) { detail::pair_laws<decltype(law)>(v, materials_.data()); });
  hist_old_ = par::Buffer<ContactSlot>{};
  pair_.resize(n_pairs_);
  par::copy(pos_built_, pos_);
  list_valid_ = true;
}

bool DemSolver::list_stale() {
  if (!list_valid_) return true;
  const Real half = skin() / 2;
  return detail::max_displacement2(view()) > half * half;
}

namespace {
// Runs the CPU's batched pass f(args..., begin, end) over blocks of pair_pass_block
// spheres, handed 4 at a time to a thread (the default chunk of 256 indices gave one of
// two threads most of the blocks); false where there is none (the scalar pass runs).
template <class Fn, class... A>
bool run_batched(Fn f, int n, const A&... args) {
#if defined(SURGE_SIMD)
  if (!f) return false;
  const int blocks = (n + pair_pass_block - 1) / pair_pass_block;
  par::parallel_for_uneven(
      blocks, [=](int b) { f(args..., b * pair_pass_block, b + 1 < blocks ? (b + 1) * pair_pass_block : n); }, 4);
  return true;
#else
  (void)f, (void)n, ((void)args, ...);
  return false;
#endif
}
} // namespace

void DemSolver::step(Real dt) {
  if (n_triangles_ > 0 && tri_grid_radius_ < max_radius_) build_triangle_grid();
  {
    const auto t = par::timed(par::Phase::DemSort);
    if (list_stale()) rebuild_list();
  }
  const DemView v = view();
  {
    const auto t = par::timed(par::Phase::DemContacts);
    with_contact_law(law_index_, [&](auto law) {
      using L = decltype(law);
      if (!run_batched(batched_, n_, v, dt)) detail::pair_pass<L>(v, dt);
      detail::sphere_pass<L>(v,
                             detail::WallsView{materials_.data(), planes_.data(), n_planes_, triangles_.data(),
                                               tri_grid_, bodies_view(),
                                               has_wall_bodies() ? wall_react_.data() : nullptr,
                                               has_wall_bodies() ? body_flag_.data() : nullptr},
                             detail::MirrorSearch{grid_.view(v.pos), materials_.data()}, dt);
    });
    if (has_wall_bodies()) sum_body_loads();
  }
  {
    const auto t = par::timed(par::Phase::DemIntegrate);
    if (!run_batched(batched_motion_, n_, v, gravity_, local_damping_, dt))
      detail::integrate(v, gravity_, local_damping_, dt);
  }
}

namespace {
// Appends / reads one buffer: element count, then raw elements.
// Wall-history rows from id order (the solver's) to sorted order (the saved state's:
// the order of the other per-sphere fields), or back.
std::vector<ContactSlot> reorder_wall_rows(const std::vector<ContactSlot>& rows, const std::vector<std::uint32_t>& id,
                                           bool to_sorted) {
  std::vector<ContactSlot> out(rows.size());
  for (std::size_t i = 0; i < id.size(); ++i)
    for (std::size_t k = 0; k < max_wall_slots; ++k) {
      const std::size_t sorted = i * max_wall_slots + k, by_id = static_cast<std::size_t>(id[i]) * max_wall_slots + k;
      if (to_sorted)
        out[sorted] = rows[by_id];
      else
        out[by_id] = rows[sorted];
    }
  return out;
}

template <class T>
void save_vector(std::string& out, const std::vector<T>& v) {
  const std::uint64_t n = v.size();
  out.append(reinterpret_cast<const char*>(&n), sizeof n);
  out.append(reinterpret_cast<const char*>(v.data()), n * sizeof(T));
}
template <class T>
void load_buffer(const std::string& in, std::size_t& pos, par::Buffer<T>& b, std::size_t expect) {
  std::uint64_t n = 0;
  if (pos + sizeof n > in.size()) throw std::invalid_argument("DEM state truncated");
  std::memcpy(&n, in.data() + pos, sizeof n);
  pos += sizeof n;
  if (n != expect || pos + n * sizeof(T) > in.size())
    throw std::invalid_argument("DEM state does not match this case (sphere count or truncated data)");
  std::vector<T> v(n);
  std::memcpy(v.data(), in.data() + pos, n * sizeof(T));
  pos += n * sizeof(T);
  par::upload(b, v);
}
} // namespace

// The per-sphere buffers, declared once: with the view's pointer to each, its elements
// per sphere and how it travels (kSorted: carried through the sort, the others are
// recomputed or indexed by id; every one is saved, in this order, which is the
// checkpoint's). set_spheres sizes and clears them, sort_spheres gathers the sorted ones,
// save and restore write and read them all, view() points the kernels at them.
template <class Self, class View, class F>
void DemSolver::for_each_sphere_field(Self& s, View& v, F&& f) {
  constexpr unsigned sorted = kSorted;
  f(s.pos_, v.pos, 1, sorted);
  f(s.vel_, v.vel, 1, sorted);
  f(s.omega_, v.omega, 1, sorted);
  f(s.quat_, v.quat, 4, sorted);
  f(s.radius_, v.radius, 1, sorted);
  f(s.mass_, v.mass, 1, sorted);
  f(s.inertia_, v.inertia, 1, sorted);
  f(s.material_, v.material, 1, sorted);
  f(s.fixed_, v.fixed, 1, sorted);
  f(s.id_, v.id, 1, sorted);
  f(s.broken_, v.broken, 1, sorted);
  f(s.ncontact_, v.ncontact, 1, 0U);                // this step's, recomputed
  f(s.force_, v.force, 1, 0U);                      // this step's, recomputed
  f(s.torque_, v.torque, 1, 0U);                    // this step's, recomputed
  f(s.ext_force_, v.ext_force, 1, 0U);              // by id
  f(s.ext_torque_, v.ext_torque, 1, 0U);            // by id
  f(s.wall_hist_, v.wall_hist, max_wall_slots, 0U); // by id (never sorted: no scratch of 176 B per sphere)
  f(s.nbr_, v.list.nbr, max_contacts, 0U);          // the list: rebuilt after a sort
  f(s.nnbr_, v.list.nnbr, 1, 0U);
  f(s.entry_, v.list.entry, max_contacts, 0U);
  f(s.pair_begin_, v.list.pair_begin, 1, sorted); // each sphere keeps its pairs' range
  f(s.pair_count_, v.list.pair_count, 1, sorted);
  f(s.pos_built_, v.pos_built, 1, 0U); // set when the list is built
}

std::string DemSolver::save() const {
  std::string out;
  const auto n = static_cast<std::uint64_t>(n_);
  out.append(reinterpret_cast<const char*>(&n), sizeof n);
  // The list as it stands (a restored run rebuilds it exactly when the straight run does).
  const std::uint64_t valid = list_valid_ ? 1 : 0;
  out.append(reinterpret_cast<const char*>(&valid), sizeof valid);
  DemView unused{};
  for_each_sphere_field(*this, unused, [&](const auto& b, auto&, int, unsigned) {
    if constexpr (std::is_same_v<std::decay_t<decltype(b)>, par::Buffer<ContactSlot>>) {
      if (&b == &wall_hist_) { // rows by id, saved in sorted order (the format as it was)
        save_vector(out, reorder_wall_rows(par::download(wall_hist_), par::download(id_), true));
        return;
      }
    }
    save_vector(out, par::download(b));
  });
  save_vector(out, par::download(hist_));                        // the pairs' histories
  if (mirrored()) save_vector(out, par::download(mirror_hist_)); // by id
  return out;
}

void DemSolver::restore(const std::string& bytes) {
  std::uint64_t n = 0;
  if (bytes.size() < sizeof n) throw std::invalid_argument("DEM state truncated");
  std::memcpy(&n, bytes.data(), sizeof n);
  if (n != static_cast<std::uint64_t>(n_)) throw std::invalid_argument("DEM state holds another number of spheres");
  std::uint64_t valid = 0;
  if (bytes.size() < 2 * sizeof n) throw std::invalid_argument("DEM state truncated");
  std::memcpy(&valid, bytes.data() + sizeof n, sizeof valid);
  if (valid > 1) throw std::invalid_argument("DEM state of an older surge (before neighbour lists)");
  std::size_t pos = 2 * sizeof n;
  const auto N = static_cast<std::size_t>(n_);
  DemView unused{};
  for_each_sphere_field(*this, unused, [&](auto& b, auto&, int block, unsigned) {
    load_buffer(bytes, pos, b, N * static_cast<std::size_t>(block));
  });
  // The pairs: as many as the restored A counts say.
  const auto counts = par::download(pair_count_);
  std::size_t pairs = 0;
  for (auto c : counts) pairs += c;
  load_buffer(bytes, pos, hist_, pairs);
  if (mirrored()) load_buffer(bytes, pos, mirror_hist_, N * max_mirror_slots);
  n_pairs_ = static_cast<std::uint32_t>(pairs);
  pair_.resize(pairs);
  law_.resize(pairs);
  pair_b_.resize(pairs);
  if (pos != bytes.size()) throw std::invalid_argument("DEM state has trailing data");
  const DemView v = view();
  neighbour::pair_partners<max_contacts>(v.list, v.id, n_);
  with_contact_law(law_index_, [&](auto law) { detail::pair_laws<decltype(law)>(v, materials_.data()); });
  list_valid_ = valid == 1;
  if (mirrored() && list_valid_) { // the mirror search's grid: the cells of the last sort, from its positions
    grid_.sort(pos_built_.data(), nullptr, n_); // (sorted already: the permutation is the identity)
    grid_.build_cell_start(n_);
  }
  // The wall histories, saved in sorted order, back to rows by id.
  par::upload(wall_hist_, reorder_wall_rows(par::download(wall_hist_), par::download(id_), false));
}

void DemSolver::rigid_states(par::Buffer<RigidState>& out) {
  out.resize(static_cast<std::size_t>(n_));
  const DemView v = view();
  RigidState* o = out.data();
  par::parallel_for(
      n_, SURGE_LAMBDA(int i) {
        RigidState s;
        s.pos = v.pos[i];
        s.vel = v.vel[i];
        s.omega = v.omega[i];
        for (int k = 0; k < 4; ++k) s.q[k] = v.quat[4 * static_cast<std::size_t>(i) + k];
        o[v.id[i]] = s;
      });
}

long DemSolver::bond_touching(Real gap) {
  if (!(gap < skin_)) { // the list must hold every pair within the gap
    skin_ = 2 * gap;
    set_grid();
  }
  rebuild_list();
  const DemView v = view();
  detail::bond(v, materials_.data(), gap);
  const auto h = par::download(hist_);
  long bonds = 0; // marked on the A side only
  for (const auto& s : h) bonds += s.bonded ? 1 : 0;
  if (mirrored()) { // each sphere's bonds to images, one per slot
    tmpu_.resize(static_cast<std::size_t>(n_));
    detail::bond_mirrors(v, detail::MirrorSearch{grid_.view(v.pos), materials_.data()}, gap, tmpu_.data());
    for (const std::uint32_t b : par::download(tmpu_)) {
      if (b > static_cast<std::uint32_t>(max_mirror_slots))
        throw std::runtime_error("DEM: a sphere would bond to " + std::to_string(b) + " mirror images, more than the " +
                                 std::to_string(max_mirror_slots) + " it can hold");
      bonds += b;
    }
  }
  return bonds;
}

WallLoad DemSolver::wall_load(int plane, int mesh, Vec3 about) {
  const DemView v = view();
  WallLoad out;
  with_contact_law(law_index_, [&](auto law) {
    out = detail::wall_load<decltype(law)>(v, materials_.data(), planes_.data(), triangles_.data(), bodies_view(),
                                           plane, mesh, about);
  });
  return out;
}

bool DemSolver::finite() {
  const Vec3* pos = pos_.data();
  const int bad = par::parallel_reduce(
      n_, 0,
      SURGE_LAMBDA(int i) {
        const Vec3 x = pos[i];
        return (std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z)) ? 0 : 1;
      },
      par::Sum{});
  return bad == 0;
}

long DemSolver::broken_bonds() const {
  long b = 0;
  for (auto x : par::download(broken_)) b += x;
  return b / 2;
}

std::vector<Sphere> DemSolver::spheres() const {
  const auto id = par::download(id_);
  const auto pos = by_id(par::download(pos_), id), vel = by_id(par::download(vel_), id),
             omega = by_id(par::download(omega_), id);
  const auto radius = by_id(par::download(radius_), id);
  const auto mat = by_id(par::download(material_), id);
  std::vector<Sphere> out(id.size());
  const auto fixed = by_id(par::download(fixed_), id);
  for (std::size_t k = 0; k < id.size(); ++k) out[k] = {pos[k], vel[k], omega[k], radius[k], mat[k], fixed[k] != 0};
  return out;
}
std::vector<Vec3> DemSolver::forces() const { return by_id(par::download(force_), par::download(id_)); }
std::vector<Vec3> DemSolver::torques() const { return by_id(par::download(torque_), par::download(id_)); }
std::vector<std::uint32_t> DemSolver::intact_bonds() const {
  const auto id = par::download(id_), begin = par::download(pair_begin_), count = par::download(pair_count_);
  const auto hist = par::download(hist_);
  std::vector<std::uint32_t> out;
  for (std::size_t i = 0; i < id.size(); ++i)
    for (std::uint32_t p = begin[i]; p < begin[i] + count[i]; ++p)
      if (hist[p].bonded) out.insert(out.end(), {id[i], hist[p].partner});
  return out;
}

std::vector<std::uint32_t> DemSolver::contact_counts() const {
  return by_id(par::download(ncontact_), par::download(id_));
}
std::vector<Real> DemSolver::quaternions() const { return by_id(par::download(quat_), par::download(id_), 4); }

} // namespace surge::dem
