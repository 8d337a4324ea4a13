#include "surge/sph/hazard_maps.hpp"

#include "surge/core/error.hpp"
#include "surge/geometry/terrain.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

namespace surge::sph {
namespace {
constexpr double nan = std::numeric_limits<double>::quiet_NaN();
}

HazardMaps::HazardMaps(const Case& c, const InitialState& init) : cfg_(c.hazard) {
  if (!cfg_.enabled) return;
  const auto terrain = std::find_if(c.walls.begin(), c.walls.end(), [](const WallSpec& w) { return w.terrain; });
  const geometry::Raster grid = geometry::read_terrain(terrain->mesh_path, c.domain);
  // Every coarsen-th node inside the domain's x-y extent.
  const int f = cfg_.coarsen;
  auto first = [&](double lo, double o, double d) { return static_cast<long>(std::ceil((lo - o) / d - 1e-9)); };
  const long i0 = first(c.domain.min.x, grid.x0, grid.dx), j0 = first(c.domain.min.y, grid.y0, grid.dy);
  lattice_ = grid;
  lattice_.x0 = grid.x(i0);
  lattice_.y0 = grid.y(j0);
  lattice_.dx = grid.dx * f;
  lattice_.dy = grid.dy * f;
  lattice_.nx = static_cast<long>(std::floor((c.domain.max.x - lattice_.x0) / lattice_.dx + 1e-9)) + 1;
  lattice_.ny = static_cast<long>(std::floor((c.domain.max.y - lattice_.y0) / lattice_.dy + 1e-9)) + 1;
  lattice_.v.resize(static_cast<std::size_t>(lattice_.nx * lattice_.ny));
  for (long j = 0; j < lattice_.ny; ++j)
    for (long i = 0; i < lattice_.nx; ++i) lattice_.at(i, j) = grid.at(i0 + i * f, j0 + j * f);
  n_cells_ = lattice_.v.size();

  Case cols = c; // the columns as height gauges of a copy of the case
  cols.gauges.clear();
  auto column = [&](double x, double y) {
    GaugeSpec g;
    g.type = GaugeType::Height;
    g.x = x;
    g.y = y;
    g.name = "c" + std::to_string(cols.gauges.size());
    cols.gauges.push_back(g);
  };
  for (long j = 0; j < lattice_.ny; ++j)
    for (long i = 0; i < lattice_.nx; ++i) column(lattice_.x(i), lattice_.y(j));
  // Run-up points a spacing apart along each line, ends included.
  for (std::size_t l = 0; l < cfg_.run_up.size(); ++l) {
    const auto& ln = cfg_.run_up[l];
    const double len = std::hypot(ln.x1 - ln.x0, ln.y1 - ln.y0);
    const long n = std::max(1L, static_cast<long>(std::ceil(len / c.dp)));
    for (long k = 0; k <= n; ++k) {
      const double s = static_cast<double>(k) / static_cast<double>(n);
      run_up_points_.push_back({static_cast<int>(l), ln.x0 + s * (ln.x1 - ln.x0), ln.y0 + s * (ln.y1 - ln.y0)});
      column(run_up_points_.back().x, run_up_points_.back().y);
    }
  }
  cols_ = std::make_unique<Gauges>(cols, init);
  max_eta_.assign(n_cells_, nan);
  max_depth_.assign(n_cells_, nan);
  max_speed_.assign(n_cells_, nan);
  arrival_.assign(n_cells_, nan);
  first_wet_.assign(run_up_points_.size(), nan);
  top_.assign(run_up_points_.size(), nan);
  ground_.assign(run_up_points_.size(), nan);
}

void HazardMaps::sample(double t, WcsphSolver& solver, const Distribution& dist) {
  if (!enabled()) return;
  const auto col = cols_->columns(solver, dist);
  auto raise = [](double& m, double v) { m = std::isnan(m) ? v : std::max(m, v); };
  // A run-up point is wet when water, not wall, fills part of its column: on a dry slope
  // the walls beside the line fill it half a spacing and more above the bed (the gauge's
  // column then has a depth), but its fluid fraction is 0; a film of one layer of particles
  // reads 0.4-0.6. A map cell is wet where the fluid fraction reaches 0.5: its surface is
  // the water's (Column::water_top), not a slide's above it.
  auto wet = [](const Gauges::Column& cl) { return cl.fluid >= 0.3 && cl.top > cl.bed; };
  for (std::size_t k = 0; k < n_cells_; ++k) {
    const double eta = col[k].water_top, depth = eta - col[k].bed;
    if (!(col[k].fluid >= 0.5 && depth > 0)) continue;
    raise(max_eta_[k], eta);
    raise(max_depth_[k], depth);
    const Vec3d v = col[k].velocity;
    raise(max_speed_[k], std::sqrt(v.x * v.x + v.y * v.y));
    if (std::isnan(arrival_[k]) && eta > cfg_.still_level + cfg_.arrival_height) arrival_[k] = t;
  }
  for (std::size_t p = 0; p < run_up_points_.size(); ++p) {
    const auto& cl = col[n_cells_ + p];
    ground_[p] = cl.bed;
    if (!wet(cl)) continue;
    if (std::isnan(first_wet_[p])) first_wet_[p] = t;
    // The water's surface over the point: a film thinner than the fluid-fraction criterion
    // reads as the column's top.
    raise(top_[p], cl.water_top > cl.bed ? cl.water_top : cl.top);
  }
}

std::vector<std::string> HazardMaps::map_names() { return {"max_elevation", "max_depth", "max_speed", "arrival_time"}; }

std::vector<std::vector<double>> HazardMaps::maps() const { return {max_eta_, max_depth_, max_speed_, arrival_}; }

std::string HazardMaps::run_up_csv() const {
  // The run-up: at the highest ground the water wetted, the highest surface it stood to
  // there (the waterline's elevation; the wetted ground alone lies up to a spacing's rise
  // below it, between the points a spacing apart).
  std::string out = "line,x,y,ground_z,run_up_z,above_still_level,first_wet_time\n";
  for (std::size_t l = 0; l < cfg_.run_up.size(); ++l) {
    long best = -1;
    for (std::size_t p = 0; p < run_up_points_.size(); ++p)
      if (run_up_points_[p].line == static_cast<int>(l) && !std::isnan(first_wet_[p]) &&
          (best < 0 || ground_[p] > ground_[static_cast<std::size_t>(best)]))
        best = static_cast<long>(p);
    char row[256];
    if (best < 0) {
      std::snprintf(row, sizeof row, "%s,,,,,,\n", cfg_.run_up[l].name.c_str());
    } else {
      const auto b = static_cast<std::size_t>(best);
      const auto& q = run_up_points_[b];
      std::snprintf(row, sizeof row, "%s,%.3f,%.3f,%.4f,%.4f,%.4f,%.4f\n", cfg_.run_up[l].name.c_str(), q.x, q.y,
                    ground_[b], top_[b], top_[b] - cfg_.still_level, first_wet_[b]);
    }
    out += row;
  }
  return out;
}

std::string HazardMaps::save() const {
  std::string b;
  for (const auto* v : {&max_eta_, &max_depth_, &max_speed_, &arrival_, &first_wet_, &ground_, &top_}) {
    const std::uint64_t n = v->size();
    b.append(reinterpret_cast<const char*>(&n), sizeof n);
    b.append(reinterpret_cast<const char*>(v->data()), n * sizeof(double));
  }
  return b;
}

void HazardMaps::restore(const std::string& bytes, const std::string& checkpoint_path) {
  if (!enabled()) return;
  std::size_t pos = 0;
  for (auto* v : {&max_eta_, &max_depth_, &max_speed_, &arrival_, &first_wet_, &ground_, &top_}) {
    std::uint64_t n = 0;
    if (pos + sizeof n > bytes.size()) throw InputError(checkpoint_path, 0, "", "its hazard maps are truncated");
    std::memcpy(&n, bytes.data() + pos, sizeof n);
    pos += sizeof n;
    if (n != v->size() || pos + n * sizeof(double) > bytes.size())
      throw InputError(checkpoint_path, 0, "",
                       "its hazard maps do not fit this case's map lattice or run-up lines (hazard changed since?)");
    std::memcpy(v->data(), bytes.data() + pos, n * sizeof(double));
    pos += n * sizeof(double);
  }
}

} // namespace surge::sph
