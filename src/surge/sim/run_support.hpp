// Small helpers shared by the SPH and DEM run loops.
#pragma once
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <sys/resource.h>
#include <vector>

namespace surge::sim {

inline std::string hms(double s) {
  if (!std::isfinite(s) || s < 0) return "--:--:--";
  const long t = std::lround(s);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%02ld:%02ld:%02ld", t / 3600, (t / 60) % 60, t % 60);
  return buf;
}

inline double peak_rss_bytes() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) * 1024.0;
}

inline std::string json_escape(const std::string& s) {
  std::string out;
  for (char ch : s) {
    if (ch == '"' || ch == '\\') out += '\\';
    if (ch == '\n') {
      out += "\\n";
      continue;
    }
    out += ch;
  }
  return out;
}

// gauges.csv: a header of names after "time", one row per sample.
inline std::string csv_text(const std::vector<std::string>& names, const std::vector<std::vector<double>>& rows) {
  std::ostringstream s;
  s.precision(9);
  s << "time";
  for (const auto& n : names) s << "," << n;
  s << "\n";
  for (const auto& r : rows) {
    for (std::size_t k = 0; k < r.size(); ++k) s << (k ? "," : "") << r[k];
    s << "\n";
  }
  return s.str();
}

// When a checkpoint is due between outputs: every `every_s` seconds of wall time since
// the last one written (time.checkpoint_every_wall; 0: never).
class WallCheckpoints {
public:
  explicit WallCheckpoints(double every_s) : every_s_(every_s) {}
  [[nodiscard]] bool due() const {
    return every_s_ > 0 && std::chrono::duration<double>(std::chrono::steady_clock::now() - last_).count() >= every_s_;
  }
  void written() { last_ = std::chrono::steady_clock::now(); }

private:
  double every_s_;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

} // namespace surge::sim
