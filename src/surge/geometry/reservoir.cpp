#include "surge/geometry/reservoir.hpp"

#include "surge/geometry/particle_generators.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

namespace surge::geometry {

bool keeps_water_out(const WallSpec& w, const Mesh* mesh, const Vec3d& p, double dp) {
  if (w.is_mesh || w.solid) return blocked_by(w, mesh, p, dp, 0.0);
  return !w.box.contains(p, -0.5 * dp * (1 - 1e-6));
}

Vec3d lattice_origin(const Case& c) {
  Vec3d o = c.domain.min;
  for (const auto& f : c.fluid)
    if (f.reservoir) {
      o.z = f.level - std::ceil((f.level - c.domain.min.z) / c.dp - 1e-9) * c.dp;
      break;
    }
  return o;
}

ReservoirFill fill_reservoir(const FluidRegion& f, const Box& domain, const Vec3d& origin, double dp,
                             const std::function<bool(const Vec3d&)>& blocked) {
  ReservoirFill out;
  // Lattice indices [first, last) whose points lie in [lo, hi].
  auto first = [&](double lo, double o) { return static_cast<long>(std::ceil((lo - o) / dp - 0.5 - 1e-9)); };
  auto last = [&](double hi, double o) { return static_cast<long>(std::floor((hi - o) / dp - 0.5 + 1e-9)) + 1; };
  const long ix = first(domain.min.x, origin.x), iy = first(domain.min.y, origin.y), iz = first(domain.min.z, origin.z);
  const long nx = last(domain.max.x, origin.x) - ix, ny = last(domain.max.y, origin.y) - iy;
  // The top layer's centre half a spacing below the level.
  const long nz = last(std::min(f.level - 0.5 * dp, domain.max.z), origin.z) - iz;
  auto at = [&](long i, long j, long k) {
    return Vec3d{origin.x + (static_cast<double>(ix + i) + 0.5) * dp,
                 origin.y + (static_cast<double>(iy + j) + 0.5) * dp,
                 origin.z + (static_cast<double>(iz + k) + 0.5) * dp};
  };
  const long si = std::clamp(static_cast<long>(std::floor((f.seed_x - origin.x) / dp)) - ix, 0L, std::max(nx - 1, 0L));
  const long sj = std::clamp(static_cast<long>(std::floor((f.seed_y - origin.y) / dp)) - iy, 0L, std::max(ny - 1, 0L));
  if (nx < 1 || ny < 1 || nz < 1 || blocked(at(si, sj, nz - 1))) {
    char msg[200];
    std::snprintf(msg, sizeof msg,
                  "the seed point (%.3f, %.3f) is on dry land: the ground or a wall there reaches "
                  "above the level minus dp/2",
                  f.seed_x, f.seed_y);
    out.seed_problem = msg;
    return out;
  }
  // 0 unvisited, 1 water, 2 blocked; a stack of cells to visit (depth first, the same
  // set as any order).
  const auto n = static_cast<std::size_t>(nx * ny * nz);
  std::vector<std::uint8_t> state(n, 0);
  auto index = [&](long i, long j, long k) { return static_cast<std::size_t>((k * ny + j) * nx + i); };
  std::vector<std::size_t> stack{index(si, sj, nz - 1)};
  state[stack.back()] = 1;
  while (!stack.empty()) {
    const std::size_t c = stack.back();
    stack.pop_back();
    const long i = static_cast<long>(c % static_cast<std::size_t>(nx));
    const long j = static_cast<long>((c / static_cast<std::size_t>(nx)) % static_cast<std::size_t>(ny));
    const long k = static_cast<long>(c / static_cast<std::size_t>(nx * ny));
    const long nb[6][3] = {{i - 1, j, k}, {i + 1, j, k}, {i, j - 1, k}, {i, j + 1, k}, {i, j, k - 1}, {i, j, k + 1}};
    for (const auto& q : nb) {
      if (q[0] < 0 || q[0] >= nx || q[1] < 0 || q[1] >= ny || q[2] < 0 || q[2] >= nz) continue;
      const std::size_t d = index(q[0], q[1], q[2]);
      if (state[d] != 0) continue;
      state[d] = blocked(at(q[0], q[1], q[2])) ? 2 : 1;
      if (state[d] == 1) stack.push_back(d);
    }
  }
  std::vector<std::uint8_t> wet_column(static_cast<std::size_t>(nx * ny), 0);
  for (long k = 0; k < nz; ++k)
    for (long j = 0; j < ny; ++j)
      for (long i = 0; i < nx; ++i)
        if (state[index(i, j, k)] == 1) {
          out.points.push_back(at(i, j, k));
          wet_column[static_cast<std::size_t>(j * nx + i)] = 1;
        }
  for (const auto w : wet_column) out.columns += w;
  // Columns with a dry column (or the lattice's edge) within 2 dp: where the lake is this
  // narrow, fewer than four particles span it.
  auto wet = [&](long i, long j) {
    return i >= 0 && j >= 0 && i < nx && j < ny && wet_column[static_cast<std::size_t>(j * nx + i)] != 0;
  };
  for (long j = 0; j < ny; ++j)
    for (long i = 0; i < nx; ++i) {
      if (!wet(i, j)) continue;
      bool shore = false;
      for (long b = -2; b <= 2 && !shore; ++b)
        for (long a = -2; a <= 2 && !shore; ++a) shore = a * a + b * b <= 4 && !wet(i + a, j + b);
      out.near_shore += shore ? 1 : 0;
    }
  return out;
}

} // namespace surge::geometry
