// DEM spheres (SPEC §3): sphere–sphere and sphere–wall contacts with per-contact
// history (shear force, rolling and twisting rotation), under the contact law the case
// names (contact_law.hpp: the paper's linear spring or Hertz–Mindlin), Newton–Euler
// integration with an orientation quaternion. Each sphere computes all of its own contacts and writes
// only its own force, torque and history row; the pair terms are evaluated in a
// canonical order (lower id first) and negated on the other side, so both sides agree
// bit for bit and results do not depend on the thread count.
//
// Neighbour list with a skin (neighbour/pair_list.hpp): each sphere lists the spheres
// within r_i + r_j + skin (and its bonded partners). A step has two passes: each pair is evaluated once, by its A
// sphere (lower id), which updates the pair's history in its own slot and writes the
// pair's forces beside it; then each sphere sums the forces of its listed pairs in list
// order, its A-side pairs with their sign and its B-side ones through the slot index of
// the partner's entry (found when the list was built). No grid walk, no slot search, no
// sort per step, no atomics. The spheres are sorted and the lists rebuilt (histories
// carried over by partner id) only when a sphere has moved more than half the skin.
//
// External forces (the fluid's, SPEC §4) are held per sphere id and added to the
// contact forces at every step until replaced.
#pragma once
#include "surge/dem/contact_law.hpp"
#include "surge/dem/rigid_state.hpp"
#include "surge/domain/image_frame.hpp"
#include "surge/domain/periodic.hpp"
#include "surge/neighbour/pair_list.hpp"
#include "surge/neighbour/uniform_grid.hpp"
#include "surge/par/phase_timer.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace surge::dem {

// An infinite plane wall: points x with dot(x - point, normal) >= 0 are inside.
struct Plane {
  Vec3 point{}, normal{0, 0, 1};
  int material = 0;
  int body = -1; // >= 0: the plane moves with that wall body (set_wall_bodies), else it stands
};

// A wall triangle (from an STL mesh). Triangles of one mesh form one smooth surface:
// a sphere touching several of them at a shared edge or vertex gets one contact.
struct WallTriangle {
  Vec3 a{}, b{}, c{};
  int mesh = 0;
  int material = 0;
  int body = -1; // >= 0: the triangle moves with that wall body, else it stands (in the grid)
};

// A sphere's reaction from one wall contact slot (bodies only): the force on the sphere
// and the torque about its centre, as the step applied them; the wall body feels minus
// these (about its pivot: minus (x_sphere - pivot) x force minus the torque).
struct WallReaction {
  Vec3 force{}, torque{};
};

// The wall triangles a sphere may touch, by the cell of its centre: each cell lists (in
// ascending order) the triangles whose bounding box, grown by the largest sphere radius,
// meets it. Plain view for the kernels.
struct TriangleGridView {
  Vec3 lo{};
  Real inv_cell = 0;
  int n[3] = {0, 0, 0};
  const std::uint32_t* start = nullptr; // per cell, into items (CSR)
  const std::uint32_t* items = nullptr;
  // The range [begin, end) of items for a point; empty outside the grid.
  SURGE_HD void range(const Vec3& x, std::uint32_t& begin, std::uint32_t& end) const {
    begin = end = 0;
    int c[3];
    for (int k = 0; k < 3; ++k) {
      const Real u = (x[k] - lo[k]) * inv_cell;
      if (!(u >= 0) || !(u < static_cast<Real>(n[k]))) return;
      c[k] = static_cast<int>(u);
    }
    const int cell = (c[2] * n[1] + c[1]) * n[0] + c[0];
    begin = start[cell];
    end = start[cell + 1];
  }
};

// The walls that move, as the kernels see them: each body's state, reach (its farthest
// vertex from the pivot) and triangles (CSR by body).
struct WallBodiesView {
  int n = 0;
  const RigidState* state = nullptr;
  const Real* reach = nullptr;
  const std::uint32_t* start = nullptr;
  const std::uint32_t* items = nullptr;
  // Whether sphere (x, r) may touch a triangle of body b.
  SURGE_HD bool near(int b, const Vec3& x, Real r) const {
    const Real d = reach[b] + r;
    const Vec3 e = x - state[b].pos;
    return start[b + 1] > start[b] && dot(e, e) < d * d;
  }
};

// A sphere touching a moving wall, for the sum of the loads on the bodies: its id, its
// position and, per wall slot, the slot's body (or -1) and reaction.
struct BodyContact {
  std::uint32_t id;
  Vec3 pos;
  int body[4]; // max_wall_slots
  WallReaction react[4];
};

struct Sphere {
  Vec3 pos{}, vel{}, omega{};
  Real radius = 0.01f;
  int material = 0;
  bool fixed = false; // held in place (still feels contacts and the fluid, which are reported)
};

inline constexpr int max_contacts = 16;  // listed partner spheres (with history) per sphere
inline constexpr int max_wall_slots = 4; // wall contacts (planes, mesh points) with history per sphere
static_assert(sizeof(BodyContact::body) / sizeof(int) == max_wall_slots);
inline constexpr std::uint32_t no_partner = 0xFFFFFFFFU;
inline constexpr std::uint32_t plane_partner = 0x80000000U;    // partner id of plane k: plane_partner | k
inline constexpr std::uint32_t triangle_partner = 0x40000000U; // partner id of wall triangle t
inline constexpr int max_wall_candidates = 8;                  // wall triangles touching one sphere
// Contacts with mirror images across symmetry faces, with history, per sphere (more are
// evaluated, without history); each slot's partner is mirror_key(image, id).
inline constexpr int max_mirror_slots = 8;
inline constexpr std::uint32_t max_mirrored_spheres = 1U << 27;
// image: (sx + 1) + 3 (sy + 1) + 9 (sz + 1) for the shifts sx, sy, sz (domain::shifted).
[[nodiscard]] SURGE_HD constexpr std::uint32_t mirror_key(int image, std::uint32_t id) {
  return (static_cast<std::uint32_t>(image) << 27) | id;
}

// One history slot: the partner and the A-side (lower id) springs of that contact.
struct ContactSlot {
  std::uint32_t partner = no_partner;
  Vec3 shear{};             // shear force on the canonical A sphere
  Vec3 roll{};              // accumulated rolling rotation (A relative to B)
  Vec3 twist{};             // accumulated twisting rotation
  std::uint32_t bonded = 0; // 1 while a cohesive bond holds this contact
};

// A listed pair's evaluation by its A sphere: force on A, torques about A's and B's centres.
struct PairForce {
  Vec3 force_a{}, torque_a{}, torque_b{};
  std::uint32_t flags = 0; // 1: touching (or bonded), 2: its bond broke this step
};

// Force and moment the spheres exert on a wall (a gauge).
struct WallLoad {
  Vec3 force{}, moment{};
};
struct WallLoadD {
  Vec3d force{}, moment{};
};
struct SumWallLoads {
  SURGE_HD WallLoad operator()(const WallLoad& a, const WallLoad& b) const {
    return {a.force + b.force, a.moment + b.moment};
  }
};

// What two materials' contacts share, whatever the radii (friction, rolling and twisting
// resistance, bond strengths; SPEC 3): a table of n x n, mixed once.
// (T: one value, or a batch in the CPU's batched pair pass.)
template <class T>
struct MixedPairT {
  T tan_phi;
  T k_roll, k_roll_max, k_twist, k_twist_max;
  T bond_cn, bond_cs; // 0 unless both materials bond
};
using MixedPair = MixedPairT<Real>;

struct DemView {
  int n = 0;
  const MixedPair* mixed; // n_materials x n_materials
  int n_materials;
  bool resists; // some pair of materials has rolling or twisting resistance
  Vec3 *pos, *vel, *omega, *force, *torque;
  Real* quat; // 4 per sphere (w, x, y, z)
  Real *radius, *mass, *inertia;
  std::uint8_t* material;
  std::uint32_t* id;
  neighbour::PairListView list;       // the listed partners (max_contacts each) and the pairs
  ContactSlot* hist;                  // by pair: the A side's history (partner: B's id)
  PairForce* pair;                    // by pair: the A side's evaluation this step
  PairLaw* law;                       // by pair: the contact law's constants
  ContactSlot* wall_hist;             // max_wall_slots per sphere: wall contacts, by partner id
  std::uint32_t* broken;              // bonds this sphere has lost so far (each bond counts on both spheres)
  std::uint32_t* ncontact;            // contacts of the last step
  std::uint8_t* fixed;                // 1: not integrated
  const Vec3 *ext_force, *ext_torque; // by sphere id
  Vec3* pos_built;                    // positions when the list was built
  domain::PeriodicAxes period;        // pairs meet through the nearest image (rel)
  domain::ImageFrame mirror;          // symmetry faces (mirror_lo / hi), band: the list's reach
  ContactSlot* mirror_hist;           // max_mirror_slots per sphere, by id (null without symmetry faces)
  // Position of a less that of b, through b's nearest periodic image.
  [[nodiscard]] SURGE_HD Vec3 rel(int a, int b) const { return period.rel(pos[a], pos[b]); }
};

// The CPU's batched passes (dem_simd.hpp), for spheres [begin, end): the pair pass
// evaluates their pairs (their A side) and writes each pair's history and forces, as
// detail::pair_pass does; the integration advances them, as detail::integrate does.
using PairPassFn = void (*)(const DemView& v, Real dt, int begin, int end);
using IntegrateFn = void (*)(const DemView& v, Vec3 gravity, Real ad, Real dt, int begin, int end);
// The spheres the solver hands to one call.
constexpr int pair_pass_block = 64;

class DemSolver {
public:
  // contact_law: an index into ContactLaws (contact_law.hpp; 0, the linear spring, by
  // default). Throws std::invalid_argument for a material the law cannot take.
  DemSolver(std::vector<Material> materials, std::vector<Plane> planes, Vec3 gravity, Vec3 lo, Vec3 hi,
            int contact_law = 0);
  void set_spheres(const std::vector<Sphere>& s);
  // Periodic axes (before set_spheres): spheres meet across their faces through the
  // nearest image, and a sphere is moved back by a period once it lies half a period
  // beyond a face (until then it moves exactly as in a wider box). Throws
  // std::invalid_argument for a period under twice the list's reach plus a sphere.
  void set_periodic(const domain::PeriodicAxes& p) { period_ = p; }
  [[nodiscard]] const domain::PeriodicAxes& periodic() const { return period_; }
  // Symmetry faces (before set_spheres; indexed as Face: xmin, xmax, ymin, ...): a sphere
  // near one meets the mirror images of its neighbours and of itself (positions reflected,
  // velocities' normal components and spins mirrored), each contact kept with its history
  // and bond by the sphere itself, so half a symmetric pack behaves as the whole.
  // set_spheres throws std::invalid_argument for a sphere that crosses such a face (it
  // would overlap its own image) and for symmetry faces with periodic ones.
  void set_symmetry(const std::array<bool, 6>& faces);
  // Triangle-mesh walls (all meshes together; WallTriangle::mesh tells them apart).
  void set_wall_triangles(const std::vector<WallTriangle>& t);
  // Bonds every pair of spheres of bonded materials whose gap is below `gap` (SPEC §3,
  // CFM); call once after set_spheres. Returns the number of bonds.
  long bond_touching(Real gap);
  // Cundall local damping coefficient a_d (0: off, the default for dynamic runs).
  void set_local_damping(Real ad) { local_damping_ = ad; }
  // Force and moment (about `about`) of the spheres on plane `plane` (index among the
  // planes, or -1) or on the triangles of mesh `mesh` (or -1), from the current contacts.
  [[nodiscard]] WallLoad wall_load(int plane, int mesh, Vec3 about);
  // Walls that move (issue 34): the planes and triangles whose `body` is k follow body k's
  // rigid state. `placed`: each body's state as the walls were given (its pivot there, no
  // rotation); call after set_spheres and set_wall_triangles. move_walls places them for
  // new states (pivot, orientation, velocities: the spheres feel the wall's velocity at
  // the contact point); each step then sums the spheres' reactions on every body
  // (body_loads: force, and moment about the pivot of the last move_walls), exactly the
  // negatives of what the spheres received, in sphere id order and in double.
  void set_wall_bodies(const std::vector<RigidState>& placed);
  void move_walls(const std::vector<RigidState>& states);
  [[nodiscard]] const std::vector<WallLoadD>& body_loads() const { return body_loads_; }
  [[nodiscard]] bool has_wall_bodies() const { return !body_states_host_.empty(); }
  // The moving triangles where they are now (host copies; empty without moving walls).
  [[nodiscard]] std::vector<std::array<Vec3, 3>> moving_triangles() const;
  // Bonds broken since the start.
  [[nodiscard]] long broken_bonds() const;
  // dt = factor * the contact law's smallest time scale over the spheres (linear spring:
  // sqrt(m / k_n) against an equal sphere, SPEC §3; Hertz-Mindlin: the Rayleigh time).
  [[nodiscard]] Real critical_dt(Real factor) const;
  void step(Real dt);
  // External force and moment on each sphere, by id (n entries each, in the execution
  // space; the fluid's in a coupled run), held until overwritten; gravity is not included.
  par::Buffer<Vec3>& external_force() { return ext_force_; }
  par::Buffer<Vec3>& external_torque() { return ext_torque_; }
  [[nodiscard]] std::vector<Vec3> external_forces() const { return par::download(ext_force_); }
  [[nodiscard]] std::vector<Vec3> external_torques() const { return par::download(ext_torque_); }
  // The complete state (spheres, orientations, contact history, broken bonds, external
  // forces) as bytes, and back: a restored solver continues bit for bit. restore() needs a
  // solver built from the same case (materials, walls, sphere count).
  [[nodiscard]] std::string save() const;
  void restore(const std::string& bytes);
  // Centre, velocities and orientation of every sphere into out[id] (execution space).
  void rigid_states(par::Buffer<RigidState>& out);
  // Current state by sphere id (host copies).
  [[nodiscard]] std::vector<Sphere> spheres() const;
  [[nodiscard]] std::vector<Vec3> forces() const; // contact forces of the last step, by id
  [[nodiscard]] std::vector<Vec3> torques() const;
  [[nodiscard]] std::vector<Real> quaternions() const;             // 4 per sphere, by id
  [[nodiscard]] std::vector<std::uint32_t> contact_counts() const; // by id
  [[nodiscard]] std::vector<std::uint32_t> intact_bonds() const;   // id pairs (lower id first), flattened
  [[nodiscard]] int size() const { return n_; }
  // The pair pass and integration: "avx2" or "sse2" (the batched copies, in builds with
  // SURGE_SIMD on a CPU that has the set) or "off" (the scalar passes, the ones CUDA runs);
  // false, and nothing changed, where the copy is not there. By default the widest, or
  // SURGE_SIMD's choice.
  bool set_pair_pass(const char* isa);
  [[nodiscard]] const char* pair_pass() const { return pair_pass_name_; }
  // True when every sphere position is finite (a reduction; nothing is copied to the host).
  [[nodiscard]] bool finite();
  DemView view();

private:
  enum FieldUse : unsigned { kSorted = 1 };
  template <class Self, class View, class F>
  static void for_each_sphere_field(Self& s, View& v, F&& f);
  // The sort's scratch buffer for a buffer of T (sort_spheres runs only at the start of
  // rebuild_list, when hist_old_ holds nothing needed).
  template <class T>
  par::Buffer<T>& scratch_for(par::Buffer<T>& /*b*/) {
    if constexpr (std::is_same_v<T, Vec3>)
      return tmp3_;
    else if constexpr (std::is_same_v<T, Real>)
      return tmp1_;
    else if constexpr (std::is_same_v<T, std::uint8_t>)
      return tmpb_;
    else if constexpr (std::is_same_v<T, std::uint32_t>)
      return tmpu_;
    else
      return hist_old_; // (no ContactSlot field is sorted: the wall histories are by id)
  }
  void sort_spheres();
  void set_grid(); // the spheres' grid over the domain (and half a period beyond periodic faces)
  void check_mirrored(const std::vector<Sphere>& s) const;
  [[nodiscard]] bool mirrored() const { return mirror_.any(); } // some symmetry face
  // Sorts the spheres and lists each one's partners within r_i + r_j + skin (or bonded).
  void rebuild_list();
  // Whether some sphere has moved more than half the skin since the list was built.
  [[nodiscard]] bool list_stale();
  // Neighbour search radius: touching spheres, and bonded ones pulled slightly apart.
  [[nodiscard]] Real reach() const { return Real(2.1) * max_radius_; }
  // The list's skin (a tenth of the largest radius, or more for a wide bond gap), and the
  // grid search radius of a rebuild.
  [[nodiscard]] Real skin() const { return skin_; }
  [[nodiscard]] Real list_reach() const { return std::max(reach(), 2 * max_radius_ + skin()); }

  std::vector<Material> materials_host_;
  par::Buffer<Material> materials_;
  par::Buffer<MixedPair> mixed_; // by material pair (MixedPair)
  bool resists_ = false;         // DemView::resists
  par::Buffer<Plane> planes_;
  int n_planes_ = 0;
  par::Buffer<WallTriangle> triangles_;
  int n_triangles_ = 0;
  // The triangles by cell (TriangleGridView), built for spheres up to tri_grid_radius_.
  std::vector<WallTriangle> triangles_host_;
  par::Buffer<std::uint32_t> tri_start_, tri_items_;
  TriangleGridView tri_grid_{};
  Real tri_grid_radius_ = -1;
  void build_triangle_grid();
  // Moving walls: each body's state (host and device), its triangles (CSR by body, their
  // indices and body-frame arms from the pivot) and reach (the farthest vertex from the
  // pivot); the planes' body-frame arms; the reactions per sphere wall slot; the loads.
  std::vector<RigidState> body_states_host_;
  par::Buffer<RigidState> body_states_;
  std::vector<Plane> planes_host_, planes_ref_;
  par::Buffer<std::uint32_t> body_start_, body_items_;
  par::Buffer<WallTriangle> body_ref_;
  par::Buffer<Real> body_reach_;
  par::Buffer<WallReaction> wall_react_;
  par::Buffer<std::uint32_t> body_flag_, body_at_; // per sphere (sorted): touches a body; its place
  par::Buffer<BodyContact> body_contacts_;
  std::vector<BodyContact> body_contacts_host_;
  std::vector<WallLoadD> body_loads_;
  void sum_body_loads();
  [[nodiscard]] WallBodiesView bodies_view();
  Vec3 gravity_{};
  Real local_damping_ = 0;
  int law_index_ = 0;                    // the contact law, an index into ContactLaws
  PairPassFn batched_ = nullptr;         // the CPU's batched pair pass (null: the scalar one)
  IntegrateFn batched_motion_ = nullptr; // and integration
  const char* pair_pass_name_ = "off";
  neighbour::UniformGrid grid_;
  Vec3 lo_{}, hi_{};
  domain::PeriodicAxes period_{};
  int n_ = 0;
  Real max_radius_ = 0;
  par::Buffer<Vec3> pos_, vel_, omega_, force_, torque_, tmp3_;
  par::Buffer<Real> quat_, radius_, mass_, inertia_, tmp1_;
  par::Buffer<std::uint8_t> material_, fixed_, tmpb_;
  par::Buffer<Vec3> ext_force_, ext_torque_;
  par::Buffer<std::uint32_t> id_, tmpu_, broken_, ncontact_;
  par::Buffer<ContactSlot> hist_, hist_old_, wall_hist_; // pairs; the last list's (the sort's scratch); walls
  par::Buffer<std::uint32_t> nbr_, nnbr_, entry_, pair_begin_, pair_count_, pair_b_;
  par::Buffer<PairForce> pair_;
  par::Buffer<PairLaw> law_;
  std::uint32_t n_pairs_ = 0;
  domain::ImageFrame mirror_{};          // symmetry faces (no periodic axes: those are period_); 84 B beside n_pairs_
  par::Buffer<Vec3> pos_built_;          // positions when the list was built
  par::Buffer<ContactSlot> mirror_hist_; // max_mirror_slots per sphere, by id; with symmetry faces only
  bool list_valid_ = false;
  Real skin_ = 0;
};

} // namespace surge::dem
