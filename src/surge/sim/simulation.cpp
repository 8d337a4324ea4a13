#include "surge/sim/simulation.hpp"

#include "surge/core/error.hpp"
#include "surge/coupling/sph_dem_coupling.hpp"
#include "surge/geometry/particle_generators.hpp"
#include "surge/geometry/raster.hpp"
#include "surge/geometry/terrain.hpp"
#include "surge/io/atomic_file.hpp"
#include "surge/io/case_reader.hpp"
#include "surge/io/checkpoint.hpp"
#include "surge/io/vtk_writer.hpp"
#include "surge/sim/dem_setup.hpp"
#include "surge/sim/distributed_run.hpp"
#include "surge/sim/moving_bodies.hpp"
#include "surge/sim/run_loop.hpp"
#include "surge/sim/run_summary.hpp"
#include "surge/sim/run_support.hpp"
#include "surge/sim/wall_leaks.hpp"
#include "surge/sph/gauges.hpp"
#include "surge/sph/hazard_maps.hpp"
#include "surge/sph/wcsph_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <sys/resource.h>

namespace surge::sim {
namespace {

using Clock = std::chrono::steady_clock;

// Throughput assumed by `surge check` for its run-time estimate: all-particle steps
// per second on 2 CPU threads, docs/benchmarks.md (2.3-2.6e6 measured), rounded down.
constexpr double assumed_particle_steps_per_s = 2.0e6;
// Peak memory per particle (solver buffers 118 B + host copies for output), docs/benchmarks.md.
constexpr double bytes_per_particle_estimate = 150.0;

// A run's removals, and the fluid found inside walls at outputs.
struct Totals {
  Removals removed;
  LeakRecord leaks;
};

// Share of spheres touching another one (gap below a tenth of the smaller radius);
// brute force, on at most 20,000 spheres (beyond that the assembly counts as dense).
double touching_share(const std::vector<dem::Sphere>& sp) {
  if (sp.size() > 20000) return 1.0;
  std::size_t touching = 0;
  for (std::size_t i = 0; i < sp.size(); ++i)
    for (std::size_t j = 0; j < sp.size(); ++j) {
      if (i == j) continue;
      const Real gap = norm(sp[i].pos - sp[j].pos) - sp[i].radius - sp[j].radius;
      if (gap < Real(0.1) * std::min(sp[i].radius, sp[j].radius)) {
        ++touching;
        break;
      }
    }
  return sp.empty() ? 0.0 : static_cast<double>(touching) / static_cast<double>(sp.size());
}

std::string fmt(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3g", v);
  return b;
}

double first_dt(const Case& c) {
  const double h = c.h();
  const double c0 = c.sound_speed();
  return c.sph.cfl * std::min(std::sqrt(h / c.g()), h / c0);
}

// A Courant number above 1: the explicit step is unstable (surge check and run say so).
std::string cfl_warning(const Case& c) {
  if (c.sph.cfl <= 1) return "";
  return "sph.cfl = " + fmt(c.sph.cfl) + " is above 1: the explicit time step is unstable there (0.2 is the default)";
}

// surge check's warnings (resolution, kernel, Mach number, the paper's guidance for
// spheres); returns how many were printed.
int check_warnings(const Case& c, const sph::InitialState& init, const CoupledParts* cp, double water_share) {
  int warnings = 0;
  auto warn = [&](const std::string& w) {
    std::printf("warning     %s\n", w.c_str());
    ++warnings;
  };
  if (water_share < 0.98 && init.fluid_dropped_by_walls == 0)
    warn("the fluid boxes hold " + fmt(100 * water_share) +
         " % of their volume in water: their sizes are not whole numbers of dp (choose dp dividing them, or fill: "
         "exact)");
  if (c.sph.h_over_dp < 1.2)
    warn("h = " + std::to_string(c.sph.h_over_dp) + " dp: the paper's run with h = 1.0 dp diverged; use 1.2 to 2.0");
  if (c.sph.h_over_dp > 2.0) warn("h > 2 dp widens the gap between water and walls (paper, sect. 3.1)");
  if (!c.fluid.empty() && c.dp > c.water_depth() / 25)
    warn("dp is coarser than 1/25 of the water depth (" + fmt(c.water_depth()) +
         " m): the paper's guidance is dp <= depth/25");
  if (cp) {
    // Paper sect. 4: loose spheres need dp <= D/20, dense assemblies dp <= D/6 (D/8 better).
    const auto& sp = cp->setup.spheres;
    double dmin = 1e300;
    for (const auto& x : sp) dmin = std::min(dmin, 2.0 * x.radius);
    const bool dense = touching_share(sp) >= 0.5;
    // Radii are stored as Real (float by default): D = 0.06 comes back as 0.0599999987, so
    // dp = D/20 exactly must pass; a relative margin of 1e-5 covers float rounding.
    const double ratio = c.dp / dmin, slack = 1 + 1e-5;
    // The dynamic boundary's gap makes each sphere act larger: the slide tsunami at D/4
    // raised M1's crest by a quarter against mDBC (docs/validation.md).
    const std::string gap = c.sph.boundary == "dynamic"
                                ? "; with the dynamic boundary the gap at the spheres raises the slide's wave (at D/4: "
                                  "+24 % near the source against mdbc)"
                                : "";
    if (dense && ratio > slack / 6)
      warn("dp = D/" + fmt(1 / ratio) +
           " for a dense assembly of spheres: the paper's guidance is dp <= D/6 (D/8 better)" + gap);
    else if (!dense && ratio > slack / 20)
      warn("dp = D/" + fmt(1 / ratio) +
           " for loose spheres (not touching): the paper's guidance is dp <= D/20; coarser runs overestimate buoyancy "
           "and drag (gap effect)");
  }
  // delta_plus shifts at Ma c0 whether the water moves or not, and lacks the free surface's
  // normal that Sun et al. project its shift on (docs/validation.md, still water).
  if (c.sph.shifting == "delta_plus" && !c.fluid.empty() && c.g() > 0)
    warn("shifting: delta_plus under gravity: at a free surface it lifts the water (still water 0.2 m deep rose 13.7 "
         "mm in 2 s); use fickian for water with a free surface");
  if (c.sph.eta < 10) warn("eta < 10: the Mach number may exceed 0.1 and the water compress noticeably");
  if (const std::string w = cfl_warning(c); !w.empty()) warn(w);
  return warnings;
}

// Terrain steeper than the wall lattice follows well: slopes above 60 degrees (the layers
// become steps a spacing high) and pixels much finer than dp (detail the particles cannot
// hold), with where they are.
void print_terrain_warnings(const Case& c, const WallSpec& w) {
  const auto g = geometry::read_terrain(w.mesh_path, c.domain);
  long steep = 0;
  double xlo = 1e300, xhi = -1e300, ylo = 1e300, yhi = -1e300;
  for (long j = 0; j + 1 < g.ny; ++j)
    for (long i = 0; i + 1 < g.nx; ++i) {
      const double sx = (g.at(i + 1, j) - g.at(i, j)) / g.dx, sy = (g.at(i, j + 1) - g.at(i, j)) / g.dy;
      if (std::hypot(sx, sy) <= std::tan(60.0 * M_PI / 180)) continue;
      ++steep;
      xlo = std::min(xlo, g.x(i));
      xhi = std::max(xhi, g.x(i + 1));
      ylo = std::min(ylo, g.y(j));
      yhi = std::max(yhi, g.y(j + 1));
    }
  if (steep > 0)
    std::printf("warning     terrain '%s': %ld pixels steeper than 60 degrees within x [%.3f, %.3f], y [%.3f, %.3f]: "
                "its wall layers step there by a spacing or more (cliffs hold water, but the flow along them is coarse)"
                "\n",
                w.name.c_str(), steep, xlo, xhi, ylo, yhi);
  if (std::min(g.dx, g.dy) < 0.5 * c.dp)
    std::printf("warning     terrain '%s': pixels of %g m, finer than dp/2 = %g m: features narrower than a few dp "
                "(gullies, ridges) are smoothed away by the particles\n",
                w.name.c_str(), std::min(g.dx, g.dy), 0.5 * c.dp);
}

// surge check's lines on where water is removed, and on the faces that bring it back.
void print_removal(const Case& c, const sph::InitialState& init) {
  const Vec3d a = Vec3d(init.fluid_lo) + init.origin, b = Vec3d(init.fluid_hi) + init.origin;
  std::printf("removal     fluid leaving x [%.3f, %.3f], y [%.3f, %.3f], z [%.3f, %.3f] m is removed (the domain, "
              "grown to hold the wall layers); fluid inside a wall is counted at every output (summary.json: "
              "in_walls)\n",
              a.x, b.x, a.y, b.y, a.z, b.z);
  std::string faces;
  for (int f = 0; f < 6; ++f)
    if (c.image_face(f)) faces += std::string(faces.empty() ? "" : ", ") + face_name(static_cast<Face>(f));
  if (!faces.empty())
    std::printf("images      periodic and symmetry faces %s: water crossing one is brought back (wrapped or "
                "mirrored), not removed\n",
                faces.c_str());
}
} // namespace

int check(const Case& c) {
  if (c.dem.active() && !c.coupled()) return check_dem(c);
  auto init = sph::build_initial_state(c);
  const MovingBodies bodies(c, &init); // refuses a motion that leaves the domain
  std::optional<CoupledParts> cp;
  if (c.coupled()) cp.emplace(c, init);
  const double n_body = cp ? static_cast<double>(cp->coupling->n_body()) : 0.0;
  const double n = static_cast<double>(init.n_fluid + init.n_wall) + n_body;
  const double dt0 = first_dt(c);
  const double steps = c.time.end / dt0;
  std::printf("case        %s (%s)\n", c.name.c_str(), c.source.c_str());
  std::printf("particles   %zu fluid, %zu wall (%d wall layers), %zu fluid particles dropped inside walls\n",
              init.n_fluid, init.n_wall, geometry::wall_layers(c), init.fluid_dropped_by_walls);
  double water_share = 1;
  if (!c.fluid.empty()) {
    // Counted before the water inside spheres is taken out.
    const double placed = init.fluid_volume_placed;
    water_share = placed / init.fluid_volume_asked;
    if (std::all_of(c.fluid.begin(), c.fluid.end(), [](const FluidRegion& f) { return f.reservoir; }))
      std::printf("water       %.6g m^3 placed (reservoirs filled to their levels)\n", placed);
    else
      std::printf("water       %.6g m^3 placed of %.6g m^3 in the fluid boxes and reservoirs (%.1f %%)\n", placed,
                  init.fluid_volume_asked, 100.0 * placed / init.fluid_volume_asked);
    if (init.reservoir_columns > 0)
      std::printf("reservoir   free surface %.6g m^2 (%ld lattice columns of dp^2), the water counted above\n",
                  static_cast<double>(init.reservoir_columns) * c.dp * c.dp, init.reservoir_columns);
    const double narrow =
        static_cast<double>(init.reservoir_near_shore) / static_cast<double>(std::max(init.reservoir_columns, 1L));
    if (narrow > 0.5)
      std::printf("warning     the lake is narrow for dp = %g m: %.0f %% of its surface lies within 2 dp of a shore "
                  "(as in a channel under 8 dp wide); a smaller dp resolves the flow across it\n",
                  c.dp, 100 * narrow);
  }
  print_moving_walls(c, bodies);
  if (cp) {
    std::printf("spheres     %zu, %ld bonds, %zu body particles (%d layers), %zu fluid particles removed inside "
                "spheres\n",
                cp->setup.spheres.size(), cp->bonds, cp->coupling->n_body(), cp->layers, cp->fluid_removed);
    if (const std::string w = no_bonds_warning(c, cp->setup, cp->bonds); !w.empty())
      std::printf("warning     %s\n", w.c_str());
    std::printf("DEM step    %.3g s (dt_factor %g): about %.0f DEM sub-steps per SPH step at the first dt\n",
                static_cast<double>(cp->coupling->dt_dem()), c.dem.dt_factor,
                std::ceil(dt0 / static_cast<double>(cp->coupling->dt_dem())));
    if (const std::string w = dem_step_warning(c, *cp->dem); !w.empty()) std::printf("warning     %s\n", w.c_str());
    print_slides(c, cp->setup);
    double slide_volume = 0;
    for (const auto& sl : cp->setup.slides) slide_volume += sl.volume;
    const double per_particle = init.particle_mass > 0 ? init.particle_mass / c.sph.rho0 : c.dp * c.dp * c.dp;
    const double displaced = static_cast<double>(cp->fluid_removed) * per_particle;
    if (slide_volume > 0 && displaced > slide_volume)
      std::printf("warning     the slide bodies overlap %.6g m^3 of water, more than their own %.6g m^3: is the "
                  "sliding surface under the lake, or the level too high?\n",
                  displaced, slide_volume);
  }
  for (const auto& w : c.walls)
    if (w.terrain) print_terrain_warnings(c, w);
  if (c.hazard.enabled && c.hazard.arrival_height < c.dp / 8)
    std::printf("warning     hazard.arrival_height = %g m is below dp/8 = %g m: the surface read at rest scatters "
                "by up to dp/8, so cells would record arrivals before any wave\n",
                c.hazard.arrival_height, c.dp / 8);
  std::printf("memory      about %.1f MiB (%.0f bytes per particle)\n", n * bytes_per_particle_estimate / 1048576.0,
              bytes_per_particle_estimate);
  std::printf("resolution  dp = %g m, h = %g m, water depth %g m, c0 = %g m/s\n", c.dp, c.h(), c.water_depth(),
              c.sound_speed());
  print_removal(c, init);
  std::printf("time step   first dt = %.3g s, about %.3g steps to t = %g s\n", dt0, steps, c.time.end);
  std::printf("run time    about %s on 2 CPU threads (assuming %.1e particle-steps/s; the step shrinks when the flow "
              "accelerates)\n",
              hms(steps * n / assumed_particle_steps_per_s).c_str(), assumed_particle_steps_per_s);
  if (check_warnings(c, init, cp ? &*cp : nullptr, water_share) == 0) std::printf("warnings    none\n");
  return 0;
}

namespace {

// What a run that came apart numerically may try (the failures that are not a setup's).
constexpr const char* kUnstable = "; try a smaller sph.cfl or dem.dt_factor, or a finer dp";

// Water, and with DEM packs the spheres coupled to it, on one process or as one slab of a
// distributed run.
class SphStepper final : public Stepper {
public:
  // `ck`: the checkpoint of a restart (its particles are moved out). Everything that can
  // fail on input happens before the output folder is touched.
  SphStepper(const Case& c, const RunOptions& opt, io::Checkpoint* ck)
      : c_(c), opt_(opt), init_(sph::build_initial_state(c)), bodies_(c, &init_), cp_(coupled_parts(c, init_)),
        solver_(sph::solver_config(c), init_, DistributedRun::enabled() ? &none_ : nullptr), gauges_(c, init_),
        hazard_(c, init_), dist_(c, solver_, cp_ ? cp_->coupling.get() : nullptr), out_(opt.out_dir), leaks_(c),
        walls_(opt.out_dir, "walls"), fluid_(opt.out_dir, "fluid"),
        dt_min_(c.time.dt_min > 0 ? c.time.dt_min : 1e-3 * first_dt(c)),
        max_removed_(c.sph.max_removed_share * static_cast<double>(init_.n_fluid)) {
    if (cp_) {
      spheres_.emplace(opt.out_dir, "spheres");
      dem_walls_.emplace(out_, bodies_.moves_dem());
    }
    if (ck) check_restart(*ck);
    if (root()) prepare_output(c, opt.out_dir);
    if (ck) {
      tot_.removed.domain = ck->removed_domain;
      tot_.removed.density = ck->removed_density;
      tot_.removed.non_finite = ck->non_finite;
      dist_.start(std::move(ck->particles), ck->steps); // a checkpoint of any number of processes
      // The moving walls placed at the checkpoint's time, as the straight run placed them
      // (their positions the checkpoint's, bit for bit; ghost offsets and faces turned).
      bodies_.place(solver_, ck->time);
      if (cp_) bodies_.attach(*cp_->dem, ck->time);
      // The body particles' mDBC ghost nodes turn with the restored spheres (the positions
      // placed again are the checkpoint's, bit for bit).
      if (cp_) cp_->coupling->place_bodies(solver_, *cp_->dem);
      ck->particles = {};
    } else {
      if (root()) {
        io::write_particles_vtp(walls_.path(0), init_.particles, init_.origin, {Kind::Wall});
        walls_.add(0, 0.0);
      }
      dist_.start(init_.particles);
      bodies_.place(solver_, 0.0); // their velocities at t = 0
      if (cp_) {
        bodies_.attach(*cp_->dem, 0.0);
        cp_->coupling->reduce_forces(solver_, *cp_->dem); // the fluid force at t = 0, for the gauges
      }
    }
    // The initial particles' host copy (37 B per particle or more) is not read again.
    init_.particles = {};
  }

  double step(double dt_max, double t, bool& stop, bool& checkpoint_due, std::string& failure) override {
    dist_.sync();
    sph::StepStats s = solver_.step(dt_max);
    dist_.stepped();
    // Free bodies under the water's force of the step's rates (those the spheres touch hold
    // it over the DEM's sub-steps, advancing with the spheres).
    bodies_.advance(solver_, s.dt);
    if (cp_) {
      const double t0 = t;
      cp_->coupling->after_fluid_step(solver_, *cp_->dem, s.dt,
                                      [&](int k, double h) { bodies_.advance(*cp_->dem, h, t0 + (k + 1) * h); });
    }
    t += s.dt;
    bodies_.place(solver_, t); // the run loop's new time, the same double
    if (cp_) bodies_.place(*cp_->dem, t);
    dist_.combine(s, stop, checkpoint_due);
    for (Removals* x : {&tot_.removed, &since_output_}) {
      x->domain += s.removed_domain;
      x->density += s.removed_density;
      x->non_finite += s.non_finite;
      if (s.removed_domain + s.removed_density > 0) {
        for (int k = 0; k < 3; ++k) {
          x->lo[k] = std::min(x->lo[k], init_.origin[k] + static_cast<double>(s.removed_lo[k]));
          x->hi[k] = std::max(x->hi[k], init_.origin[k] + static_cast<double>(s.removed_hi[k]));
        }
      }
    }
    std::ostringstream m;
    m << "diverged at t = " << t << " s (step " << solver_.step_count() << "): ";
    if (cp_ && !cp_->dem->finite()) {
      m << "a DEM sphere has a non-finite position (try a smaller dem.dt_factor or sph.cfl)";
      failure = m.str();
    } else if (s.non_finite > 0) {
      m << s.non_finite << " particles have non-finite position, velocity or density" << kUnstable;
      failure = m.str();
    } else if (static_cast<double>(tot_.removed.total()) > max_removed_ && init_.n_fluid > 0) {
      const Removals& r = tot_.removed;
      m << r.total() << " of " << init_.n_fluid
        << " fluid particles removed (limit sph.max_removed_share = " << c_.sph.max_removed_share << "; " << r.domain
        << " left the domain, " << r.density << " density out of range)" << kUnstable;
      failure = m.str();
    } else if (s.dt < dt_min_ && s.dt < dt_max * (1 - 1e-9)) {
      m << "the time step fell to " << s.dt << " s, below time.dt_min = " << dt_min_ << " s" << kUnstable;
      failure = m.str();
    } else if (const std::string e = bodies_.escaped(); !e.empty()) {
      failure = m.str() + e;
    }
    return s.dt;
  }

  [[nodiscard]] long steps() const override { return solver_.step_count(); }
  [[nodiscard]] std::vector<std::string> gauge_names() const override { return gauges_.names(); }

  std::vector<double> sample(double t) override {
    dist_.sync();
    hazard_.sample(t, solver_, dist_.distribution());
    if (bodies_.any()) gauges_.set_bodies(bodies_.states(t));
    std::optional<DemGauges> dem;
    if (cp_) dem.emplace(c_, cp_->setup, *cp_->dem, bodies_, true);
    return gauges_.sample(
        solver_, [&](const GaugeSpec& g) { return dem ? dem->value(g, t) : 0.0; }, dist_.distribution());
  }

  bool write_frame(int frame, double t, std::string& failure) override {
    (void)failure; // a non-finite state has stopped the run before
    dist_.sync();
    solver_.mark_surface(); // refreshes
    dist_.gather(host_, false);
    const bool quiet = opt_.quiet || !root();
    if (root()) {
      io::write_particles_vtp(fluid_.path(frame), host_, init_.origin, {Kind::Fluid});
      fluid_.add(frame, t);
      if (cp_) {
        io::write_spheres_vtp(spheres_->path(frame), sphere_frame(*cp_->dem), init_.origin);
        spheres_->add(frame, t);
        dem_walls_->write(*cp_->dem, frame, t, init_.origin);
      }
      if (bodies_.sph_count() > 0) write_walls(frame, t);
      if (hazard_.enabled()) write_hazard();
      for (std::size_t k = 0; k < bodies_.sph_count(); ++k)
        leaks_.set_pose(bodies_.wall(k).wall, bodies_.wall(k).pivot, bodies_.pose(k, t));
      const LeakCount in_walls = leaks_.count(host_, init_.origin);
      tot_.leaks.add(in_walls, t);
      if (in_walls.count > 0 && !quiet)
        std::fprintf(stderr,
                     "%st = %.4f s: %ld fluid particles inside walls (first: %s) within x [%.3f, %.3f], y [%.3f, "
                     "%.3f], z [%.3f, %.3f] m\n",
                     opt_.progress_tty ? "\n" : "", t, in_walls.count, in_walls.wall.c_str(), in_walls.lo.x,
                     in_walls.hi.x, in_walls.lo.y, in_walls.hi.y, in_walls.lo.z, in_walls.hi.z);
    }
    const Removals& so = since_output_;
    if (so.total() > 0 && !quiet)
      std::fprintf(stderr,
                   "%st = %.4f s: removed %ld fluid particles since the last output (%ld left the domain, %ld density "
                   "out of range, %ld non-finite) within x [%.3f, %.3f], y [%.3f, %.3f], z [%.3f, %.3f] m\n",
                   opt_.progress_tty ? "\n" : "", t, so.total(), so.domain, so.density, so.non_finite, so.lo.x, so.hi.x,
                   so.lo.y, so.hi.y, so.lo.z, so.hi.z);
    since_output_ = {};
    return true;
  }

  void save(io::Checkpoint& k) override {
    k.removed_domain = tot_.removed.domain;
    k.removed_density = tot_.removed.density;
    k.non_finite = tot_.removed.non_finite;
    dist_.gather(k.particles, true);
    if (cp_) k.dem_state = cp_->dem->save();
    k.body_state = bodies_.save();
    if (hazard_.enabled()) k.hazard_state = hazard_.save();
  }

  void restored(const std::vector<double>& frame_times) override {
    fluid_.restored(frame_times);
    // The walls of every frame when they move; else the one file of the start.
    walls_.restored(bodies_.sph_count() > 0 ? frame_times : std::vector<double>{0.0});
    if (cp_) {
      spheres_->restored(frame_times);
      dem_walls_->restored(frame_times);
    }
  }

  RunCounts counts() override {
    // Collective: every process takes part (RSS summed over processes).
    RunCounts n;
    n.fluid = init_.n_fluid;
    n.wall = init_.n_wall;
    if (cp_) {
      n.body = cp_->coupling->n_body();
      n.spheres = cp_->setup.spheres.size();
      n.dem = true;
      n.dem_dt = static_cast<double>(cp_->coupling->dt_dem());
      n.bonds = cp_->bonds;
      n.broken_bonds = cp_->dem->broken_bonds();
    }
    n.stepped = n.fluid + n.wall + n.body;
    n.fluid_now = dist_.owned_particles();
    n.removed = tot_.removed;
    n.in_walls = tot_.leaks.json();
    dist_.measure_waits();
    n.distributed = dist_.summary_json();
    n.peak_rss = dist_.active() ? DistributedRun::total(peak_rss_bytes()) : peak_rss_bytes();
    return n;
  }

  void report_end(const std::string& status, const LoopClock& k) override {
    const double n = static_cast<double>(init_.n_fluid + init_.n_wall);
    // Throughput over this invocation's own steps (after a restart, not the whole run's).
    std::fprintf(stderr,
                 "%s: %ld steps to t = %.4g s in %.1f s wall, %.3g particle-steps/s (%zu fluid + %zu wall), %ld fluid "
                 "particles removed\n  output in %s\n",
                 status.c_str(), k.steps, k.t, k.wall, n * static_cast<double>(k.loop_steps) / k.loop_wall,
                 init_.n_fluid, init_.n_wall, tot_.removed.total(), out_.string().c_str());
  }

  [[nodiscard]] bool root() const override { return DistributedRun::root(); }

private:
  static std::optional<CoupledParts> coupled_parts(const Case& c, sph::InitialState& init) {
    std::optional<CoupledParts> cp;
    if (c.coupled()) cp.emplace(c, init);
    return cp;
  }

  // With moving walls every frame has its walls (walls_NNNN.vtp; frame 0 is written at the
  // start, before any output, from the initial state).
  void write_walls(int frame, double t) {
    if (frame == 0) return;
    io::write_particles_vtp(walls_.path(frame), host_, init_.origin, {Kind::Wall});
    walls_.add(frame, t);
  }

  // maps/: the hazard maps as GeoTIFFs in the terrain's coordinate system, all of them and
  // the ground in one VTK image, and the run-up per line.
  void write_hazard() {
    const auto dir = out_ / "maps";
    std::filesystem::create_directories(dir);
    const auto maps = hazard_.maps();
    const auto names = sph::HazardMaps::map_names();
    const auto& lat = hazard_.lattice();
    for (std::size_t k = 0; k < maps.size(); ++k)
      geometry::write_geotiff((dir / (names[k] + ".tif")).string(), lat, {maps[k]}, {names[k]});
    auto all = maps;
    auto all_names = names;
    all.push_back(lat.v);
    all_names.emplace_back("ground");
    io::write_image_vti((dir / "hazard.vti").string(), lat.nx, lat.ny, lat.x0, lat.y0, lat.dx, lat.dy, all_names, all);
    io::write_file_atomic((dir / "runup.csv").string(), hazard_.run_up_csv());
  }

  void check_restart(const io::Checkpoint& ck) {
    const std::string path = (out_ / "checkpoint.bin").string();
    if (ck.hazard_state.empty() == hazard_.enabled())
      throw InputError(path, 0, "hazard",
                       std::string(hazard_.enabled() ? "the case has hazard maps but the checkpoint holds none"
                                                     : "the checkpoint holds hazard maps but the case has none") +
                           "; restart with the case.yaml of that run");
    if (hazard_.enabled()) hazard_.restore(ck.hazard_state, path);
    bodies_.restore(ck.body_state, path);
    check_restart_gauges(ck, gauges_.names().size(), path);
    if (ck.dem_state.empty() != !cp_)
      throw InputError(path, 0, "dem",
                       cp_ ? "the checkpoint holds no DEM spheres but the case has them; restart with the case.yaml "
                             "of that run"
                           : "the checkpoint holds DEM spheres but the case has none; restart with the case.yaml of "
                             "that run");
    if (!cp_) return;
    try {
      cp_->dem->restore(ck.dem_state);
    } catch (const std::invalid_argument& e) {
      throw InputError(path, 0, "dem", std::string(e.what()) + "; restart with the case.yaml of that run");
    }
  }

  const Case& c_;
  const RunOptions& opt_;
  sph::InitialState init_;
  MovingBodies bodies_; // walls with a motion
  std::optional<CoupledParts> cp_;
  const particles::HostParticles none_; // a distributed run's solver starts empty: each process uploads its slab
  sph::WcsphSolver solver_;
  sph::Gauges gauges_;
  sph::HazardMaps hazard_;
  DistributedRun dist_; // built with MPI: slabs of particles, one per process
  std::filesystem::path out_;
  WallLeaks leaks_;
  io::FrameSeries walls_, fluid_;
  std::optional<io::FrameSeries> spheres_;
  std::optional<DemWallFrames> dem_walls_; // the DEM's moving meshes of every frame
  particles::HostParticles host_;
  Totals tot_;
  Removals since_output_;
  double dt_min_, max_removed_;
};

} // namespace

int run(const Case& c, const RunOptions& opt) {
  if (c.dem.active() && !c.coupled()) return run_dem(c, opt);
  const auto wall0 = Clock::now();
  if (const std::string w = cfl_warning(c); !w.empty() && !opt.quiet && DistributedRun::root())
    std::fprintf(stderr, "warning: %s\n", w.c_str());
  std::optional<io::Checkpoint> ck;
  if (opt.restart) ck = io::read_checkpoint((std::filesystem::path(opt.out_dir) / "checkpoint.bin").string());
  SphStepper s(c, opt, ck ? &*ck : nullptr);
  return run_loop(c, opt, s, ck ? &*ck : nullptr, wall0);
}

} // namespace surge::sim
