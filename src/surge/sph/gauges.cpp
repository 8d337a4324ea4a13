#include "surge/sph/gauges.hpp"
#include "surge/motion/body_reading.hpp"

#include "surge/geometry/bed.hpp"
#include "surge/geometry/terrain.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

namespace surge::sph {
namespace {
bool needs_bed(const Case& c) {
  return std::any_of(c.gauges.begin(), c.gauges.end(), [](const GaugeSpec& g) { return g.type == GaugeType::Height; });
}
// Where the fraction crosses 0.5 between a sample at z (fraction f0) and the one dz above (f1).
double crossing(double z, double dz, double f0, double f1) { return z + dz * (f0 - 0.5) / (f0 - f1); }
} // namespace

namespace detail {
// out[id - id0] = a of each owned particle with id in [id0, id1) (free function: nvcc's
// extended lambdas may not live in private member functions).
void wall_accelerations(const particles::ParticleView& p, std::uint32_t id0, std::uint32_t id1, Vec3* out, Vec3* pos) {
  par::parallel_for(
      p.n, SURGE_LAMBDA(int i) {
        if (p.id[i] < id0 || p.id[i] >= id1 || !p.owned(i)) return;
        out[p.id[i] - id0] = p.acc[i];
        if (pos) pos[p.id[i] - id0] = p.pos[i];
      });
}
// out[k] = the kernel sums at pts[k] (a free function for nvcc's extended lambdas).
void point_sums(const WcsphParams& prm, const neighbour::GridView& g, const particles::ParticleView& p, const Vec3* pts,
                int n, PointSums* out) {
  par::parallel_for(
      n, SURGE_LAMBDA(int k) { out[k] = fluid_sums(prm, g, p, pts[k]); });
}
} // namespace detail

Gauges::Gauges(const Case& c, const InitialState& init) {
  dz_ = c.dp / 4;
  bed_reach_ = static_cast<int>(2 * c.h() / dz_);
  const Vec3d o = init.origin;
  origin_z_ = o.z;
  origin_ = o;
  std::vector<std::unique_ptr<geometry::Mesh>> meshes;
  for (const auto& w : c.walls)
    meshes.push_back(w.is_mesh && needs_bed(c)
                         ? std::make_unique<geometry::Mesh>(geometry::load_surface(w.mesh_path, w.terrain, c.domain))
                         : nullptr);
  for (const auto& g : c.gauges) {
    Probe pr{g, static_cast<int>(points_host_.size()), 0, 0, 0};
    names_.push_back(g.name);
    if (g.type == GaugeType::Height) {
      // Sample points up the vertical line, from the bed (the highest upward-facing wall
      // surface on the line, inside the domain) or, with no wall below, the domain bottom.
      double z0 = c.domain.min.z;
      // A moving wall (a gate lifted from the bed) is no bed.
      for (std::size_t w = 0; w < c.walls.size(); ++w) {
        if (c.walls[w].moves()) continue;
        if (const auto bed = geometry::bed_below(c.walls[w], meshes[w].get(), g.x, g.y);
            bed && *bed > z0 && *bed < c.domain.max.z)
          z0 = *bed;
      }
      const int n = static_cast<int>(std::ceil((c.domain.max.z - z0) / dz_)) + 1;
      for (int k = 0; k < n; ++k) points_host_.push_back(Vec3(Vec3d{g.x, g.y, z0 + k * dz_} - o));
      pr.n_samples = n;
    } else if (g.type == GaugeType::Pressure || g.type == GaugeType::Velocity) {
      points_host_.push_back(Vec3(g.at - o));
      pr.n_samples = 1;
    } else if (g.type == GaugeType::Force || g.type == GaugeType::Body) {
      bool found = false;
      for (std::size_t w = 0; w < c.walls.size(); ++w)
        if (c.walls[w].name == g.wall) {
          pr.id0 = init.wall_ids[w].first;
          pr.id1 = init.wall_ids[w].second;
          found = true;
        }
      if (g.type == GaugeType::Body) pr.body = found ? init.body_of(pr.id0) : -1; // -1: a DEM wall's (the caller's)
    }
    probes_.push_back(pr);
  }
  par::upload(points_, points_host_);
  sums_.resize(points_host_.size());
}

std::vector<PointSums> Gauges::point_sums(WcsphSolver& solver, const Distribution& dist) {
  solver.refresh();
  auto p = solver.view();
  const auto g = solver.grid_view();
  const WcsphParams prm = solver.params();
  detail::point_sums(prm, g, p, points_.data(), static_cast<int>(points_host_.size()), sums_.data());
  std::vector<PointSums> sums;
  par::download(sums, sums_, sums_.size());
  if (dist.distributed()) {
    for (std::size_t k = 0; k < sums.size(); ++k)
      if (!dist.owns(points_host_[k])) sums[k] = PointSums{};
    dist.sum(reinterpret_cast<Real*>(sums.data()), kPointSumReals * sums.size());
  }
  return sums;
}

std::vector<Gauges::Column> Gauges::columns(WcsphSolver& solver, const Distribution& dist) {
  const std::vector<PointSums> sums = point_sums(solver, dist);
  std::vector<Column> out(probes_.size());
  for (std::size_t g = 0; g < probes_.size(); ++g) {
    const Probe& pr = probes_[g];
    if (pr.spec.type != GaugeType::Height) continue;
    const Top top = column_top(pr, sums);
    Column& col = out[g];
    col.bed = static_cast<double>(points_host_[pr.first_sample].z) + origin_z_;
    col.top = top.z + origin_z_;
    double w = 0;
    Vec3d wv{};
    for (int k = 0; k <= top.last; ++k) {
      w += static_cast<double>(sums[pr.first_sample + k].vw);
      wv += Vec3d(sums[pr.first_sample + k].vwv);
      col.fluid = std::max(col.fluid, static_cast<double>(sums[pr.first_sample + k].vw));
    }
    if (w > 0) col.velocity = wv * (1.0 / w);
    col.water_top = col.bed;
    for (int k = top.last; k >= 0; --k) {
      const double f = sums[pr.first_sample + k].vw;
      if (f < 0.5) continue;
      const double z = static_cast<double>(points_host_[pr.first_sample + k].z) + origin_z_;
      col.water_top = k == top.last ? col.top : crossing(z, dz_, f, sums[pr.first_sample + k + 1].vw);
      break;
    }
  }
  return out;
}

std::vector<double> Gauges::sample(WcsphSolver& solver, const std::function<double(const GaugeSpec&)>& sphere_value,
                                   const Distribution& dist) {
  const std::vector<PointSums> sums = point_sums(solver, dist);
  std::vector<double> values;
  for (const auto& pr : probes_) {
    const auto& spec = pr.spec;
    double v = 0;
    if (spec.type == GaugeType::Height) {
      v = (spec.surface == "highest" ? highest_wet(pr, sums) : column_top(pr, sums).z) + origin_z_;
    } else if (spec.type == GaugeType::Pressure || spec.type == GaugeType::Velocity) {
      const PointSums& s = sums[pr.first_sample];
      // Shepard normalisation; a point with too little fluid around it reads 0.
      const double w = s.vw;
      if (w > 0.1) {
        if (spec.type == GaugeType::Pressure)
          v = s.vwp / w;
        else {
          const Vec3d vel = Vec3d(s.vwv) * (1.0 / w);
          v = spec.component == "x" ? vel.x : spec.component == "y" ? vel.y : spec.component == "z" ? vel.z : norm(vel);
        }
      }
    } else if (spec.type == GaugeType::Sphere || spec.type == GaugeType::DemWall ||
               (spec.type == GaugeType::Body && pr.body < 0)) {
      v = sphere_value ? sphere_value(spec) : 0.0;
    } else if (spec.type == GaugeType::Body) {
      v = body_value(solver, pr, dist);
    } else {
      const Vec3d fd = wall_load(solver, pr, dist).force;
      v = spec.component == "x" ? fd.x : spec.component == "y" ? fd.y : spec.component == "z" ? fd.z : norm(fd);
    }
    values.push_back(v);
  }
  return values;
}

// Sum of m a over the wall's particles (and of (x - about) x m a), in id order and in
// double: the same value whatever order the particles are stored in and however they are
// distributed.
Gauges::Load Gauges::wall_load(WcsphSolver& solver, const Probe& pr, const Distribution& dist, const Vec3* about) {
  const std::uint32_t id0 = pr.id0, id1 = pr.id1;
  wall_acc_.resize(id1 - id0);
  par::fill(wall_acc_, Vec3{});
  if (about) {
    wall_pos_.resize(id1 - id0);
    par::fill(wall_pos_, Vec3{});
  }
  detail::wall_accelerations(solver.view(), id0, id1, wall_acc_.data(), about ? wall_pos_.data() : nullptr);
  std::vector<Vec3> acc, pos;
  par::download(acc, wall_acc_, wall_acc_.size());
  dist.sum(reinterpret_cast<Real*>(acc.data()), 3 * acc.size());
  if (about) {
    par::download(pos, wall_pos_, wall_pos_.size());
    dist.sum(reinterpret_cast<Real*>(pos.data()), 3 * pos.size());
  }
  // Sums of a (and of arm x a), then times the mass: one mass for every particle.
  Load l;
  for (std::size_t k = 0; k < acc.size(); ++k) {
    l.force += Vec3d(acc[k]);
    if (about) l.moment += cross(Vec3d(pos[k]) - Vec3d(*about), Vec3d(acc[k]));
  }
  const auto m = static_cast<double>(solver.params().mass);
  return {l.force * m, l.moment * m};
}

// A body gauge: its pivot's position (absolute) and velocity, the water's force on it and
// moment about the pivot, or its tilt.
double Gauges::body_value(WcsphSolver& solver, const Probe& pr, const Distribution& dist) {
  const RigidState s = bodies_.at(static_cast<std::size_t>(pr.body));
  const Load l = motion::reads_load(pr.spec.component) ? wall_load(solver, pr, dist, &s.pos) : Load{};
  return motion::body_reading(pr.spec.component, s, origin_, l.force, l.moment);
}

namespace {
// A column's samples within 1.5 dp of the bed's face (dz = dp / 4); the fractions that
// count as water or spheres within reach, and as spheres present (past_pores).
constexpr int kNearFace = 6;
constexpr double kNear = 0.04, kSpheres = 0.1;
} // namespace

// What a wave gauge reads: the top of the water standing on the bed. The samples start at
// the bed's face, where the filled fraction (water and wall together) is about 1/2 when
// dry and near 1 under water; the surface is where the fraction, going up, next falls
// below 0.5, interpolated between samples. Water above an air gap (a sheet thrown over an
// obstacle, spray) is not counted, so a dry bed reads the bed whatever flies above it.
// Within 1.5 spacings of the face a fraction under 0.5 is not an air gap: the fraction at
// the face itself comes out anywhere from 0.45 to 0.55 (a coarse wall, a sloping mesh),
// and water on the bed stands off it by up to 1.5 spacings (the lattice next to a slope,
// the dynamic boundary's gap). The column starts at the highest filled sample there; where
// there is none, spheres on the bed (a deposit held off by the water's stand-off) may fill
// the gap up to the water above them (past_pores).
Gauges::Top Gauges::column_top(const Probe& pr, const std::vector<PointSums>& sums) const {
  const auto filled = [&](int k) {
    const PointSums& s = sums[pr.first_sample + k];
    return static_cast<double>(s.vw + s.vw_solid);
  };
  const auto z = [&](int k) { return static_cast<double>(points_host_[pr.first_sample + k].z); };
  int k = std::min(pr.n_samples - 1, kNearFace);
  while (k >= 0 && filled(k) < 0.5) --k;
  if (k < 0) k = past_pores(pr, sums, first_near(pr, sums)); // spheres on the bed, water above
  if (k < 0) return {z(0), -1};                              // dry
  for (; k + 1 < pr.n_samples; ++k) {
    const double f0 = filled(k), f1 = filled(k + 1);
    if (f1 >= 0.5) continue;
    const int above = past_pores(pr, sums, k + 1);
    if (above < 0) return {crossing(z(k), dz_, f0, f1), k};
    k = above - 1;
  }
  return {z(pr.n_samples - 1), pr.n_samples - 1};
}

// A porous deposit (a slide come to rest, a rock pile) holds water in its pores, but
// coarse SPH water does not enter them: the spheres' body particles fill a third to a
// half of the pile, and the pores and the stand-off between the pile and the water above
// read as gaps. A gap is part of the column when the column is filled again above it,
// every sample in it is within kernel reach of water or spheres (fluid + body fraction
// at least kNear: 0.07 between two layers of spheres beside a line through the pores;
// within the kernel's reach of the bed's face, 2 h, the bed is near, so the gap between
// the bed and spheres held off it is part of the column) and spheres are in it (a body
// fraction of at least kSpheres somewhere).
// Returns that filled sample, or -1 where the gap is air: nothing above it, a stretch
// with nothing near, or no sphere in it (spray, a sheet: read as before, and walls
// farther up do not count, so a line along a wall does not climb it).
int Gauges::past_pores(const Probe& pr, const std::vector<PointSums>& sums, int k) const {
  if (k < 0) return -1;
  bool spheres = false;
  for (; k < pr.n_samples; ++k) {
    const PointSums& s = sums[pr.first_sample + k];
    if (static_cast<double>(s.vw + s.vw_solid) >= 0.5) return spheres ? k : -1;
    if (k >= bed_reach_ && static_cast<double>(s.vw + s.vw_body) < kNear) return -1; // the bed is within reach below
    spheres = spheres || static_cast<double>(s.vw_body) >= kSpheres;
  }
  return -1;
}

// The first of the samples within kNearFace of the bed's face with water or spheres
// within kernel reach (where spheres touch the bed only at points, the line between
// them starts empty); -1 if none.
int Gauges::first_near(const Probe& pr, const std::vector<PointSums>& sums) const {
  for (int k = 0; k <= kNearFace && k < pr.n_samples; ++k) {
    const PointSums& s = sums[pr.first_sample + k];
    if (static_cast<double>(s.vw + s.vw_body) >= kNear) return k;
  }
  return -1;
}

// The highest z where the fluid fraction reaches 0.5, interpolated between samples: the
// surface where the water is one body, but a sheet of spray above it reads as the surface.
// The domain bottom when the line is dry.
double Gauges::highest_wet(const Probe& pr, const std::vector<PointSums>& sums) const {
  for (int k = pr.n_samples - 1; k >= 0; --k) {
    const double f = sums[pr.first_sample + k].vw;
    if (f < 0.5) continue;
    const double z = points_host_[pr.first_sample + k].z;
    if (k + 1 == pr.n_samples) return z;
    return crossing(z, dz_, f, sums[pr.first_sample + k + 1].vw);
  }
  return points_host_[pr.first_sample].z;
}

} // namespace surge::sph
