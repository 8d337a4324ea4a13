#include "surge/dem/contact_hertz_mindlin.hpp"

#include <algorithm>
#include <map>
#include <mutex>

namespace surge::dem {

namespace {
// The impact u'' = -F, F = max(0, u^(3/2) + alpha u^(1/4) u'), from u = 0, u' = 1, by
// classical Runge-Kutta with a step of 1e-4 (the undamped contact lasts 3.2); the contact
// ends when u returns to 0 or when F vanishes while the spheres part (after that they
// move apart freely). Returns the parting speed.
double rebound(double alpha) {
  auto acc = [alpha](double u, double du) {
    const double up = std::max(u, 0.0);
    return -std::max(0.0, up * std::sqrt(up) + alpha * std::sqrt(std::sqrt(up)) * du);
  };
  const double h = 1e-4;
  double u = 0, du = 1;
  for (int k = 0; k < 10000000; ++k) {
    const double a1 = acc(u, du);
    const double a2 = acc(u + h / 2 * du, du + h / 2 * a1);
    const double a3 = acc(u + h / 2 * (du + h / 2 * a1), du + h / 2 * a2);
    const double a4 = acc(u + h * (du + h / 2 * a2), du + h * a3);
    u += h * (du + h / 6 * (a1 + a2 + a3));
    du += h / 6 * (a1 + 2 * a2 + 2 * a3 + a4);
    if (u <= 0 || (du < 0 && acc(u, du) == 0)) break;
  }
  return -du;
}
} // namespace

double hertz_restitution(double alpha) { return rebound(alpha); }

double hertz_damping_factor(double restitution) {
  if (restitution >= 1) return 0;
  // Solved once per value (about 0.1 s each; a case builds its solver more than once).
  static std::mutex m;
  static std::map<double, double> solved;
  const std::lock_guard lock(m);
  if (const auto it = solved.find(restitution); it != solved.end()) return it->second;
  // The rebound falls as alpha rises; bisection to 1e-6 of the restitution.
  double lo = 0, hi = 1;
  while (rebound(hi) > restitution) hi *= 2;
  for (int k = 0; k < 60 && hi - lo > 1e-7 * hi; ++k) {
    const double mid = (lo + hi) / 2;
    (rebound(mid) > restitution ? lo : hi) = mid;
  }
  return solved[restitution] = (lo + hi) / 2;
}

} // namespace surge::dem
