// Turns the case's regions into particles: fluid lattices, wall layers from
// boxes and triangle meshes. Positions are absolute (double); the caller
// shifts them to the case origin.
#pragma once
#include "surge/core/case.hpp"
#include "surge/geometry/stl_mesh.hpp"

#include <vector>

namespace surge::geometry {

// Number of wall layers that fill the kernel support: ceil(2h/dp).
int wall_layers(const Case& c);

// How a box of water is filled: whole spacings dp from its corner (Lattice), the same
// centred in the box (Centred: a box that is not a whole number of spacings keeps its
// shortfall at both ends), or round(L / dp) points per axis with the spacing stretched to
// L / n (Stretched: the box filled exactly, each point standing for stretched_cell_volume).
enum class BoxFill { Lattice, Centred, Stretched };
std::vector<Vec3d> fill_box(const Box& b, double dp, BoxFill fill = BoxFill::Lattice);
double stretched_cell_volume(const Box& b, double dp);
// Layers of thickness `layers` dp around a tank box (outside it, faces in `open` left out),
// or inside it when `solid`: with `fit`, on a lattice stretched to fit the solid box (each
// face half a spacing in front of its first layer, as mDBC's no-penetration condition
// needs), else on the lattice (i + 1/2) dp from its lowest corner.
std::vector<Vec3d> box_wall(const WallSpec& w, double dp, int layers, bool fit = true);
// Lattice points (aligned to `origin` + (i + 1/2) dp) behind the mesh surface
// (the side its normals point away from) within layers * dp of it; with `clip`, only those
// inside that box (a terrain's, whose hills may rise far above the domain).
std::vector<Vec3d> mesh_wall(const Mesh& m, const Vec3d& origin, double dp, int layers, const Box* clip = nullptr);
// The ghost node of a wall particle at p (modified dynamic boundary): p mirrored through
// the closest point of the wall's surface, into the fluid side.
Vec3d ghost_point(const WallSpec& w, const Mesh* mesh, const Vec3d& p);
// How far the wall particle at p holds water off under the no-penetration condition
// (sph/boundary/no_penetration.hpp), from the wall lattice around it: `patch`, the half-width of
// its patch of face; `sphere`, the radius around it that water may not enter; `faces`,
// the ghost-style offsets (twice the way to the face) of the faces it holds besides the
// one it mirrors through (a solid box's edge and corner particles: one or two more).
struct Reach {
  double patch = 0, sphere = 0;
  std::vector<Vec3d> faces;
};
// `mirror`: the particle's ghost offset, ghost_point(w, mesh, p) - p; `fit`: as given to
// box_wall (the solid box's lattice stretched to fit it).
Reach wall_reach(const WallSpec& w, const Mesh* mesh, const Vec3d& p, const Vec3d& mirror, double dp, bool fit);
// True if a fluid particle at p would overlap wall w (inside a solid box, or
// behind or within mesh_clearance dp of a mesh surface; 0: at or behind it).
bool blocked_by(const WallSpec& w, const Mesh* mesh, const Vec3d& p, double dp, double mesh_clearance = 0.5);
// The mesh's axis-aligned bounding box.
Box bounds(const Mesh& m);
// True if p lies behind a face of wall w, within its `band` of wall layers (a tank's
// walls, not the open air beyond an open face or above its walls; inside a solid box;
// behind a mesh surface): where no water can be.
bool behind_wall(const WallSpec& w, const Mesh* mesh, const Vec3d& p, double band);

} // namespace surge::geometry
