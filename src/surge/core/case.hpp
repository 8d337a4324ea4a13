// Typed description of a case, produced by io::read_case from a YAML file.
// Solvers read these structs, never YAML. Defaults are SPEC's.
#pragma once
#include "surge/core/types.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace surge {

struct Box {
  Vec3d min{}, max{};
  [[nodiscard]] bool contains(const Vec3d& p, double tol = 0) const {
    return p.x >= min.x - tol && p.x <= max.x + tol && p.y >= min.y - tol && p.y <= max.y + tol && p.z >= min.z - tol &&
           p.z <= max.z + tol;
  }
  [[nodiscard]] double volume() const { return (max.x - min.x) * (max.y - min.y) * (max.z - min.z); }
};

struct TimeConfig {
  double end = 1.0;
  double output_every = 0.02;
  double gauge_every = 0.0; // 0: every output_every / 10
  double dt_min = 0.0;      // 0: 1e-3 of the first time step; below this the run is stopped
  long max_steps = 0;       // > 0: stop after this many steps (benchmarks)
  // Wall-clock seconds between checkpoints written between outputs (0: only with outputs),
  // so that a killed run loses at most this much work however far apart the outputs are.
  double checkpoint_every_wall = 1800;
};

struct SphConfig {
  double h_over_dp = 1.2;
  double alpha = 0.01;
  // The defaults are the settings docs/validation.md recommends for waves (mdbc, laminar,
  // fickian); the paper's scheme is dynamic, artificial, none, which its cases name.
  std::string viscosity = "laminar"; // artificial (SPEC 2.4) | laminar (SPEC 8, Morris et al. 1997) | laminar_sps
  double nu = 1.0e-6;                // kinematic viscosity [m^2/s] (laminar)
  double sps_smagorinsky = 0.12;     // laminar_sps: C_s (Dalrymple & Rogers 2006)
  double sps_blin = 0.0066;          // laminar_sps: C_I
  std::string shifting = "fickian";  // none | fickian (SPEC 8, Lind et al. 2012) | delta_plus
  double shifting_coefficient = 2.0; // A
  double shifting_mach = 0.1;        // delta_plus: the flow's Mach number (speed in D: Ma c0)
  double free_surface = 2.75;        // position divergence below which a particle is at the surface
  double delta = 0.1;
  double eta = 20.0;
  double cfl = 0.2;
  double rho0 = 1000.0;
  double hmax = 0.0;                 // 0: from the fluid regions (highest water top - lowest water bottom)
  double c0 = 0.0;                   // 0: c0 = eta sqrt(g hmax); > 0 sets the speed of sound directly
  std::string integrator = "verlet"; // verlet | symplectic
  std::string diffusion = "molteni"; // density diffusion: molteni (SPEC §2.3) | fourtakas (dynamic part only)
  std::string boundary = "mdbc";     // dynamic (the paper's, SPEC §2.6) | mdbc (English et al. 2022, no gap)
  bool no_penetration = true;        // keep fluid dp/4 in front of every wall face (sph/boundary/no_penetration.hpp)
  int euler_every =
      10; // Verlet: an Euler step every this many steps (40 is unstable with delta-SPH: docs/validation.md)
  double rho_min = 0.7; // removal bounds, as fractions of rho0
  double rho_max = 1.3;
  double max_removed_share = 0.05; // stop the run beyond this share of fluid particles removed
  bool hydrostatic_init = true;    // start fluid density from the hydrostatic pressure
};

struct FluidRegion {
  // A box of water, or a reservoir: every lattice point below `level`, clear of the walls
  // and connected to the seed point's column (sph/initial_state.cpp). A reservoir's box is
  // the domain below its level (what the hydrostatic start and the sound speed read).
  Box box;
  Vec3d velocity{};
  // A box's filling: exact (round(L / dp) points per axis, the spacing stretched to fill
  // it, the particle mass from the volume placed) or lattice (whole spacings, centred).
  std::string fill = "exact";
  bool reservoir = false;
  double level = 0;              // the still water surface [m]
  double seed_x = 0, seed_y = 0; // a point of the water's surface, in the reservoir
  // Water given particle by particle (`particles`: a table of x, y, z, vx, vy, vz and
  // optionally rho; rho 0 where absent: the still water's below the region's top). Its
  // box is the particles' bounds grown by dp/2.
  std::string particles; // the file, as resolved
  std::vector<Vec3d> given_pos, given_vel;
  std::vector<double> given_rho;
  int line = 0;
  [[nodiscard]] bool given() const { return !particles.empty(); }
};

enum class Face { XMin, XMax, YMin, YMax, ZMin, ZMax };

// An absorbing zone (damping): the last `length` of the domain before `face`, in which the
// water's velocity relaxes towards zero (sph/damping.hpp).
struct DampingSpec {
  Face face = Face::XMax;
  double length = 0; // [m]
  double rate = 10;  // relaxation rate at the face [1/s]
  int line = 0;
};

// A wall's prescribed motion (motion/motion_law.hpp): a law chosen by name and the
// parameters it reads (each law's entry in motion/motion_laws.cpp says which). The law
// gives the displacement of the pivot and a rotation about it, from `start` on.
struct MotionSpec {
  std::string law;                // empty: the wall stands still
  double start = 0;               // the wall rests until then [s]
  Vec3d velocity{};               // constant_velocity; uniform_acceleration: the velocity at start
  Vec3d acceleration{};           // uniform_acceleration
  Vec3d direction{1, 0, 0};       // ln_cosh, capped_acceleration, solitary: the line of motion
  double s0 = 0, t0 = 0;          // ln_cosh: s = s0 ln cosh(t / t0)
  double accel = 0, terminal = 0; // capped_acceleration: s = accel t^2 / 2 until the speed reaches terminal
  double period = 0, phase = 0;   // sinusoidal [s], [degrees]
  Vec3d amplitude{};              // sinusoidal: translation amplitude [m]
  double angle = 0;               // sinusoidal: rotation amplitude about axis through pivot [degrees]
  Vec3d axis{0, 1, 0};            // rotation axis (sinusoidal)
  Vec3d pivot{};                  // the point the rotation turns about and body gauges report
  bool pivot_given = false;       // else the centre of the wall's box or mesh bounds
  double height = 0, depth = 0;   // solitary: the wave's amplitude A and the still depth h [m]
  std::string csv, csv_path;      // time_series: as written, resolved against the case file
  int line = 0;
  [[nodiscard]] bool moves() const { return !law.empty(); }
};

// A wall that moves freely (a rigid body): under gravity and the water's force and
// moment, in 6 degrees of freedom or along a line (a slider on a rail or slope) with
// Coulomb friction against it (motion/free_body.hpp).
struct BodySpec {
  bool free = false;                    // the wall has a `body` section
  double mass = 0, density = 0;         // one of them: the mass, or from the volume of the solid box or closed mesh
  Vec3d inertia{};                      // principal moments about the centre of mass, along x, y, z; 0: from the shape
  std::string constraint = "none";      // none (6 DOF) | line (translation along direction only)
  Vec3d direction{1, 0, 0};             // line: the rail
  double mu_static = 0, mu_kinetic = 0; // line: Coulomb friction against the rail
  double travel = 0; // line: > 0, the body stops for good after this far along direction (a stop block) [m]
  Vec3d velocity{};  // at t = 0
  Vec3d spin{};      // 6 DOF: angular velocity at t = 0 [rad/s] (a perturbation)
  int line = 0;
};

struct WallSpec {
  std::string name;       // for force gauges
  bool is_mesh = false;   // a triangle surface: an STL file, or an elevation grid (`terrain`)
  bool terrain = false;   // mesh_path is a raster of ground elevations (geometry/terrain.hpp)
  Box box;                // box walls: the tank interior, or the solid obstacle
  bool solid = false;     // box: particles fill the inside instead of surrounding it; mesh: no water behind it
  std::vector<Face> open; // box tank: faces left without wall
  std::string mesh;       // as written in the case file
  std::string mesh_path;  // resolved against the case file's folder
  MotionSpec motion;      // prescribed motion; none by default
  BodySpec body;          // or free motion
  [[nodiscard]] bool moves() const { return motion.moves() || body.free; }
  int line = 0;
};

enum class GaugeType { Height, Pressure, Velocity, Force, Sphere, DemWall, Body };

struct GaugeSpec {
  std::string name;
  GaugeType type = GaugeType::Height;
  double x = 0, y = 0;            // height gauges
  std::string surface = "column"; // height: column (top of the water standing on the bed) or highest (wet point)
  Vec3d at{};                     // pressure / velocity gauges
  std::string component = "z";    // velocity: x|y|z|mag ; force: x|y|z|mag ; sphere: x|y|z|vx|vy|vz|fx|fy|fz|mx|my|mz
  std::string wall;               // force and body gauges: name of the wall
  int sphere = 0;                 // sphere gauges: index of the sphere (packs in order, spheres in pack order)
  Vec3d about{};                  // dem_wall gauges: moments about this point (absolute)
  int line = 0;
};

// DEM (SPEC §3): materials by name, sphere packs, walls for the spheres.
struct DemMaterialSpec {
  std::string name;
  double density = 2500, young = 1e6, nu = 0.2, phi_deg = 30, restitution = 0.5;
  double k_roll = 0, k_roll_max = 0, k_twist = 0, k_twist_max = 0;
  bool bonded = false;
  double bond_cn = 0, bond_cs = 0;
  int line = 0;
};

struct DemPackSpec {
  bool from_csv = false;
  Box box;               // region: a box, or the bounding box of `mesh`
  std::string mesh_path; // region: inside this closed STL mesh (resolved path); empty: the box
  long random_count = 0; // > 0: a random loose pack of this many spheres instead of the lattice
  double settle = 0;     // > 0: settle the pack under gravity (local damping 0.7) for this long [s]
  double radius = 0;
  double radius_min = 0; // > 0: radii drawn uniformly from [radius_min, radius]
  double jitter = 0;     // lattice: random offset of each sphere, as a fraction of its radius
  std::string csv;       // x, y, z, r per line (resolved path)
  // A slide body: between a pre-failure surface (top) and a sliding surface (bottom), two
  // elevation grids (resolved paths; geometry/slide_body.hpp).
  std::string top_path, bottom_path;
  int material = 0; // index into DemConfig::materials
  Vec3d velocity{};
  bool fixed = false; // held in place (forces on it are still computed)
  int line = 0;
  // Whether radii are drawn from [radius_min, radius].
  [[nodiscard]] bool radius_range() const { return radius_min > 0 && radius_min < radius; }
};

struct DemWallSpec {
  std::string name; // optional, for dem_wall gauges
  bool is_mesh = false;
  bool terrain = false;           // mesh_path is an elevation grid, not an STL file
  Vec3d point{}, normal{0, 0, 1}; // plane
  std::string mesh_path;          // STL or raster
  int material = 0;
  MotionSpec motion;   // prescribed motion (a plane or mesh); none by default
  BodySpec body;       // or free motion (a closed mesh), under the spheres' contacts and gravity
  std::string follows; // or the motion of the named SPH wall (one solid seen by water and spheres)
  [[nodiscard]] bool moves() const { return motion.moves() || body.free || !follows.empty(); }
  int line = 0;
};

struct DemConfig {
  double dt_factor = 0.1;                // dt = factor * min sqrt(m / k_n)
  double bond_gap = 1e-4;                // spheres of bonded materials closer than this are bonded at the start [m]
  double local_damping = 0;              // Cundall local damping a_d (0 for dynamic runs; ~0.7 to settle a pack)
  std::string contact = "linear_spring"; // the contact law by name (dem/contact_law.hpp)
  std::vector<DemMaterialSpec> materials;
  std::vector<DemPackSpec> packs;
  std::vector<DemWallSpec> walls;
  [[nodiscard]] bool active() const { return !packs.empty(); }
};

struct CouplingConfig {
  int body_layers = 0; // layers of body particles per sphere; 0: ceil(2h/dp) (SPEC §4)
  // Distributed runs: "exact" combines every body particle's acceleration across processes
  // (sphere forces bitwise those of one process; traffic 24 B per body particle and step);
  // "per_sphere" combines each process's per-sphere sums in rank order (24 B per sphere,
  // the same on every process, equal to one process's to round-off): for 10^5 spheres.
  std::string force_sum = "exact";
};

// Hazard maps (sph/hazard_maps.hpp): accumulated at every gauge time on the lattice of the
// first terrain wall's grid (every `coarsen`-th pixel centre), written with every output.
struct RunUpLine {
  std::string name;
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0; // from, to
  int line = 0;
};
struct HazardConfig {
  bool enabled = false;        // the case has a `hazard` section
  int coarsen = 1;             // map cell = this many terrain pixels
  double arrival_height = 0.1; // arrival: first time the surface stands this far above still_level [m]
  double still_level = 0;      // given, or the first reservoir's level
  std::vector<RunUpLine> run_up;
  int line = 0;
};

struct Case {
  std::string name = "case";
  std::string source; // file it came from
  double dp = 0.0;
  TimeConfig time;
  Vec3d gravity{0, 0, -9.81};
  Box domain;
  // domain.periodic: the axes whose two faces are one (particles leaving through one enter
  // at the other, neighbours are found across them).
  std::array<bool, 3> periodic{};
  // domain.symmetry: the faces (indexed by Face) that are mirror planes (the water near one
  // sees its mirror image, so half a symmetric tank gives the whole tank's answer).
  std::array<bool, 6> symmetry{};
  std::vector<DampingSpec> damping;
  SphConfig sph;
  std::vector<FluidRegion> fluid;
  std::vector<WallSpec> walls;
  std::vector<GaugeSpec> gauges;
  DemConfig dem;
  CouplingConfig coupling;
  HazardConfig hazard;

  [[nodiscard]] bool any_periodic() const { return periodic[0] || periodic[1] || periodic[2]; }
  [[nodiscard]] bool any_symmetry() const {
    return std::any_of(symmetry.begin(), symmetry.end(), [](bool b) { return b; });
  }
  // Faces of either kind: their images (domain/images.hpp) supply what lies beyond.
  [[nodiscard]] bool image_face(int face) const {
    return periodic[static_cast<std::size_t>(face / 2)] || symmetry[static_cast<std::size_t>(face)];
  }
  [[nodiscard]] bool coupled() const { return dem.active() && !fluid.empty(); }
  // The wall (SPH) or DEM wall of that name, or null.
  [[nodiscard]] const WallSpec* wall_named(const std::string& n) const {
    for (const auto& w : walls)
      if (w.name == n) return &w;
    return nullptr;
  }
  [[nodiscard]] const DemWallSpec* dem_wall_named(const std::string& n) const {
    for (const auto& w : dem.walls)
      if (!w.name.empty() && w.name == n) return &w;
    return nullptr;
  }
  [[nodiscard]] double h() const { return sph.h_over_dp * dp; }
  [[nodiscard]] double water_depth() const {
    if (sph.hmax > 0) return sph.hmax;
    double lo = 1e300, hi = -1e300;
    for (const auto& f : fluid) {
      lo = std::min(lo, f.box.min.z);
      hi = std::max(hi, f.box.max.z);
    }
    return fluid.empty() ? 0.0 : hi - lo;
  }
  [[nodiscard]] double g() const { return norm(gravity); }
  [[nodiscard]] double sound_speed() const { return sph.c0 > 0 ? sph.c0 : sph.eta * std::sqrt(g() * water_depth()); }
};

inline const char* face_name(Face f) {
  constexpr const char* names[] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  return names[static_cast<int>(f)];
}

} // namespace surge
