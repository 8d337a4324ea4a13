// DEM-only runs: spheres from the case's packs, walls from planes and STL meshes.
#include "surge/core/error.hpp"
#include "surge/core/version.hpp"
#include "surge/dem/dem_solver.hpp"
#include "surge/geometry/sphere_packs.hpp"
#include "surge/geometry/stl_mesh.hpp"
#include "surge/io/atomic_file.hpp"
#include "surge/io/case_reader.hpp"
#include "surge/io/checkpoint.hpp"
#include "surge/io/vtk_writer.hpp"
#include "surge/sim/dem_setup.hpp"
#include "surge/sim/run_support.hpp"
#include "surge/sim/simulation.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>

namespace surge::sim {
namespace {

using Clock = std::chrono::steady_clock;

} // namespace

int check_dem(const Case& c) {
  const DemSetup s = dem_setup(c);
  auto solver = make_dem_solver(c, s);
  const double dt = solver.critical_dt(static_cast<Real>(c.dem.dt_factor));
  const double steps = c.time.end / dt;
  std::printf("case        %s (%s), DEM only\n", c.name.c_str(), c.source.c_str());
  std::printf("spheres     %zu, %zu wall planes, %zu wall triangles, %zu materials\n", s.spheres.size(),
              s.planes.size(), s.triangles.size(), s.materials.size());
  if (s.bonded)
    std::printf("bonds       %ld at the start (gap tolerance %g m)\n",
                solver.bond_touching(static_cast<Real>(c.dem.bond_gap)), c.dem.bond_gap);
  std::printf("time step   DEM dt = %.3g s (dt_factor %g x min sqrt(m/k_n)), about %.3g steps to t = %g s\n", dt,
              c.dem.dt_factor, steps, c.time.end);
  std::printf("memory      about %.1f MiB\n", static_cast<double>(s.spheres.size()) * 1100.0 / 1048576.0);
  return 0;
}

int run_dem(const Case& c, const RunOptions& opt) {
  const auto wall0 = Clock::now();
  const DemSetup setup = dem_setup(c);
  check_sphere_gauges(c, setup.spheres.size());
  auto solver = make_dem_solver(c, setup);
  const long bonds = setup.bonded ? solver.bond_touching(static_cast<Real>(c.dem.bond_gap)) : 0;
  const Real dt = solver.critical_dt(static_cast<Real>(c.dem.dt_factor));

  namespace fs = std::filesystem;
  const fs::path out(opt.out_dir);
  io::Checkpoint ck;
  if (opt.restart) {
    const std::string path = (out / "checkpoint.bin").string();
    ck = io::read_checkpoint(path);
    if (ck.dem_state.empty() || !ck.particles.pos.empty())
      throw InputError(path, 0, "", "not the checkpoint of a DEM-only run; restart with the case.yaml of that run");
    if (!ck.gauge_rows.empty() && ck.gauge_rows.front().size() != c.gauges.size() + 1)
      throw InputError(path, 0, "gauges", "the checkpoint's gauges differ from the case's");
    try {
      solver.restore(ck.dem_state);
    } catch (const std::invalid_argument& e) {
      throw InputError(path, 0, "dem", std::string(e.what()) + "; restart with the case.yaml of that run");
    }
  }
  fs::create_directories(out / "particles");
  io::write_file_atomic((out / "case.yaml").string(), io::to_yaml(c));
  io::PvdCollection pvd((out / "spheres.pvd").string());
  double t = 0;
  long steps = 0;
  int frame = 0;
  std::string status = "running", message;
  int code = 0;
  auto write_summary = [&] {
    const double wall = std::chrono::duration<double>(Clock::now() - wall0).count();
    const double n = static_cast<double>(setup.spheres.size());
    std::ostringstream j;
    j.precision(10);
    j << "{\n  \"name\": \"" << c.name << "\",\n  \"surge_version\": \"" << version_string << "\",\n  \"backend\": \""
      << par::backend_name() << "\",\n  \"threads\": " << par::threads() << ",\n  \"status\": \"" << status
      << "\",\n  \"exit_code\": " << code << ",\n  \"message\": \"" << json_escape(message) << "\",\n"
      << "  \"particles\": {\"fluid\": 0, \"wall\": 0, \"body\": 0, \"sphere\": " << setup.spheres.size() << "},\n"
      << "  \"dem\": {\"dt\": " << dt << ", \"bonds\": " << bonds << ", \"broken_bonds\": " << solver.broken_bonds()
      << "},\n  \"steps\": " << steps << ",\n  \"simulated_time\": " << t << ",\n  \"wall_seconds\": " << wall
      << ",\n  \"particle_steps_per_second\": " << (wall > 0 ? n * static_cast<double>(steps) / wall : 0.0)
      << ",\n  \"removed\": {\"total\": 0},\n  \"peak_rss_bytes\": " << peak_rss_bytes() << "\n}\n";
    io::write_file_atomic((out / "summary.json").string(), j.str());
  };
  // Sphere gauges (the only kind a DEM-only case has): no fluid force.
  std::vector<std::string> gauge_names;
  for (const auto& g : c.gauges) gauge_names.push_back(g.name);
  std::vector<std::vector<double>> rows;
  auto sample_gauges = [&] {
    const auto sp = solver.spheres();
    std::vector<double> row{t};
    for (const auto& g : c.gauges)
      row.push_back(g.type == GaugeType::DemWall ? dem_wall_gauge_value(g, c, setup, solver)
                                                 : sphere_gauge_value(g, sp, {}, {}, setup.origin));
    rows.push_back(std::move(row));
  };
  double next_out = c.time.output_every, next_gauge = c.time.gauge_every;
  std::vector<double> frame_times;
  WallCheckpoints wall_checkpoints(c.time.checkpoint_every_wall);
  // The gauge rows so far and the checkpoint: with every output, and between outputs
  // when a wall-clock checkpoint is due.
  auto save_progress = [&] {
    if (!gauge_names.empty()) io::write_file_atomic((out / "gauges.csv").string(), csv_text(gauge_names, rows));
    io::Checkpoint k;
    k.time = t;
    k.steps = steps;
    k.frame = frame;
    k.next_output = next_out;
    k.next_gauge = next_gauge;
    k.frame_times = frame_times;
    k.gauge_rows = rows;
    k.dem_state = solver.save();
    io::write_checkpoint((out / "checkpoint.bin").string(), k);
    wall_checkpoints.written();
  };
  auto write_output = [&] {
    const io::SphereFrame f = sphere_frame(solver);
    for (const auto& p : f.pos)
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false; // keep the last good files
    char name[64];
    std::snprintf(name, sizeof name, "spheres_%04d.vtp", frame++);
    io::write_spheres_vtp((out / "particles" / name).string(), f, setup.origin);
    pvd.add(t, std::string("particles/") + name);
    frame_times.push_back(t);
    save_progress();
    return true;
  };
  if (opt.restart) {
    t = ck.time;
    steps = ck.steps;
    frame = ck.frame;
    next_out = ck.next_output;
    next_gauge = ck.next_gauge;
    frame_times = ck.frame_times;
    rows = ck.gauge_rows;
    std::vector<std::pair<double, std::string>> entries;
    for (std::size_t k = 0; k < frame_times.size(); ++k) {
      char name[64];
      std::snprintf(name, sizeof name, "particles/spheres_%04zu.vtp", k);
      entries.emplace_back(frame_times[k], name);
    }
    pvd.restore(entries);
    if (!opt.quiet) std::fprintf(stderr, "restarting at t = %g s (step %ld)\n", t, steps);
  } else {
    if (!gauge_names.empty()) sample_gauges();
    write_output();
  }
  write_summary();
  const double eps = 1e-9 * c.time.end;
  auto last_report = Clock::now();
  while (t < c.time.end - eps) {
    if (opt.stop && *opt.stop) break;
    if (c.time.max_steps > 0 && steps >= c.time.max_steps) break;
    solver.step(dt); // a fixed step: outputs fall on the first step at or after their time
    t += static_cast<double>(dt);
    ++steps;
    if (!gauge_names.empty() && t >= next_gauge - eps) {
      sample_gauges();
      next_gauge += c.time.gauge_every;
    }
    if (t >= next_out - eps) {
      next_out += c.time.output_every;
      if (!write_output()) {
        status = "diverged";
        code = 3;
        message = "non-finite sphere position at t = " + std::to_string(t) + " s; try a smaller dem.dt_factor";
        write_summary();
        std::fprintf(stderr, "error: %s\n", message.c_str());
        return 3;
      }
      write_summary();
    } else if (wall_checkpoints.due() && solver.finite()) {
      save_progress(); // no frame
    }
    const auto now = Clock::now();
    if (!opt.quiet &&
        std::chrono::duration<double>(now - last_report).count() > (opt.progress_tty ? 0.5 : opt.report_every_s)) {
      last_report = now;
      std::fprintf(stderr, "%st = %.4f / %g s  %5.1f%%  %ld steps  %ld broken bonds%s", opt.progress_tty ? "\r" : "", t,
                   c.time.end, 100.0 * t / c.time.end, steps, solver.broken_bonds(), opt.progress_tty ? "   " : "\n");
    }
  }
  const bool interrupted = opt.stop && *opt.stop;
  if (frame_times.empty() || t > frame_times.back()) write_output(); // the final state, unless just written
  status = interrupted ? "interrupted" : "completed";
  code = interrupted ? 130 : 0;
  write_summary();
  if (!opt.quiet)
    std::fprintf(stderr, "%s%s: %ld DEM steps to t = %.4g s, %zu spheres, %ld of %ld bonds broken\n  output in %s\n",
                 opt.progress_tty ? "\n" : "", status.c_str(), steps, t, setup.spheres.size(), solver.broken_bonds(),
                 bonds, out.string().c_str());
  return code;
}

} // namespace surge::sim
