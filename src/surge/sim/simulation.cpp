#include "surge/sim/simulation.hpp"

#include "surge/core/error.hpp"
#include "surge/core/version.hpp"
#include "surge/coupling/sph_dem_coupling.hpp"
#include "surge/geometry/particle_generators.hpp"
#include "surge/io/atomic_file.hpp"
#include "surge/io/case_reader.hpp"
#include "surge/io/checkpoint.hpp"
#include "surge/io/vtk_writer.hpp"
#include "surge/sim/dem_setup.hpp"
#include "surge/sim/distributed_run.hpp"
#include "surge/sim/run_support.hpp"
#include "surge/sim/wall_leaks.hpp"
#include "surge/sph/gauges.hpp"
#include "surge/sph/wcsph_solver.hpp"

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

struct Totals {
  long removed_domain = 0, removed_density = 0, non_finite = 0;
  Vec3d lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300}; // where (absolute)
  LeakRecord leaks;                                          // fluid found inside walls at outputs
  [[nodiscard]] long removed() const { return removed_domain + removed_density + non_finite; }
};

// Particle counts of a run beyond the fluid and wall ones of InitialState.
struct ExtraCounts {
  std::size_t body = 0, spheres = 0;
};

std::string summary_json(const Case& c, const sph::InitialState& init, const ExtraCounts& extra,
                         const std::string& status, int code, long steps, double t, double wall, long loop_steps,
                         double loop_wall, const Totals& tot, long n_now, double rss, const std::string& distributed,
                         const std::string& message) {
  std::ostringstream j;
  j.precision(10);
  const double n_all = static_cast<double>(init.n_fluid + init.n_wall + extra.body);
  const std::string msg = json_escape(message);
  j << "{\n  \"name\": \"" << c.name << "\",\n  \"surge_version\": \"" << version_string << "\",\n"
    << "  \"backend\": \"" << par::backend_name() << "\",\n  \"threads\": " << par::threads() << ",\n"
    << "  \"distributed\": " << distributed << ",\n"
    << "  \"status\": \"" << status << "\",\n  \"exit_code\": " << code << ",\n  \"message\": \"" << msg << "\",\n"
    << "  \"particles\": {\"fluid\": " << init.n_fluid << ", \"wall\": " << init.n_wall << ", \"body\": " << extra.body
    << ", \"sphere\": " << extra.spheres << ", \"now\": " << n_now << "},\n"
    << "  \"steps\": " << steps << ",\n  \"simulated_time\": " << t << ",\n  \"wall_seconds\": " << wall << ",\n"
    << "  \"loop_steps\": " << loop_steps << ",\n  \"loop_seconds\": " << loop_wall << ",\n"
    << "  \"particle_steps_per_second\": "
    << (loop_wall > 0 ? n_all * static_cast<double>(loop_steps) / loop_wall : 0.0) << ",\n"
    << "  \"fluid_particle_steps_per_second\": "
    << (loop_wall > 0 ? static_cast<double>(init.n_fluid) * static_cast<double>(loop_steps) / loop_wall : 0.0) << ",\n"
    << "  \"removed\": {\"total\": " << tot.removed() << ", \"left_domain\": " << tot.removed_domain
    << ", \"density_out_of_range\": " << tot.removed_density << ", \"non_finite\": " << tot.non_finite;
  if (tot.removed_domain + tot.removed_density > 0)
    j << ", \"where\": {\"min\": [" << tot.lo.x << ", " << tot.lo.y << ", " << tot.lo.z << "], \"max\": [" << tot.hi.x
      << ", " << tot.hi.y << ", " << tot.hi.z << "]}";
  j << "},\n"
    << "  \"in_walls\": " << tot.leaks.json() << ",\n"
    << "  \"peak_rss_bytes\": " << rss << ",\n  \"bytes_per_particle\": " << (n_all > 0 ? rss / n_all : 0.0) << "\n}\n";
  return j.str();
}

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

} // namespace

int check(const Case& c) {
  if (c.dem.active() && !c.coupled()) return check_dem(c);
  auto init = sph::build_initial_state(c);
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
    // Each fluid box holds a whole number of spacings per axis, centred in the box.
    // Counted before the water inside spheres is taken out.
    const double placed = static_cast<double>(init.n_fluid + (cp ? cp->fluid_removed : 0)) * c.dp * c.dp * c.dp;
    water_share = placed / init.fluid_volume_asked;
    std::printf("water       %.6g m^3 placed of %.6g m^3 in the fluid boxes (%.1f %%; lattices of whole spacings, "
                "centred in each box)\n",
                placed, init.fluid_volume_asked, 100.0 * placed / init.fluid_volume_asked);
  }
  if (cp) {
    std::printf("spheres     %zu, %ld bonds, %zu body particles (%d layers), %zu fluid particles removed inside "
                "spheres\n",
                cp->setup.spheres.size(), cp->bonds, cp->coupling->n_body(), cp->layers, cp->fluid_removed);
    std::printf("DEM step    %.3g s (dt_factor %g): about %.0f DEM sub-steps per SPH step at the first dt\n",
                static_cast<double>(cp->coupling->dt_dem()), c.dem.dt_factor,
                std::ceil(dt0 / static_cast<double>(cp->coupling->dt_dem())));
  }
  std::printf("memory      about %.1f MiB (%.0f bytes per particle)\n", n * bytes_per_particle_estimate / 1048576.0,
              bytes_per_particle_estimate);
  std::printf("resolution  dp = %g m, h = %g m, water depth %g m, c0 = %g m/s\n", c.dp, c.h(), c.water_depth(),
              c.sound_speed());
  {
    const auto [lo, hi] = sph::fluid_region(c, init);
    const Vec3d a = Vec3d(lo) + init.origin, b = Vec3d(hi) + init.origin;
    std::printf("removal     fluid leaving x [%.4g, %.4g], y [%.4g, %.4g], z [%.4g, %.4g] m is removed (the domain, "
                "grown to hold the wall layers); fluid inside a wall is counted at every output (summary.json: "
                "in_walls)\n",
                a.x, b.x, a.y, b.y, a.z, b.z);
  }
  std::printf("time step   first dt = %.3g s, about %.3g steps to t = %g s\n", dt0, steps, c.time.end);
  std::printf("run time    about %s on 2 CPU threads (assuming %.1e particle-steps/s; the step shrinks when the flow "
              "accelerates)\n",
              hms(steps * n / assumed_particle_steps_per_s).c_str(), assumed_particle_steps_per_s);
  int warnings = 0;
  auto warn = [&](const std::string& w) {
    std::printf("warning     %s\n", w.c_str());
    ++warnings;
  };
  if (water_share < 0.98 && init.fluid_dropped_by_walls == 0)
    warn("the fluid boxes hold " + fmt(100 * water_share) +
         " % of their volume in water: their sizes are not whole numbers of dp (choose dp dividing them)");
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
    if (dense && ratio > slack / 6)
      warn("dp = D/" + fmt(1 / ratio) +
           " for a dense assembly of spheres: the paper's guidance is dp <= D/6 (D/8 better)");
    else if (!dense && ratio > slack / 20)
      warn("dp = D/" + fmt(1 / ratio) +
           " for loose spheres (not touching): the paper's guidance is dp <= D/20; coarser runs overestimate buoyancy "
           "and drag (gap effect)");
  }
  if (c.sph.eta < 10) warn("eta < 10: the Mach number may exceed 0.1 and the water compress noticeably");
  if (warnings == 0) std::printf("warnings    none\n");
  return 0;
}

int run(const Case& c, const RunOptions& opt) {
  // DEM-only cases are not distributed: rank 0 runs them.
  if (c.dem.active() && !c.coupled()) return DistributedRun::root() ? run_dem(c, opt) : 0;
  const auto wall0 = Clock::now();
  // Everything that can fail on input happens before the output folder is touched.
  sph::InitialState init = sph::build_initial_state(c);
  std::optional<CoupledParts> cp;
  if (c.coupled()) cp.emplace(c, init);
  // A distributed run's solver starts empty: each process uploads only its slab (below).
  const particles::HostParticles none;
  sph::WcsphSolver solver(c, init, DistributedRun::enabled() ? &none : nullptr);
  sph::Gauges gauges(c, init);
  const ExtraCounts extra{cp ? cp->coupling->n_body() : 0, cp ? cp->setup.spheres.size() : 0};
  // Built with MPI: slabs of particles, one per process; only rank 0 writes files and prints.
  DistributedRun dist(c, solver, cp ? cp->coupling.get() : nullptr);
  const bool root = DistributedRun::root();
  const bool quiet = opt.quiet || !root;

  namespace fs = std::filesystem;
  const fs::path out(opt.out_dir);
  io::Checkpoint ck;
  if (opt.restart) {
    ck = io::read_checkpoint((out / "checkpoint.bin").string());
    if (ck.gauge_rows.empty() || ck.gauge_rows.front().size() != gauges.names().size() + 1)
      throw InputError((out / "checkpoint.bin").string(), 0, "gauges",
                       "the checkpoint's gauges differ from the case's; restart with the case.yaml of that run");
    if (ck.dem_state.empty() != !cp)
      throw InputError((out / "checkpoint.bin").string(), 0, "dem",
                       cp ? "the checkpoint holds no DEM spheres but the case has them; restart with the case.yaml of "
                            "that run"
                          : "the checkpoint holds DEM spheres but the case has none; restart with the case.yaml of "
                            "that run");
    if (cp) {
      try {
        cp->dem->restore(ck.dem_state);
      } catch (const std::invalid_argument& e) {
        throw InputError((out / "checkpoint.bin").string(), 0, "dem",
                         std::string(e.what()) + "; restart with the case.yaml of that run");
      }
    }
  }
  if (root) {
    fs::create_directories(out / "particles");
    io::write_file_atomic((out / "case.yaml").string(), io::to_yaml(c));
  }
  io::PvdCollection walls_pvd((out / "walls.pvd").string());
  io::PvdCollection fluid_pvd((out / "fluid.pvd").string());
  std::optional<io::PvdCollection> spheres_pvd;
  if (cp) spheres_pvd.emplace((out / "spheres.pvd").string());
  if (!opt.restart && root) {
    io::write_particles_vtp((out / "particles" / "walls_0000.vtp").string(), init.particles, init.origin, {Kind::Wall});
    walls_pvd.add(0.0, "particles/walls_0000.vtp");
  }

  particles::HostParticles host;
  const WallLeaks leaks(c);
  std::vector<std::vector<double>> rows;
  Totals tot, since_output;
  double t = 0;
  int frame = 0;
  std::size_t rows_written = 0;
  std::vector<double> frame_times;
  // The time loop of this invocation (a restart's loop starts at its checkpoint): the
  // throughput figures count its steps over its time, set-up and first output excluded.
  auto loop0 = Clock::now();
  long steps0 = 0;
  auto write_summary = [&](const std::string& status, int code, const std::string& msg) {
    const double wall = std::chrono::duration<double>(Clock::now() - wall0).count();
    const double loop_wall = std::chrono::duration<double>(Clock::now() - loop0).count();
    // Collective: every process takes part, rank 0 writes (RSS summed over processes).
    const long n_now = dist.owned_particles();
    dist.measure_waits();
    const double rss = dist.active() ? DistributedRun::total(peak_rss_bytes()) : peak_rss_bytes();
    if (root)
      io::write_file_atomic((out / "summary.json").string(),
                            summary_json(c, init, extra, status, code, solver.step_count(), t, wall,
                                         solver.step_count() - steps0, loop_wall, tot, n_now, rss, dist.summary_json(),
                                         msg));
  };
  auto sample_gauges = [&] {
    dist.sync();
    std::vector<dem::Sphere> sp;
    std::vector<Vec3> ff, fm;
    if (cp) {
      sp = cp->dem->spheres();
      ff = cp->dem->external_forces();
      fm = cp->dem->external_torques();
    }
    auto v = gauges.sample(
        solver,
        [&](const GaugeSpec& g) {
          return g.type == GaugeType::DemWall ? dem_wall_gauge_value(g, c, cp->setup, *cp->dem)
                                              : sphere_gauge_value(g, sp, ff, fm, init.origin);
        },
        dist.distribution());
    v.insert(v.begin(), t);
    rows.push_back(std::move(v));
  };
  double next_out = c.time.output_every, next_gauge = c.time.gauge_every;
  WallCheckpoints wall_checkpoints(c.time.checkpoint_every_wall);
  // The gauge rows so far, the checkpoint and the summary: with every output, and between
  // outputs when a wall-clock checkpoint is due.
  auto save_progress = [&] {
    if (root) io::write_file_atomic((out / "gauges.csv").string(), csv_text(gauges.names(), rows));
    rows_written = rows.size();
    io::Checkpoint k;
    k.time = t;
    k.steps = solver.step_count();
    k.frame = frame;
    k.next_output = next_out;
    k.next_gauge = next_gauge;
    k.frame_times = frame_times;
    k.gauge_rows = rows;
    k.removed_domain = tot.removed_domain;
    k.removed_density = tot.removed_density;
    k.non_finite = tot.non_finite;
    dist.gather(k.particles, true);
    if (cp) k.dem_state = cp->dem->save();
    if (root) io::write_checkpoint((out / "checkpoint.bin").string(), k);
    wall_checkpoints.written();
    write_summary("running", 0, "");
  };
  auto write_output = [&] {
    dist.sync();
    solver.refresh();
    dist.gather(host, false);
    char name[64];
    std::snprintf(name, sizeof name, "fluid_%04d.vtp", frame);
    if (root) {
      io::write_particles_vtp((out / "particles" / name).string(), host, init.origin, {Kind::Fluid});
      fluid_pvd.add(t, std::string("particles/") + name);
    }
    if (cp && root) {
      std::snprintf(name, sizeof name, "spheres_%04d.vtp", frame);
      io::write_spheres_vtp((out / "particles" / name).string(), sphere_frame(*cp->dem), init.origin);
      spheres_pvd->add(t, std::string("particles/") + name);
    }
    if (root) {
      const LeakCount in_walls = leaks.count(host, init.origin);
      tot.leaks.add(in_walls, t);
      if (in_walls.count > 0 && !quiet)
        std::fprintf(stderr,
                     "%st = %.4f s: %ld fluid particles inside walls (first: %s) within x [%.3f, %.3f], y [%.3f, "
                     "%.3f], z [%.3f, %.3f] m\n",
                     opt.progress_tty ? "\n" : "", t, in_walls.count, in_walls.wall.c_str(), in_walls.lo.x,
                     in_walls.hi.x, in_walls.lo.y, in_walls.hi.y, in_walls.lo.z, in_walls.hi.z);
    }
    frame_times.push_back(t);
    ++frame;
    save_progress();
    if (since_output.removed() > 0 && !quiet)
      std::fprintf(stderr,
                   "%st = %.4f s: removed %ld fluid particles since the last output (%ld left the domain, %ld density "
                   "out of range, %ld non-finite) within x [%.3f, %.3f], y [%.3f, %.3f], z [%.3f, %.3f] m\n",
                   opt.progress_tty ? "\n" : "", t, since_output.removed(), since_output.removed_domain,
                   since_output.removed_density, since_output.non_finite, since_output.lo.x, since_output.hi.x,
                   since_output.lo.y, since_output.hi.y, since_output.lo.z, since_output.hi.z);
    since_output = {};
  };

  if (opt.restart) {
    // Continue exactly where the checkpoint was written (at an output time).
    t = ck.time;
    frame = ck.frame;
    next_out = ck.next_output;
    next_gauge = ck.next_gauge;
    // Checkpoints of builds before 2026-11-22 were written before the next output time
    // was advanced: never take a zero-length step on their account.
    while (next_out <= t + 1e-9 * c.time.end) next_out += c.time.output_every;
    while (next_gauge <= t + 1e-9 * c.time.end) next_gauge += c.time.gauge_every;
    frame_times = ck.frame_times;
    rows = ck.gauge_rows;
    rows_written = rows.size();
    tot.removed_domain = ck.removed_domain;
    tot.removed_density = ck.removed_density;
    tot.non_finite = ck.non_finite;
    std::vector<std::pair<double, std::string>> entries;
    for (int k = 0; k < static_cast<int>(frame_times.size()); ++k) {
      char name[64];
      std::snprintf(name, sizeof name, "particles/fluid_%04d.vtp", k);
      entries.emplace_back(frame_times[k], name);
    }
    fluid_pvd.restore(entries);
    walls_pvd.restore({{0.0, "particles/walls_0000.vtp"}});
    if (cp) {
      for (auto& e : entries) e.second.replace(e.second.find("fluid_"), 6, "spheres_");
      spheres_pvd->restore(entries);
    }
    dist.start(std::move(ck.particles), ck.steps); // a checkpoint of any number of processes
    // The body particles' mDBC ghost nodes turn with the restored spheres (the positions
    // placed again are the checkpoint's, bit for bit).
    if (cp) cp->coupling->place_bodies(solver, *cp->dem);
    ck.particles = {};
    if (!quiet) std::fprintf(stderr, "restarting at t = %g s (step %ld)\n", t, ck.steps);
  } else {
    dist.start(init.particles);
    if (cp) cp->coupling->reduce_forces(solver, *cp->dem); // the fluid force at t = 0, for the gauges
    sample_gauges();
    write_output();
  }
  const double eps = 1e-9 * c.time.end;
  const double dt_min = c.time.dt_min > 0 ? c.time.dt_min : 1e-3 * first_dt(c);
  const double max_removed = c.sph.max_removed_share * static_cast<double>(init.n_fluid);
  auto last_report = Clock::now();
  loop0 = Clock::now();
  steps0 = solver.step_count();
  const double t0 = t;
  std::string failure;
  bool stop = false; // Ctrl-C, agreed by every process
  while (t < c.time.end - eps) {
    if (stop) break;
    if (c.time.max_steps > 0 && solver.step_count() >= c.time.max_steps) break;
    const double dt_max = std::min({next_out, next_gauge, c.time.end}) - t;
    dist.sync();
    sph::StepStats s = solver.step(dt_max);
    dist.stepped();
    if (cp) cp->coupling->after_fluid_step(solver, *cp->dem, s.dt);
    t += s.dt;
    stop = opt.stop && *opt.stop;
    // Wall-clock checkpoints are collective (a gather): every process must agree to write one.
    bool checkpoint_due = wall_checkpoints.due();
    dist.combine(s, stop, checkpoint_due);
    for (Totals* x : {&tot, &since_output}) {
      x->removed_domain += s.removed_domain;
      x->removed_density += s.removed_density;
      x->non_finite += s.non_finite;
      if (s.removed_domain + s.removed_density > 0) {
        for (int k = 0; k < 3; ++k) {
          x->lo[k] = std::min(x->lo[k], init.origin[k] + static_cast<double>(s.removed_lo[k]));
          x->hi[k] = std::max(x->hi[k], init.origin[k] + static_cast<double>(s.removed_hi[k]));
        }
      }
    }
    if (cp && !cp->dem->finite()) {
      std::ostringstream m;
      m << "diverged at t = " << t << " s (step " << solver.step_count()
        << "): a DEM sphere has a non-finite position (try a smaller dem.dt_factor or sph.cfl)";
      failure = m.str();
    } else if (s.non_finite > 0) {
      std::ostringstream m;
      m << "diverged at t = " << t << " s (step " << solver.step_count() << "): " << s.non_finite
        << " particles have non-finite position, velocity or density";
      failure = m.str();
    } else if (static_cast<double>(tot.removed()) > max_removed && init.n_fluid > 0) {
      std::ostringstream m;
      m << "diverged at t = " << t << " s (step " << solver.step_count() << "): " << tot.removed() << " of "
        << init.n_fluid << " fluid particles removed (limit sph.max_removed_share = " << c.sph.max_removed_share << "; "
        << tot.removed_domain << " left the domain, " << tot.removed_density << " density out of range)";
      failure = m.str();
    } else if (s.dt < dt_min && s.dt < dt_max * (1 - 1e-9)) {
      std::ostringstream m;
      m << "diverged at t = " << t << " s (step " << solver.step_count() << "): the time step fell to " << s.dt
        << " s, below time.dt_min = " << dt_min << " s";
      failure = m.str();
    }
    if (!failure.empty()) break;
    if (t >= next_gauge - eps) {
      sample_gauges();
      next_gauge += c.time.gauge_every;
    }
    if (t >= next_out - eps) {
      next_out += c.time.output_every; // before the checkpoint is written: a restart continues from here
      write_output();
    } else if (checkpoint_due) {
      save_progress(); // no frame
    }
    const auto now = Clock::now();
    const double since = std::chrono::duration<double>(now - last_report).count();
    if (!quiet && (opt.progress_tty ? since > 0.5 : since > opt.report_every_s)) {
      last_report = now;
      const double el = std::chrono::duration<double>(now - loop0).count();
      // Rates over this session only (a restart starts the clock at its checkpoint).
      const double sps = static_cast<double>(solver.step_count() - steps0) / el;
      const double eta_s = el * (c.time.end - t) / std::max(t - t0, 1e-12);
      std::fprintf(stderr, "%st = %.4f / %g s  %5.1f%%  %.1f steps/s  dt %.2e s  ETA %s%s",
                   opt.progress_tty ? "\r" : "", t, c.time.end, 100.0 * t / c.time.end, sps, s.dt, hms(eta_s).c_str(),
                   opt.progress_tty ? "   " : "\n");
    }
  }
  if (opt.progress_tty && !quiet) std::fprintf(stderr, "\n");
  if (!failure.empty()) {
    // Outputs written so far are the last good state; nothing after it is written.
    write_summary("diverged", 3, failure);
    if (root)
      std::fprintf(stderr,
                   "error: %s\n  the last good output (t = %g s) is in %s; try a smaller sph.cfl or a finer dp\n",
                   failure.c_str(), frame > 0 ? (frame - 1) * c.time.output_every : 0.0, out.string().c_str());
    return 3;
  }
  const bool interrupted = stop;
  if (rows.size() > rows_written || interrupted) write_output();
  write_summary(interrupted ? "interrupted" : "completed", interrupted ? 130 : 0,
                interrupted ? "stopped by the user" : "");
  if (!quiet) {
    const double wall = std::chrono::duration<double>(Clock::now() - wall0).count();
    const double loop_wall = std::chrono::duration<double>(Clock::now() - loop0).count();
    const double n = static_cast<double>(init.n_fluid + init.n_wall);
    // Throughput over this invocation's own steps (after a restart, not the whole run's).
    std::fprintf(stderr,
                 "%s: %ld steps to t = %.4g s in %.1f s wall, %.3g particle-steps/s (%zu fluid + %zu wall), %ld fluid "
                 "particles removed\n  output in %s\n",
                 interrupted ? "interrupted" : "done", solver.step_count(), t, wall,
                 n * static_cast<double>(solver.step_count() - steps0) / loop_wall, init.n_fluid, init.n_wall,
                 tot.removed(), out.string().c_str());
  }
  return interrupted ? 130 : 0;
}

} // namespace surge::sim
