#include "surge/geometry/sphere_packs.hpp"

#include "surge/core/error.hpp"

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

namespace surge::geometry {

std::vector<SphereSpec> lattice_pack(const Box& box, double radius, double jitter, unsigned seed) {
  std::vector<SphereSpec> out;
  const double d = 2 * radius;
  long n[3];
  for (int k = 0; k < 3; ++k) n[k] = static_cast<long>(std::floor((box.max[k] - box.min[k]) / d + 1e-9));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter * radius, jitter * radius);
  for (long k = 0; k < n[2]; ++k)
    for (long j = 0; j < n[1]; ++j)
      for (long i = 0; i < n[0]; ++i) {
        const Vec3d c{box.min.x + (static_cast<double>(i) + 0.5) * d, box.min.y + (static_cast<double>(j) + 0.5) * d,
                      box.min.z + (static_cast<double>(k) + 0.5) * d};
        out.push_back({c + Vec3d{u(rng), u(rng), u(rng)}, radius});
      }
  return out;
}

std::vector<SphereSpec> read_sphere_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open the sphere list");
  std::vector<SphereSpec> out;
  std::string line;
  int lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    if (const auto h = line.find('#'); h != std::string::npos) line.resize(h);
    for (char& ch : line)
      if (ch == ',' || ch == ';' || ch == '\t') ch = ' ';
    std::istringstream ls(line);
    std::string first;
    if (!(ls >> first)) continue;
    if (out.empty() && (first == "x" || first == "X")) continue; // header
    SphereSpec s{};
    std::istringstream all(line);
    if (!(all >> s.centre.x >> s.centre.y >> s.centre.z >> s.radius) || !std::isfinite(s.radius))
      throw InputError(path, lineno, "", "expected four numbers: x, y, z, r");
    std::string extra;
    if (all >> extra) throw InputError(path, lineno, "", "more than four values on the line");
    if (!(s.radius > 0)) throw InputError(path, lineno, "", "radius must be positive");
    out.push_back(s);
  }
  if (out.empty()) throw InputError(path, 0, "", "the sphere list is empty");
  return out;
}

} // namespace surge::geometry
