#include "surge/sim/run_summary.hpp"

#include "surge/core/version.hpp"
#include "surge/par/parallel.hpp"
#include "surge/sim/run_support.hpp"

#include <sstream>

namespace surge::sim {

std::string summary_json(const Case& c, const RunCounts& n, const std::string& status, int code,
                         const std::string& message, const LoopClock& k) {
  std::ostringstream j;
  j.precision(10);
  const auto n_all = static_cast<double>(n.stepped);
  const auto per_s = [&](double count) {
    return k.loop_wall > 0 ? count * static_cast<double>(k.loop_steps) / k.loop_wall : 0.0;
  };
  const Removals& r = n.removed;
  j << "{\n  \"name\": \"" << json_escape(c.name) << "\",\n  \"surge_version\": \"" << version_string << "\",\n"
    << "  \"backend\": \"" << par::backend_name() << "\",\n  \"threads\": " << par::threads() << ",\n"
    << "  \"distributed\": " << n.distributed << ",\n"
    << "  \"status\": \"" << status << "\",\n  \"exit_code\": " << code << ",\n  \"message\": \""
    << json_escape(message) << "\",\n"
    << "  \"particles\": {\"fluid\": " << n.fluid << ", \"wall\": " << n.wall << ", \"body\": " << n.body
    << ", \"sphere\": " << n.spheres << ", \"now\": " << n.fluid_now << "},\n";
  if (n.dem)
    j << "  \"dem\": {\"dt\": " << n.dem_dt << ", \"bonds\": " << n.bonds << ", \"broken_bonds\": " << n.broken_bonds
      << "},\n";
  j << "  \"steps\": " << k.steps << ",\n  \"simulated_time\": " << k.t << ",\n  \"wall_seconds\": " << k.wall << ",\n"
    << "  \"loop_steps\": " << k.loop_steps << ",\n  \"loop_seconds\": " << k.loop_wall << ",\n"
    << "  \"particle_steps_per_second\": " << per_s(n_all) << ",\n"
    << "  \"fluid_particle_steps_per_second\": " << per_s(static_cast<double>(n.fluid)) << ",\n"
    << "  \"removed\": {\"total\": " << r.total() << ", \"left_domain\": " << r.domain
    << ", \"density_out_of_range\": " << r.density << ", \"non_finite\": " << r.non_finite;
  if (r.domain + r.density > 0)
    j << ", \"where\": {\"min\": [" << r.lo.x << ", " << r.lo.y << ", " << r.lo.z << "], \"max\": [" << r.hi.x << ", "
      << r.hi.y << ", " << r.hi.z << "]}";
  j << "},\n"
    << "  \"in_walls\": " << n.in_walls << ",\n"
    << "  \"peak_rss_bytes\": " << n.peak_rss
    << ",\n  \"bytes_per_particle\": " << (n_all > 0 ? n.peak_rss / n_all : 0.0) << "\n}\n";
  return j.str();
}

} // namespace surge::sim
