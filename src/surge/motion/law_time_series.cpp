// A piecewise-linear motion from a CSV file: rows t, dx, dy, dz and optionally rx, ry, rz
// (degrees: the body turned about the pivot's x axis, then y, then z), t increasing, at
// least two rows; '#' starts a comment, a line of names before the first row is skipped. Before the first
// row the first row's pose holds, after the last the last's (velocity zero).
#include "surge/core/error.hpp"
#include "surge/motion/motion_law.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

namespace surge::motion {
namespace {
struct Row {
  double t;
  Vec3d d, r; // displacement [m], angles [rad]
};

Quat euler_xyz(const Vec3d& r) {
  return after(axis_angle({0, 0, 1}, r.z), after(axis_angle({0, 1, 0}, r.y), axis_angle({1, 0, 0}, r.x)));
}
// Angular velocity of R = Rz(c) Ry(b) Rx(a) at angles r turning at rates dr.
Vec3d euler_rate(const Vec3d& r, const Vec3d& dr) {
  const Quat z = axis_angle({0, 0, 1}, r.z), zy = after(z, axis_angle({0, 1, 0}, r.y));
  return rotate(zy, Vec3d{1, 0, 0}) * dr.x + rotate(z, Vec3d{0, 1, 0}) * dr.y + Vec3d{0, 0, 1} * dr.z;
}

class TimeSeries final : public MotionLaw {
public:
  explicit TimeSeries(std::vector<Row> rows) : rows_(std::move(rows)) {}
  [[nodiscard]] Pose at(double tau) const override {
    // The motion starts at `start`: tau counts from there, the table from its own first t.
    const double t = tau + rows_.front().t;
    if (t >= rows_.back().t) return pose(rows_.back().d, rows_.back().r, {}, {});
    const auto it = std::upper_bound(rows_.begin(), rows_.end(), t, [](double v, const Row& r) { return v < r.t; });
    const Row& b = *it;
    const Row& a = *(it - 1);
    const double dt = b.t - a.t, s = (t - a.t) / dt;
    const Vec3d r = a.r + (b.r - a.r) * s;
    return pose(a.d + (b.d - a.d) * s, r, (b.d - a.d) * (1 / dt), (b.r - a.r) * (1 / dt));
  }

private:
  static Pose pose(const Vec3d& d, const Vec3d& r, const Vec3d& v, const Vec3d& dr) {
    Pose p;
    p.shift = d;
    p.vel = v;
    if (r.x != 0 || r.y != 0 || r.z != 0 || dr.x != 0 || dr.y != 0 || dr.z != 0) {
      p.q = euler_xyz(r);
      p.omega = euler_rate(r, dr);
    }
    return p;
  }
  std::vector<Row> rows_;
};

std::vector<Row> read_rows(const std::string& path, const MotionSpec& s, const MotionContext& ctx) {
  std::ifstream in(path);
  if (!in) throw InputError(ctx.source, s.line, ctx.key + ".csv", "cannot read '" + path + "'");
  std::vector<Row> rows;
  std::string line;
  int n = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++n;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream ls(line);
    std::vector<double> v;
    std::string word;
    bool numbers = true;
    while (ls >> word) {
      char* end = nullptr;
      const double x = std::strtod(word.c_str(), &end);
      if (end == word.c_str() || *end != '\0' || !std::isfinite(x)) numbers = false;
      v.push_back(x);
    }
    if (v.empty()) continue;
    if (!numbers) {
      if (rows.empty() && !header) { // a line of names before the first row
        header = true;
        continue;
      }
      throw InputError(path, n, "", "expected numbers: t, dx, dy, dz [, rx, ry, rz]");
    }
    if (v.size() != 4 && v.size() != 7)
      throw InputError(path, n, "",
                       "expected 4 values (t, dx, dy, dz) or 7 (and rx, ry, rz in degrees), found " +
                           std::to_string(v.size()));
    Row r{v[0], {v[1], v[2], v[3]}, {}};
    if (v.size() == 7) r.r = Vec3d{v[4], v[5], v[6]} * (M_PI / 180);
    if (!rows.empty() && !(r.t > rows.back().t))
      throw InputError(path, n, "",
                       "t must increase from row to row (" + std::to_string(r.t) + " follows " +
                           std::to_string(rows.back().t) + ")");
    rows.push_back(r);
  }
  if (rows.size() < 2)
    throw InputError(path, n, "",
                     "a time series needs at least two rows (t, dx, dy, dz), found " + std::to_string(rows.size()));
  return rows;
}
} // namespace

std::unique_ptr<MotionLaw> make_time_series(const MotionSpec& s, const MotionContext& ctx) {
  return std::make_unique<TimeSeries>(read_rows(s.csv_path, s, ctx));
}
} // namespace surge::motion
