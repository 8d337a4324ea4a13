// DEM-only runs: spheres from the case's packs, walls from planes and STL meshes.
#include "surge/core/error.hpp"
#include "surge/dem/dem_solver.hpp"
#include "surge/domain/comm.hpp"
#include "surge/geometry/sphere_packs.hpp"
#include "surge/geometry/stl_mesh.hpp"
#include "surge/io/atomic_file.hpp"
#include "surge/io/case_reader.hpp"
#include "surge/io/checkpoint.hpp"
#include "surge/io/vtk_writer.hpp"
#include "surge/sim/dem_setup.hpp"
#include "surge/sim/moving_bodies.hpp"
#include "surge/sim/run_loop.hpp"
#include "surge/sim/run_summary.hpp"
#include "surge/sim/run_support.hpp"
#include "surge/sim/simulation.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace surge::sim {
namespace {

using Clock = std::chrono::steady_clock;

} // namespace

int check_dem(const Case& c) {
  const DemSetup s = dem_setup(c);
  auto solver = make_dem_solver(c, s);
  const MovingBodies bodies(c, nullptr); // refuses a motion that leaves the domain
  const double dt = solver.critical_dt(static_cast<Real>(c.dem.dt_factor));
  const double steps = c.time.end / dt;
  std::printf("case        %s (%s), DEM only\n", c.name.c_str(), c.source.c_str());
  std::printf("spheres     %zu, %zu wall planes, %zu wall triangles, %zu materials\n", s.spheres.size(),
              s.planes.size(), s.triangles.size(), s.materials.size());
  if (s.bonded) {
    const long bonds = solver.bond_touching(static_cast<Real>(c.dem.bond_gap));
    std::printf("bonds       %ld at the start (gap tolerance %g m)\n", bonds, c.dem.bond_gap);
    if (const std::string w = no_bonds_warning(c, s, bonds); !w.empty()) std::printf("warning     %s\n", w.c_str());
  }
  const char* scale = "";
  dem::with_contact_law(s.contact_law, [&](auto law) { scale = decltype(law)::time_scale_name; });
  print_slides(c, s);
  print_moving_walls(c, bodies);
  std::printf("contact     %s\n", c.dem.contact.c_str());
  std::printf("time step   DEM dt = %.3g s (dt_factor %g x the smallest %s), about %.3g steps to t = %g s\n", dt,
              c.dem.dt_factor, scale, steps, c.time.end);
  if (const std::string w = dem_step_warning(c, solver); !w.empty()) std::printf("warning     %s\n", w.c_str());
  std::printf("memory      about %.1f MiB\n", static_cast<double>(s.spheres.size()) * 1100.0 / 1048576.0);
  return 0;
}

namespace {

// Spheres only, at the fixed step of the DEM. In a distributed run every process
// advances the same DEM (as in a coupled run: it is deterministic, so all hold the same
// bits without sending any) and rank 0 writes; the processes agree on Ctrl-C and on
// wall-clock checkpoints. The DEM's work is not split among them.
class DemStepper final : public Stepper {
public:
  DemStepper(const Case& c, const RunOptions& opt, const io::Checkpoint* ck)
      : c_(c), setup_(dem_setup(c)), solver_(make_dem_solver(c, setup_)), bodies_(c, nullptr), out_(opt.out_dir),
        spheres_(opt.out_dir, "spheres"), dem_walls_(out_, bodies_.moves_dem()) {
    check_sphere_gauges(c, setup_.spheres.size());
    bonds_ = setup_.bonded ? solver_.bond_touching(static_cast<Real>(c.dem.bond_gap)) : 0;
    dt_ = solver_.critical_dt(static_cast<Real>(c.dem.dt_factor));
    if (ck) {
      const std::string path = (out_ / "checkpoint.bin").string();
      if (ck->dem_state.empty() || !ck->particles.pos.empty())
        throw InputError(path, 0, "", "not the checkpoint of a DEM-only run; restart with the case.yaml of that run");
      check_restart_gauges(*ck, c.gauges.size(), path);
      try {
        solver_.restore(ck->dem_state);
      } catch (const std::invalid_argument& e) {
        throw InputError(path, 0, "dem", std::string(e.what()) + "; restart with the case.yaml of that run");
      }
      bodies_.restore(ck->body_state, path);
      steps_ = ck->steps;
    }
    bodies_.attach(solver_, ck ? ck->time : 0.0); // the moving walls where they are at the start
    if (root()) prepare_output(c, opt.out_dir);
  }

  double step(double dt_max, double t, bool& stop, bool& checkpoint_due, std::string& failure) override {
    (void)dt_max;      // non-finite states are caught at outputs
    solver_.step(dt_); // a fixed step: outputs fall on the first step at or after their time
    const auto dt = static_cast<double>(dt_);
    bodies_.advance(solver_, dt, t + dt); // the moving walls: free bodies under the spheres' loads
    if (const std::string e = bodies_.escaped(); !e.empty())
      failure = "diverged at t = " + std::to_string(t + dt) + " s: " + e;
    ++steps_;
    if (domain::comm::size() > 1) {
      double flags[2] = {stop ? 1.0 : 0.0, checkpoint_due ? 1.0 : 0.0};
      domain::comm::sum(flags, 2);
      stop = flags[0] > 0;
      checkpoint_due = flags[1] > 0;
    }
    checkpoint_due = checkpoint_due && solver_.finite(); // never a checkpoint of a diverged state
    return dt;
  }

  [[nodiscard]] bool root() const override { return domain::comm::rank() == 0; }

  [[nodiscard]] long steps() const override { return steps_; }
  [[nodiscard]] std::vector<std::string> gauge_names() const override {
    std::vector<std::string> n;
    for (const auto& g : c_.gauges) n.push_back(g.name);
    return n;
  }
  // Sphere, DEM-wall and body gauges (the only kinds a DEM-only case has): no fluid force.
  std::vector<double> sample(double t) override {
    const DemGauges dem(c_, setup_, solver_, bodies_, false);
    std::vector<double> row;
    for (const auto& g : c_.gauges) row.push_back(dem.value(g, t));
    return row;
  }

  bool write_frame(int frame, double t, std::string& failure) override {
    const io::SphereFrame f = sphere_frame(solver_);
    for (const auto& p : f.pos)
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        failure = "non-finite sphere position at t = " + std::to_string(t) + " s; try a smaller dem.dt_factor";
        return false;
      }
    if (!root()) return true;
    io::write_spheres_vtp(spheres_.path(frame), f, setup_.origin);
    spheres_.add(frame, t);
    dem_walls_.write(solver_, frame, t, setup_.origin);
    return true;
  }

  void save(io::Checkpoint& k) override {
    k.dem_state = solver_.save();
    k.body_state = bodies_.save();
  }

  void restored(const std::vector<double>& frame_times) override {
    spheres_.restored(frame_times);
    dem_walls_.restored(frame_times);
  }

  RunCounts counts() override {
    RunCounts n;
    n.spheres = n.stepped = setup_.spheres.size();
    n.distributed = "{\"ranks\": " + std::to_string(domain::comm::size()) + ", \"dem\": \"every process\"}";
    n.dem = true;
    n.dem_dt = static_cast<double>(dt_);
    n.bonds = bonds_;
    n.broken_bonds = solver_.broken_bonds();
    n.peak_rss = peak_rss_bytes();
    return n;
  }

  [[nodiscard]] std::string progress() const override {
    return "  " + std::to_string(solver_.broken_bonds()) + " broken bonds";
  }

  void report_end(const std::string& status, const LoopClock& k) override {
    std::fprintf(stderr, "%s: %ld DEM steps to t = %.4g s, %zu spheres, %ld of %ld bonds broken\n  output in %s\n",
                 status.c_str(), k.steps, k.t, setup_.spheres.size(), solver_.broken_bonds(), bonds_,
                 out_.string().c_str());
  }

private:
  const Case& c_;
  DemSetup setup_;
  dem::DemSolver solver_;
  MovingBodies bodies_; // DEM walls with a motion
  std::filesystem::path out_;
  io::FrameSeries spheres_;
  DemWallFrames dem_walls_; // the moving meshes of every frame
  long bonds_ = 0, steps_ = 0;
  Real dt_ = 0;
};

} // namespace

int run_dem(const Case& c, const RunOptions& opt) {
  const auto wall0 = Clock::now();
  std::optional<io::Checkpoint> ck;
  if (opt.restart) ck = io::read_checkpoint((std::filesystem::path(opt.out_dir) / "checkpoint.bin").string());
  DemStepper s(c, opt, ck ? &*ck : nullptr);
  return run_loop(c, opt, s, ck ? &*ck : nullptr, wall0);
}

} // namespace surge::sim
