// DEM set-up shared by DEM-only and coupled runs: case -> materials, walls, spheres,
// and the solver; one sphere frame for output.
#pragma once
#include "surge/core/case.hpp"
#include "surge/coupling/sph_dem_coupling.hpp"
#include "surge/dem/dem_solver.hpp"
#include "surge/io/vtk_writer.hpp"

#include <filesystem>
#include <memory>
#include <vector>

namespace surge::sim {

struct DemSetup {
  std::vector<dem::Material> materials;
  std::vector<dem::Plane> planes;
  std::vector<dem::WallTriangle> triangles;
  std::vector<dem::Sphere> spheres; // local coordinates (absolute - origin)
  bool bonded = false;
  int contact_law = 0; // index into dem::ContactLaws
  Vec3d origin{};
  // Per case DEM wall: {plane index, -1} or {-1, mesh index}.
  std::vector<std::pair<int, int>> wall_index;
  // Slide bodies between grids (surge check): the pack, the body's volume, its spheres.
  struct SlideReport {
    int pack;
    double volume;
    std::size_t spheres;
    double radius; // the largest
    double solid;  // the spheres' volume [m^3]
  };
  std::vector<SlideReport> slides;
};

// Everything that can fail on input (meshes, sphere lists) fails here.
DemSetup dem_setup(const Case& c);
dem::DemSolver make_dem_solver(const Case& c, const DemSetup& s);
// surge check's warning when the DEM step is above the largest the contact law's
// guidance allows (dem.dt_factor above 0.2: SPEC 3's 0.1-0.2 for the linear spring, 20 %
// of the Rayleigh time for Hertz-Mindlin), with that step; empty when it is not.
std::string dem_step_warning(const Case& c, const dem::DemSolver& solver);
// surge check's lines on the slide bodies between grids: volume, spheres, the volume their
// lattice cells hold, mass.
void print_slides(const Case& c, const DemSetup& s);
// surge check's warning when bonded materials got no bond: no two of their spheres touch
// at the start (within dem.bond_gap); empty otherwise.
std::string no_bonds_warning(const Case& c, const DemSetup& s, long bonds);
// The spheres' current state, by id, for write_spheres_vtp.
io::SphereFrame sphere_frame(const dem::DemSolver& solver);
// The DEM's moving meshes in every frame (particles/dem_walls_NNNN.vtp, dem_walls.pvd):
// what a viewer shows of a free block or a gate the spheres meet. Off without them.
class DemWallFrames {
public:
  DemWallFrames(const std::filesystem::path& out, bool enabled) : series_(out.string(), "dem_walls"), on_(enabled) {}
  void write(const dem::DemSolver& solver, int frame, double t, const Vec3d& origin);
  void restored(const std::vector<double>& frame_times) {
    if (on_) series_.restored(frame_times);
  }

private:
  io::FrameSeries series_;
  bool on_;
};
// Value of a dem_wall gauge: force of the spheres on the named wall, or its moment.
double dem_wall_gauge_value(const GaugeSpec& g, const Case& c, const DemSetup& s, dem::DemSolver& solver);

class MovingBodies;
// The gauges the DEM side reads (core/gauge_types.hpp: not `water`): spheres, DEM walls and
// the DEM walls' own bodies, for both steppers. Built at each sample (the spheres and their
// fluid loads copied once for every gauge of the row); the loads are empty without water.
class DemGauges {
public:
  DemGauges(const Case& c, const DemSetup& s, dem::DemSolver& solver, const MovingBodies& bodies, bool water);
  [[nodiscard]] double value(const GaugeSpec& g, double t) const;

private:
  const Case* c_;
  const DemSetup* setup_;
  dem::DemSolver* solver_;
  const MovingBodies* bodies_;
  std::vector<dem::Sphere> spheres_;
  std::vector<Vec3> force_, moment_; // the fluid's, on each sphere
};
// Checks that every sphere gauge names an existing sphere.
void check_sphere_gauges(const Case& c, std::size_t n_spheres);
// Value of a sphere gauge: centre (absolute), velocity, fluid force or fluid moment
// (about the centre) component; force and moment read 0 without water.
double sphere_gauge_value(const GaugeSpec& g, const std::vector<dem::Sphere>& spheres,
                          const std::vector<Vec3>& fluid_force, const std::vector<Vec3>& fluid_moment,
                          const Vec3d& origin);

// The DEM half of a coupled run: spheres, their solver and the body particles that
// carry them into the water. Construction adds the body particles to `init` (and
// removes the water inside the spheres), so it comes before the SPH solver is built.
struct CoupledParts {
  DemSetup setup;
  std::unique_ptr<dem::DemSolver> dem;
  std::unique_ptr<coupling::SphDemCoupling> coupling;
  long bonds = 0;
  std::size_t fluid_removed = 0;
  int layers = 0;
  CoupledParts(const Case& c, sph::InitialState& init);
};

} // namespace surge::sim
