// Goring's (1978) piston stroke for a solitary wave of height A on still water of depth h:
// the paddle moves with the water under the wave's profile,
//   dX/dt = c eta(X, t) / (h + eta(X, t)),  eta = A sech^2(k (c (t - T/2) - (X - S/2))),
// with k = sqrt(3 A / (4 h^3)), c = sqrt(g (h + A)), stroke S = 2 A / (k h) and duration
// T = 2 (3.8 + A / h) / (k c), after which it stands still. Integrated once here (RK4,
// 20,000 steps) and read back by cubic Hermite interpolation of X with its exact rate.
#include "surge/core/error.hpp"
#include "surge/motion/motion_law.hpp"

#include <cmath>
#include <vector>

namespace surge::motion {
namespace {
class Solitary final : public MotionLaw {
public:
  Solitary(const Vec3d& d, double a, double h, double g) : d_(d), a_(a), h_(h) {
    k_ = std::sqrt(3 * a / (4 * h * h * h));
    c_ = std::sqrt(g * (h + a));
    stroke_ = 2 * a / (k_ * h);
    duration_ = 2 * (3.8 + a / h) / (k_ * c_);
    const int n = 20000;
    dt_ = duration_ / n;
    x_.resize(n + 1);
    v_.resize(n + 1);
    double x = 0;
    for (int i = 0; i <= n; ++i) {
      const double t = i * dt_;
      x_[i] = x;
      v_[i] = rate(t, x);
      if (i == n) break;
      const double k1 = rate(t, x), k2 = rate(t + dt_ / 2, x + dt_ / 2 * k1), k3 = rate(t + dt_ / 2, x + dt_ / 2 * k2),
                   k4 = rate(t + dt_, x + dt_ * k3);
      x += dt_ / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
  }
  [[nodiscard]] Pose at(double tau) const override {
    if (tau >= duration_) return along(d_, x_.back(), 0);
    const auto i = static_cast<std::size_t>(tau / dt_);
    const double s = tau / dt_ - static_cast<double>(i);
    const double x0 = x_[i], x1 = x_[i + 1], m0 = v_[i] * dt_, m1 = v_[i + 1] * dt_;
    const double s2 = s * s, s3 = s2 * s;
    const double x = (2 * s3 - 3 * s2 + 1) * x0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * x1 + (s3 - s2) * m1;
    return along(d_, x, rate(tau, x));
  }

private:
  [[nodiscard]] double rate(double t, double x) const {
    const double ch = std::cosh(k_ * (c_ * (t - duration_ / 2) - (x - stroke_ / 2)));
    const double eta = a_ / (ch * ch);
    return c_ * eta / (h_ + eta);
  }
  Vec3d d_;
  double a_, h_, k_ = 0, c_ = 0, stroke_ = 0, duration_ = 0, dt_ = 0;
  std::vector<double> x_, v_;
};
} // namespace

std::unique_ptr<MotionLaw> make_solitary(const MotionSpec& s, const MotionContext& ctx) {
  if (!(s.depth > 0)) throw InputError(ctx.source, s.line, ctx.key + ".depth", "must be positive");
  if (!(s.height > 0) || s.height > 0.78 * s.depth)
    throw InputError(ctx.source, s.line, ctx.key + ".height",
                     "must be positive and at most 0.78 of the depth (a solitary wave breaks beyond)");
  return std::make_unique<Solitary>(unit(s.direction, ctx, s, "direction"), s.height, s.depth, ctx.g);
}
} // namespace surge::motion
