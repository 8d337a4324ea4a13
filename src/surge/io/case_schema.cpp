#include "surge/io/case_schema.hpp"

#include "surge/core/gauge_types.hpp"

#include "surge/motion/motion_law.hpp"

#include <cmath>
#include <sstream>

namespace surge::io {

namespace {
std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}
} // namespace

bool Range::holds(double v) const {
  const bool above = lo_open ? v > lo : v >= lo;
  const bool below = hi_open ? v < hi : v <= hi;
  return above && below; // NaN fails both
}

std::string Range::message() const {
  const bool no_hi = std::isinf(hi);
  if (no_hi && lo == 0) return lo_open ? "must be positive" : "must not be negative";
  if (no_hi) return (lo_open ? "must exceed " : "must be at least ") + num(lo);
  return "must lie in " + text();
}

std::string Range::text() const {
  const bool no_lo = std::isinf(lo), no_hi = std::isinf(hi);
  if (no_lo && no_hi) return "";
  if (no_hi) return (lo_open ? "> " : ">= ") + num(lo);
  if (no_lo) return (hi_open ? "< " : "<= ") + num(hi);
  return std::string(lo_open ? "(" : "[") + num(lo) + ", " + num(hi) + (hi_open ? ")" : "]");
}

Range positive() { return between(0, true, std::numeric_limits<double>::infinity(), false); }
Range non_negative() { return between(0, false, std::numeric_limits<double>::infinity(), false); }
Range at_least(double lo) { return between(lo, false, std::numeric_limits<double>::infinity(), false); }
Range between(double lo, bool lo_open, double hi, bool hi_open) {
  Range r;
  r.lo = lo;
  r.hi = hi;
  r.lo_open = lo_open;
  r.hi_open = hi_open;
  return r;
}

const std::vector<Field<TimeConfig>>& time_fields() {
  using T = TimeConfig;
  static const std::vector<Field<T>> f{
      {"end", &T::end, "s", positive(), {}, "simulated time at which the run stops"},
      {"output_every", &T::output_every, "s", positive(), {}, "time between particle outputs (and checkpoints)"},
      {"gauge_every", &T::gauge_every, "s", non_negative(), {}, "time between gauge samples; 0: output_every / 10"},
      {"dt_min",
       &T::dt_min,
       "s",
       non_negative(),
       {},
       "a step shorter than this stops the run as diverged; 0: 1e-3 of the first step"},
      {"max_steps", &T::max_steps, "", non_negative(), {}, "stop after this many steps; 0: no limit (benchmarks)"},
      {"checkpoint_every_wall",
       &T::checkpoint_every_wall,
       "s (wall clock)",
       non_negative(),
       {},
       "wall-clock time between checkpoints written between outputs; 0: with outputs only"},
  };
  return f;
}

namespace {
// sph's model choices: the viscous term (with SPS's constants), particle shifting and the
// free surface it needs.
std::vector<Field<SphConfig>> sph_model_fields() {
  using S = SphConfig;
  return {
      {"viscosity",
       &S::viscosity,
       "",
       {},
       {"artificial", "laminar", "laminar_sps"},
       "momentum's viscous term: artificial (the paper's: Monaghan's, coefficient alpha), laminar (Morris et al. "
       "1997, the water's kinematic viscosity nu; walls drag with their own velocity) or laminar_sps (laminar plus "
       "the sub-particle-scale stress of Dalrymple & Rogers 2006, filter width dp)"},
      {"nu", &S::nu, "m^2/s", non_negative(), {}, "kinematic viscosity of the water (laminar, laminar_sps)"},
      {"sps_smagorinsky", &S::sps_smagorinsky, "-", non_negative(), {}, "laminar_sps: Smagorinsky constant C_s"},
      {"sps_blin", &S::sps_blin, "-", non_negative(), {}, "laminar_sps: Blin constant C_I"},
      {"shifting",
       &S::shifting,
       "",
       {},
       {"none", "fickian", "delta_plus"},
       "particle shifting: none (the paper's); fickian (Lind et al. 2012: each fluid particle moved down the gradient "
       "of the particle concentration, A h |u| dt grad C, fading to nothing at the free surface); delta_plus (Sun et "
       "al. 2017: A h (Ma c0) dt, each pair weighted against clumping; for water without a free surface, which it "
       "lifts)"},
      {"shifting_coefficient",
       &S::shifting_coefficient,
       "-",
       positive(),
       {},
       "shifting's A (fickian: DualSPHysics's 2; delta_plus: 4 is Sun et al.'s CFL Ma (2h)^2)"},
      {"shifting_mach", &S::shifting_mach, "-", positive(), {}, "delta_plus: the flow's Mach number"},
      {"free_surface",
       &S::free_surface,
       "-",
       between(0, true, 3, true),
       {},
       "a particle whose position divergence (3 inside the water) is below this lies at the free surface: not "
       "shifted, and flagged in the frames' surface field"},
  };
}

// sph's scheme: density diffusion, sound speed, time step and integrator, wall model,
// removal bounds, the initial state.
std::vector<Field<SphConfig>> sph_scheme_fields() {
  using S = SphConfig;
  return {
      {"delta", &S::delta, "-", non_negative(), {}, "delta-SPH density diffusion coefficient (SPEC 2.3)"},
      {"eta", &S::eta, "-", positive(), {}, "speed of sound over sqrt(g hmax) when c0 is 0 (SPEC 2.4)"},
      {"cfl",
       &S::cfl,
       "-",
       positive(),
       {},
       "Courant number of the time step (SPEC 2.5); above 1 the explicit step is unstable (a warning)"},
      {"rho0", &S::rho0, "kg/m^3", positive(), {}, "reference density of the water"},
      {"hmax",
       &S::hmax,
       "m",
       non_negative(),
       {},
       "water depth for the speed of sound; 0: from the fluid boxes (highest top - lowest bottom)"},
      {"c0", &S::c0, "m/s", non_negative(), {}, "speed of sound; 0: eta sqrt(g hmax)"},
      {"integrator",
       &S::integrator,
       "",
       {},
       {"verlet", "symplectic"},
       "time integration: verlet (the paper's, one force evaluation per step) or symplectic (two)"},
      {"diffusion",
       &S::diffusion,
       "",
       {},
       {"molteni", "fourtakas"},
       "density diffusion: molteni (SPEC 2.3) or fourtakas (its dynamic part only)"},
      {"boundary",
       &S::boundary,
       "",
       {},
       {"dynamic", "mdbc"},
       "wall model: dynamic (the paper's, a gap of about h) or mdbc (modified dynamic, no gap)"},
      {"no_penetration",
       &S::no_penetration,
       "",
       {},
       {},
       "keep water a quarter spacing in front of every wall face, with either wall model, so that impacts cannot push "
       "it through a wall"},
      {"euler_every",
       &S::euler_every,
       "steps",
       at_least(1),
       {},
       "Verlet: an Euler step every this many steps (at 40, the paper's, the density diffusion's leapfrog mode "
       "grows: docs/physics.md)"},
      {"rho_min",
       &S::rho_min,
       "of rho0",
       between(0, true, 1, true),
       {},
       "fluid particles below this density are removed"},
      {"rho_max", &S::rho_max, "of rho0", between(1, true, INFINITY, false), {}, "and above this one"},
      {"max_removed_share",
       &S::max_removed_share,
       "-",
       between(0, true, 1, false),
       {},
       "stop the run when more than this share of the fluid particles has been removed"},
      {"hydrostatic_init",
       &S::hydrostatic_init,
       "",
       {},
       {},
       "start the water at the hydrostatic density below its box's top"},
  };
}
} // namespace

const std::vector<Field<SphConfig>>& sph_fields() {
  using S = SphConfig;
  static const std::vector<Field<S>> f = [] {
    std::vector<Field<S>> rows{
        {"h_over_dp", &S::h_over_dp, "-", positive(), {}, "smoothing length h over dp (SPEC 2.1)"},
        {"alpha",
         &S::alpha,
         "-",
         non_negative(),
         {},
         "artificial viscosity coefficient (SPEC 2.2); a case that sets it names sph.viscosity"},
    };
    for (auto&& part : {sph_model_fields(), sph_scheme_fields()}) rows.insert(rows.end(), part.begin(), part.end());
    return rows;
  }();
  return f;
}

const std::vector<Field<HazardConfig>>& hazard_fields() {
  using H = HazardConfig;
  static const std::vector<Field<H>> f{
      {"coarsen", &H::coarsen, "", at_least(1), {}, "map cell: this many pixels of the terrain's grid"},
      {"arrival_height",
       &H::arrival_height,
       "m",
       positive(),
       {},
       "arrival time: when the surface first stands this far above the still level"},
  };
  return f;
}

const std::vector<Field<CouplingConfig>>& coupling_fields() {
  using C = CouplingConfig;
  static const std::vector<Field<C>> f{
      {"body_layers", &C::body_layers, "", non_negative(), {}, "layers of body particles per sphere; 0: ceil(2h/dp)"},
      {"force_sum",
       &C::force_sum,
       "",
       {},
       {"exact", "per_sphere"},
       "distributed runs: exact (bitwise the same on any number of processes) or per_sphere (less traffic)"},
  };
  return f;
}

const std::vector<Field<DemConfig>>& dem_fields() {
  using D = DemConfig;
  static const std::vector<Field<D>> f{
      {"contact",
       &D::contact,
       "",
       {},
       {"linear_spring", "hertz_mindlin"},
       "contact law: linear_spring (the paper's, SPEC 3) or hertz_mindlin (Hertz normal, Mindlin no-slip tangential, "
       "Tsuji damping; no bonds)"},
      {"dt_factor",
       &D::dt_factor,
       "-",
       between(0, true, 0.5, false),
       {},
       "DEM step over the smallest contact time scale: sqrt(m / k_n) (linear spring) or the Rayleigh time "
       "(hertz_mindlin)"},
      {"bond_gap",
       &D::bond_gap,
       "m",
       non_negative(),
       {},
       "spheres of bonded materials closer than this are bonded at the start"},
      {"local_damping",
       &D::local_damping,
       "-",
       between(0, false, 1, true),
       {},
       "Cundall local damping (0 for dynamic runs, about 0.7 to settle a pack)"},
  };
  return f;
}

const std::vector<Field<DemMaterialSpec>>& material_fields() {
  using M = DemMaterialSpec;
  static const std::vector<Field<M>> f{
      {"density", &M::density, "kg/m^3", positive(), {}, "sphere density"},
      {"E", &M::young, "Pa", positive(), {}, "Young's modulus (contact stiffness, SPEC 3.1, or Hertz's)"},
      {"nu",
       &M::nu,
       "-",
       between(-1, true, INFINITY, false),
       {},
       "linear_spring: shear-to-normal stiffness ratio (> 0); hertz_mindlin: Poisson's ratio (< 0.5)"},
      {"phi", &M::phi_deg, "degrees", between(0, false, 90, true), {}, "friction angle"},
      {"restitution", &M::restitution, "-", between(0, true, 1, false), {}, "coefficient of restitution"},
  };
  return f;
}

const std::vector<Field<FluidRegion>>& fluid_fields() {
  static const std::vector<Field<FluidRegion>> f{
      {"velocity", &FluidRegion::velocity, "m/s", {}, {}, "its initial velocity"},
      {"fill",
       &FluidRegion::fill,
       "",
       {},
       {"exact", "lattice"},
       "a box: exact (round(L/dp) points per axis, the spacing stretched to fill it, and the particle mass from the "
       "water placed: the box holds its own volume) or lattice (whole spacings, centred: up to a spacing short per "
       "axis)"},
  };
  return f;
}

const std::vector<Field<WallSpec>>& wall_fields() {
  static const std::vector<Field<WallSpec>> f{
      {"solid", &WallSpec::solid, "", {}, {}, "box: fill the inside (an obstacle); mesh: no water behind the surface"},
  };
  return f;
}

const std::vector<Field<MotionSpec>>& motion_fields() {
  using M = MotionSpec;
  static const std::vector<Field<M>> f{
      {"start", &M::start, "s", non_negative(), {}, "the wall rests until this time"},
      {"velocity", &M::velocity, "m/s", {}, {}, "constant_velocity: the velocity; uniform_acceleration: at start"},
      {"acceleration", &M::acceleration, "m/s^2", {}, {}, "uniform_acceleration: the acceleration"},
      {"direction", &M::direction, "-", {}, {}, "ln_cosh, capped_acceleration, solitary: the line of motion"},
      {"s0", &M::s0, "m", non_negative(), {}, "ln_cosh: length scale (terminal speed s0 / t0)"},
      {"t0", &M::t0, "s", non_negative(), {}, "ln_cosh: time scale"},
      {"accel", &M::accel, "m/s^2", non_negative(), {}, "capped_acceleration: the acceleration"},
      {"terminal", &M::terminal, "m/s", non_negative(), {}, "capped_acceleration: the terminal speed"},
      {"period", &M::period, "s", non_negative(), {}, "sinusoidal: the period"},
      {"phase", &M::phase, "degrees", {}, {}, "sinusoidal: the phase at start"},
      {"amplitude", &M::amplitude, "m", {}, {}, "sinusoidal: translation amplitude (a piston)"},
      {"angle", &M::angle, "degrees", {}, {}, "sinusoidal: rotation amplitude about axis through pivot (a flap)"},
      {"axis", &M::axis, "-", {}, {}, "sinusoidal: the rotation axis"},
      {"height", &M::height, "m", non_negative(), {}, "solitary: the wave's height A above still water"},
      {"depth", &M::depth, "m", non_negative(), {}, "solitary: the still water depth h"},
  };
  return f;
}

const std::vector<Field<BodySpec>>& body_fields() {
  using B = BodySpec;
  static const std::vector<Field<B>> f{
      {"mass", &B::mass, "kg", non_negative(), {}, "the body's mass (or give density)"},
      {"density", &B::density, "kg/m^3", non_negative(), {}, "or its density: the mass from the solid's volume"},
      {"inertia",
       &B::inertia,
       "kg m^2",
       {},
       {},
       "principal moments about the centre of mass along x, y, z; [0, 0, 0]: from the shape, uniform density"},
      {"constraint",
       &B::constraint,
       "",
       {},
       {"none", "line"},
       "none: free in 6 degrees of freedom (a floating box); line: translates along direction only (a slider)"},
      {"direction", &B::direction, "-", {}, {}, "line: the rail's direction"},
      {"mu_static", &B::mu_static, "-", non_negative(), {}, "line: Coulomb static friction against the rail"},
      {"mu_kinetic", &B::mu_kinetic, "-", non_negative(), {}, "line: kinetic friction"},
      {"travel",
       &B::travel,
       "m",
       non_negative(),
       {},
       "line: > 0, the body stops for good this far along direction (the rail's end); 0: no end"},
      {"velocity", &B::velocity, "m/s", {}, {}, "at t = 0"},
      {"spin", &B::spin, "rad/s", {}, {}, "none: the angular velocity at t = 0 (a perturbation)"},
  };
  return f;
}

const std::vector<Field<GaugeSpec>>& gauge_fields() {
  using G = GaugeSpec;
  static const std::vector<Field<G>> f{
      {"surface",
       &G::surface,
       "",
       {},
       {"column", "highest"},
       "height gauge: the top of the water standing on the bed, or the highest wet point"},
      {"about", &G::about, "m", {}, {}, "dem_wall: moments about this point"},
  };
  return f;
}

const std::vector<Field<DemWallSpec>>& dem_wall_fields() {
  static const std::vector<Field<DemWallSpec>> f{
      {"name", &DemWallSpec::name, "", {}, {}, "name for dem_wall gauges"},
  };
  return f;
}

const std::vector<Field<DemPackSpec>>& pack_fields() {
  using P = DemPackSpec;
  static const std::vector<Field<P>> f{
      {"jitter", &P::jitter, "of the radius", between(0, false, 0.5, true), {}, "random offset of each sphere"},
      {"radius_min",
       &P::radius_min,
       "m",
       non_negative(),
       {},
       "> 0: radii drawn uniformly from [radius_min, radius] (fixed seed; the spacing stays 2 radius)"},
      {"random", &P::random_count, "", non_negative(), {}, "> 0: a random loose pack of this many spheres"},
      {"settle", &P::settle, "s", non_negative(), {}, "settle the pack under gravity for this long"},
      {"velocity", &P::velocity, "m/s", {}, {}, "initial velocity"},
      {"fixed", &P::fixed, "", {}, {}, "held in place (forces still computed)"},
  };
  return f;
}

namespace {

template <class S>
std::string type_of(const Field<S>& f) {
  if (std::holds_alternative<double S::*>(f.member)) return "number";
  if (std::holds_alternative<bool S::*>(f.member)) return "true/false";
  if (std::holds_alternative<std::string S::*>(f.member)) return f.choices.empty() ? "text" : "choice";
  if (std::holds_alternative<Vec3d S::*>(f.member)) return "[x, y, z]";
  return "integer";
}

template <class S>
std::string default_of(const Field<S>& f, const S& defaults) {
  if (const auto* m = std::get_if<double S::*>(&f.member)) return num(defaults.**m);
  if (const auto* m = std::get_if<int S::*>(&f.member)) return num(defaults.**m);
  if (const auto* m = std::get_if<long S::*>(&f.member)) return num(static_cast<double>(defaults.**m));
  if (const auto* m = std::get_if<bool S::*>(&f.member)) return defaults.**m ? "true" : "false";
  if (const auto* m = std::get_if<Vec3d S::*>(&f.member)) {
    const Vec3d v = defaults.**m;
    return "[" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + "]";
  }
  return defaults.*std::get<std::string S::*>(f.member);
}

template <class S>
std::string allowed_of(const Field<S>& f) {
  if (!f.choices.empty()) {
    std::string a;
    for (const auto& c : f.choices) a += (a.empty() ? "" : " | ") + c;
    return a;
  }
  return f.range.text();
}

template <class S>
void add(std::vector<KeyDoc>& out, const std::string& prefix, const std::vector<Field<S>>& fields) {
  static const S defaults = S(); // static: GCC 12 misreads a local one through member pointers as uninitialised
  for (const auto& f : fields)
    out.push_back({prefix + f.key, type_of(f), default_of(f, defaults), f.unit, allowed_of(f), f.help});
}

// The hazard section's keys (issue 22).
void hazard_keys(std::vector<KeyDoc>& k) {
  k.push_back({"hazard", "mapping", "", "", "",
               "hazard maps on the terrain's grid (max elevation, depth, speed, arrival), run-up; in maps/"});
  add(k, "hazard.", hazard_fields());
  k.push_back({"hazard.still_level", "number", "the reservoir's level", "m", "", "the water's level at rest"});
  k.push_back({"hazard.run_up", "list", "", "", "", "lines along which the highest wetted ground is reported"});
  k.push_back({"hazard.run_up[].name", "text", "required", "", "unique, no commas", "the line's name"});
  k.push_back({"hazard.run_up[].from", "[x, y]", "required", "m", "in the domain", "where the line starts"});
  k.push_back({"hazard.run_up[].to", "[x, y]", "required", "m", "in the domain", "where it ends"});
}

// A wall's prescribed motion (issue 34): the law by name from motion/motion_laws.cpp.
void motion_keys(std::vector<KeyDoc>& k) {
  k.push_back({"walls[].motion", "mapping", "", "", "",
               "a prescribed motion: the wall (its particles, with either wall model) moves by a law of time"});
  std::string laws, help;
  for (const auto& e : motion::motion_laws()) {
    laws += (laws.empty() ? "" : " | ") + std::string(e.name);
    help += (help.empty() ? "" : "; ") + std::string(e.name) + ": " + e.help + " (needs";
    for (const auto& r : e.required) help += " " + r;
    help += ")";
  }
  k.push_back({"walls[].motion.law", "choice", "required", "", laws, help});
  add(k, "walls[].motion.", motion_fields());
  k.push_back({"walls[].motion.pivot", "[x, y, z]", "the wall's centre", "m", "",
               "the point rotations turn about and body gauges report"});
  k.push_back({"walls[].motion.csv", "file", "", "", "t, dx, dy, dz [, rx, ry, rz]",
               "time_series: the table (relative to the case file; t increasing, at least two rows)"});
  k.push_back({"walls[].body", "mapping", "", "", "a solid box or a closed mesh",
               "a free rigid body: moves under gravity and the water's force and moment (not with motion)"});
  add(k, "walls[].body.", body_fields());
}

// dem.walls[]: planes, meshes and terrains the spheres meet, and how they move.
void dem_wall_keys(std::vector<KeyDoc>& k) {
  k.push_back({"dem.walls", "list", "", "", "", "walls the spheres meet: planes and meshes"});
  add(k, "dem.walls[].", dem_wall_fields());
  k.push_back({"dem.walls[].plane", "{point, normal}", "", "m", "normal not zero", "an infinite plane"});
  k.push_back({"dem.walls[].mesh", "file", "", "", "STL", "a triangle mesh"});
  k.push_back({"dem.walls[].terrain", "file", "", "", "a raster GDAL reads, projected (m)",
               "the ground from an elevation grid, cropped to the domain"});
  k.push_back({"dem.walls[].material", "text", "required", "", "a material's name", "its material"});
  k.push_back({"dem.walls[].motion", "mapping", "", "", "as walls[].motion",
               "a prescribed motion of the plane or mesh (the keys of walls[].motion); the spheres feel its velocity"});
  k.push_back({"dem.walls[].body", "mapping", "", "", "a closed mesh; as walls[].body",
               "a free rigid body moved by the spheres' contact forces and gravity (the keys of walls[].body)"});
  k.push_back({"dem.walls[].follows", "text", "", "", "a moving wall's name",
               "moves with that SPH wall (its law or free body): one solid seen by water and spheres; the "
               "spheres' forces on it join the water's"});
}

void damping_keys(std::vector<KeyDoc>& k) {
  k.push_back({"damping", "list", "", "", "",
               "absorbing zones (SPH): the water's velocity relaxes towards zero near a domain face, so that a long "
               "tank can be cut short without the wave reflecting (sph/damping.hpp)"});
  k.push_back({"damping[].face", "choice", "required", "",
               "xmin | xmax | ymin | ymax | zmin | zmax, not periodic or "
               "symmetry",
               "the face the zone ends at"});
  k.push_back({"damping[].length", "number", "required", "m", "> 0, shorter than the domain",
               "the zone's depth from the face"});
  k.push_back({"damping[].rate", "number", "10", "1/s", "> 0",
               "relaxation rate at the face; it rises from 0 at the zone's inner edge as the square of the depth "
               "into the zone (v <- v (1 - dt rate s^2))"});
}

// domain: the box and its periodic and symmetry faces.
void domain_keys(std::vector<KeyDoc>& k) {
  const std::string vec = "[x, y, z]";
  k.push_back({"domain", "mapping", "required", "", "", "the box water may occupy (grown by the wall layers)"});
  k.push_back({"domain.min", vec, "required", "m", "", "lowest corner"});
  k.push_back({"domain.max", vec, "required", "m", "> min", "highest corner"});
  k.push_back({"domain.periodic", "list of faces", "[]", "", "in pairs: xmin xmax | ymin ymax | zmin zmax",
               "faces that are one: water leaving through one enters at the other, and sees across it (SPH, DEM and "
               "the coupling; each period at least 4 h long, and for spheres over twice the DEM's search reach plus "
               "a diameter; walls and water end at the faces, box tanks leave them open; DEM planes lie along the "
               "periodic axes)"});
  k.push_back({"domain.symmetry", "list of faces", "[]", "", "xmin xmax ymin ymax zmin zmax, none periodic",
               "mirror planes: the water near one sees its mirror image, so half a symmetric tank gives the whole "
               "tank's answer (SPH, DEM and the coupling: a sphere meets the mirror images of its neighbours and of "
               "itself; walls and water end at the faces, box tanks leave them open; no sphere may cross a symmetry "
               "face, DEM planes lie along its axis, DEM meshes and periodic faces not yet with spheres)"});
}

std::vector<KeyDoc> build_keys() {
  std::vector<KeyDoc> k;
  const std::string vec = "[x, y, z]";
  k.push_back({"name", "text", "required", "", "no slashes", "the case's name (the default output folder out/NAME)"});
  k.push_back({"dp", "number", "required", "m", "> 0", "particle spacing of water and SPH walls (DEM-only: unused)"});
  k.push_back({"time", "mapping", "", "", "", "times of the run"});
  add(k, "time.", time_fields());
  k.push_back({"gravity", vec, "[0, 0, -9.81]", "m/s^2", "", "gravity"});
  domain_keys(k);
  k.push_back({"sph", "mapping", "", "", "", "the water's model"});
  add(k, "sph.", sph_fields());
  k.push_back({"fluid", "list", "", "", "", "boxes of water, each filled on the lattice (i + 1/2) dp, centred"});
  k.push_back({"fluid[].box", "{min, max}", "", "m", "inside the domain", "a box of water"});
  k.push_back({"fluid[].reservoir", "{level, seed}", "", "", "",
               "water below a level, clear of the walls, connected to the seed (a terrain's lake)"});
  k.push_back({"fluid[].reservoir.level", "number", "required", "m", "in the domain", "the still water surface"});
  k.push_back({"fluid[].reservoir.seed", "[x, y]", "required", "m", "on the water",
               "a point of the lake: water is placed where it connects to it"});
  k.push_back({"fluid[].particles", "file", "", "", "x, y, z, vx, vy, vz[, rho] per line",
               "water given particle by particle (a wave's initial state; relative to the case file)"});
  add(k, "fluid[].", fluid_fields());
  k.push_back({"walls", "list", "", "", "", "SPH walls: box tanks, solid boxes, triangle meshes"});
  k.push_back({"walls[].name", "text", "wallN", "", "unique", "name for force gauges"});
  k.push_back({"walls[].box", "{min, max}", "", "m", "", "a tank (layers outside it) or, with solid, an obstacle"});
  k.push_back({"walls[].open", "list of faces", "[]", "", "xmin xmax ymin ymax zmin zmax",
               "a box tank's faces left without wall"});
  add(k, "walls[].", wall_fields());
  k.push_back({"walls[].mesh", "file", "", "", "ASCII or binary STL",
               "a triangle mesh (relative to the case file); normals point to the water"});
  k.push_back({"walls[].terrain", "file", "", "", "a raster GDAL reads, projected (m)",
               "the ground: an elevation grid (GeoTIFF, ESRI ASCII, ...) cropped to the domain, solid below"});
  motion_keys(k);
  damping_keys(k);
  k.push_back({"gauges", "list", "", "", "", "quantities sampled every time.gauge_every into gauges.csv"});
  k.push_back({"gauges[].name", "text", "required", "", "unique, no commas", "the column's name"});
  k.push_back({"gauges[].type", "choice", "required", "", gauge_type_list(" | ", " | "), "what is measured"});
  k.push_back({"gauges[].x", "number", "required (height)", "m", "", "height gauge: the vertical line's x"});
  k.push_back({"gauges[].y", "number", "required (height)", "m", "", "height gauge: the vertical line's y"});
  k.push_back({"gauges[].at", vec, "required (pressure, velocity)", "m", "inside the domain", "the probe's point"});
  k.push_back({"gauges[].component", "choice", "by type", "", "x y z mag | x..mz | fx..mz",
               "velocity and force: x, y, z, mag; sphere and body: x, y, z, vx..vz, fx..fz, mx..mz (body: and tilt, "
               "degrees); dem_wall: fx..mz"});
  k.push_back({"gauges[].wall", "text", "required (force, dem_wall, body)", "", "a wall's name",
               "the wall measured (body: a moving wall, its pivot's position and velocity, the water's force and "
               "moment about the pivot)"});
  k.push_back({"gauges[].sphere", "integer", "required (sphere)", "", ">= 0",
               "the sphere (packs in order, spheres in pack order)"});
  add(k, "gauges[].", gauge_fields());
  k.push_back({"dem", "mapping", "", "", "", "the landslide as DEM spheres (SPEC 3)"});
  add(k, "dem.", dem_fields());
  k.push_back({"dem.materials", "list", "required", "", "at least one", "materials by name"});
  k.push_back({"dem.materials[].name", "text", "required", "", "unique", "the material's name"});
  add(k, "dem.materials[].", material_fields());
  k.push_back({"dem.materials[].rolling", "[k, cap]", "[0, 0]", "-", ">= 0",
               "rolling resistance: stiffness and cap factors (SPEC 3.3)"});
  k.push_back({"dem.materials[].twisting", "[k, cap]", "[0, 0]", "-", ">= 0", "twisting resistance factors"});
  k.push_back({"dem.materials[].bond", "{cn, cs}", "", "Pa", ">= 0",
               "bonded material: normal and shear bond strengths (SPEC 3.4)"});
  dem_wall_keys(k);
  k.push_back({"dem.packs", "list", "", "", "", "sphere packs"});
  k.push_back({"dem.packs[].box", "{min, max}", "", "m", "inside the domain", "a lattice (or random pack) in a box"});
  k.push_back({"dem.packs[].mesh", "file", "", "", "closed STL", "a pack inside a closed mesh"});
  k.push_back({"dem.packs[].csv", "file", "", "", "x, y, z, r per line", "spheres listed in a file"});
  k.push_back({"dem.packs[].between", "{top, bottom}", "", "", "", "a slide body between two elevation grids"});
  k.push_back({"dem.packs[].between.top", "file", "required", "", "a raster GDAL reads", "the pre-failure surface"});
  k.push_back({"dem.packs[].between.bottom", "file", "required", "", "below top", "the sliding surface"});
  k.push_back({"dem.packs[].radius", "number", "required (box, mesh, between)", "m", "> 0", "sphere radius"});
  k.push_back({"dem.packs[].material", "text", "required", "", "a material's name", "the spheres' material"});
  add(k, "dem.packs[].", pack_fields());
  hazard_keys(k);
  k.push_back({"coupling", "mapping", "", "", "", "SPH-DEM coupling (SPEC 4)"});
  add(k, "coupling.", coupling_fields());
  return k;
}

} // namespace

const std::vector<KeyDoc>& case_keys() {
  static const std::vector<KeyDoc> keys = build_keys();
  return keys;
}

std::vector<std::string> keys_under(const std::string& parent) {
  std::vector<std::string> out;
  const std::string prefix = parent.empty() ? "" : parent + ".";
  for (const auto& k : case_keys()) {
    if (k.path.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string rest = k.path.substr(prefix.size());
    if (rest.find('.') == std::string::npos && rest.find('[') == std::string::npos) out.push_back(rest);
  }
  return out;
}

std::string case_reference_markdown() {
  std::ostringstream s;
  s << "# Case file reference\n\n"
    << "Generated by `surge keys --markdown` from `src/surge/io/case_schema.cpp`; CI fails if this\n"
    << "file differs from what the program prints. `[]` stands for each item of a list\n"
    << "(`walls[].box` is the key `box` of an item of `walls`; with `--set`, `walls.0.box`).\n\n"
    << "| key | type | default | unit | allowed | meaning |\n|---|---|---|---|---|---|\n";
  auto cell = [](const std::string& v) {
    std::string o;
    for (char ch : v) o += ch == '|' ? std::string("\\|") : std::string(1, ch);
    return o;
  };
  for (const auto& k : case_keys())
    s << "| `" << k.path << "` | " << cell(k.type) << " | " << cell(k.def) << " | " << cell(k.unit) << " | "
      << cell(k.allowed) << " | " << cell(k.help) << " |\n";
  return s.str();
}

std::string keys_text(const std::string& prefix) {
  std::ostringstream s;
  for (const auto& k : case_keys()) {
    if (k.path.compare(0, prefix.size(), prefix) != 0) continue;
    s << k.path << "  (" << k.type;
    if (!k.def.empty()) s << (k.def.rfind("required", 0) == 0 ? ", " : ", default ") << k.def;
    if (!k.unit.empty() && k.unit != "-") s << ", " << k.unit;
    if (!k.allowed.empty()) s << ", " << k.allowed;
    s << ")\n    " << k.help << "\n";
  }
  return s.str();
}

} // namespace surge::io
