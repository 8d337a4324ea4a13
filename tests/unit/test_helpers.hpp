// Small cases for tests, built in memory.
#pragma once
#include "surge/io/case_reader.hpp"
#include "surge/neighbour/uniform_grid.hpp"
#include "surge/particles/particle_store.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

namespace surge::test {

// A tilted plane z = z0 + slope x, normal up, as an ascii STL over x, y in [-0.05, 0.35].
inline std::string write_slope(double z0, double slope) {
  const auto path = std::filesystem::temp_directory_path() / ("surge_slope_" + std::to_string(::getpid()) + ".stl");
  auto z = [&](double x) { return std::to_string(z0 + slope * x); };
  const std::string a = "-0.05 -0.05 " + z(-0.05), b = "0.35 -0.05 " + z(0.35), c = "0.35 0.15 " + z(0.35),
                    d = "-0.05 0.15 " + z(-0.05);
  std::ofstream f(path);
  f << "solid slope\n"
    << " facet normal 0 0 1\n  outer loop\n   vertex " << a << "\n   vertex " << b << "\n   vertex " << c
    << "\n  endloop\n endfacet\n"
    << " facet normal 0 0 1\n  outer loop\n   vertex " << a << "\n   vertex " << c << "\n   vertex " << d
    << "\n  endloop\n endfacet\nendsolid slope\n";
  return path.string();
}

// The paper's scheme, which tests of the dynamic boundary name (the defaults are mDBC,
// laminar viscosity and fickian shifting since issue 35).
inline const std::string paper_scheme = "sph: {boundary: dynamic, viscosity: artificial, shifting: none}\n";

// A closed tank holding a water block; `shift` translates the whole case.
inline std::string tank_case(double dp, double shift = 0.0, const std::string& extra = "") {
  auto v = [&](double x, double y, double z) {
    return "[" + std::to_string(x + shift) + ", " + std::to_string(y + shift) + ", " + std::to_string(z + shift) + "]";
  };
  return "name: tank\n"
         "dp: " +
         std::to_string(dp) +
         "\n"
         "time: {end: 0.1, output_every: 0.05}\n"
         "domain: {min: " +
         v(0, 0, 0) + ", max: " + v(0.2, 0.1, 0.3) +
         "}\n"
         "fluid: [{box: {min: " +
         v(0, 0, 0) + ", max: " + v(0.08, 0.1, 0.16) +
         "}}]\n"
         "walls: [{name: tank, box: {min: " +
         v(0, 0, 0) + ", max: " + v(0.2, 0.1, 0.3) + "}, open: [zmax]}]\n" + extra;
}

// Still water 0.2 m deep in a closed 0.1 x 0.1 x 0.3 m tank at dp = 0.01, with a pressure
// probe 2 cm above the floor (gauge 0) and a height gauge in the middle (gauge 1).
inline std::string hydrostatic_tank_case(const std::string& boundary = "dynamic") {
  return "name: hydro\ndp: 0.01\ndomain: {min: [0,0,0], max: [0.1,0.1,0.3]}\nsph: {boundary: " + boundary +
         "}\n"
         "fluid: [{box: {min: [0,0,0], max: [0.1,0.1,0.2]}}]\n"
         "walls: [{name: tank, box: {min: [0,0,0], max: [0.1,0.1,0.3]}}]\n"
         "gauges: [{name: P, type: pressure, at: [0.05, 0.05, 0.02]}, {name: H, type: height, x: 0.05, y: 0.05}]\n";
}

// Neighbour ids of every particle, indexed by particle id, sorted; gathered by a
// parallel loop in the execution space so that the test runs on every backend.
inline std::vector<std::vector<std::uint32_t>> neighbour_ids(const neighbour::GridView& g,
                                                             const particles::ParticleView& v, Real radius) {
  constexpr int cap = 512;
  const int n = v.n;
  par::Buffer<std::uint32_t> ids(static_cast<std::size_t>(n) * cap);
  par::Buffer<int> counts(static_cast<std::size_t>(n));
  std::uint32_t* out = ids.data();
  int* cnt = counts.data();
  const Real r2 = radius * radius;
  par::parallel_for(
      n, SURGE_LAMBDA(int i) {
        int c = 0;
        neighbour::for_each_neighbour(g, v.pos[i], r2, [&](int j, const Vec3&, Real) {
          if (c < cap) out[static_cast<std::size_t>(i) * cap + c] = v.id[j];
          ++c;
        });
        cnt[i] = c;
      });
  const auto h_ids = par::download(ids);
  const auto h_cnt = par::download(counts);
  std::vector<std::uint32_t> own(static_cast<std::size_t>(n));
  if (n > 0) {
    par::Buffer<std::uint32_t> own_buf(static_cast<std::size_t>(n));
    std::uint32_t* o = own_buf.data();
    const std::uint32_t* id = v.id;
    par::parallel_for(
        n, SURGE_LAMBDA(int i) { o[i] = id[i]; });
    own = par::download(own_buf);
  }
  std::uint32_t max_id = 0;
  for (auto x : own) max_id = std::max(max_id, x);
  std::vector<std::vector<std::uint32_t>> result(n > 0 ? max_id + 1 : 0);
  for (int i = 0; i < n; ++i) {
    if (h_cnt[i] > cap) throw std::runtime_error("neighbour_ids: more than 512 neighbours");
    auto& l = result[own[i]];
    l.assign(h_ids.begin() + static_cast<long>(i) * cap, h_ids.begin() + static_cast<long>(i) * cap + h_cnt[i]);
    std::sort(l.begin(), l.end());
  }
  return result;
}

} // namespace surge::test
