// s = s0 ln cosh(t / t0), v = (s0 / t0) tanh(t / t0): starts at rest with acceleration
// s0 / t0^2 and tends to the terminal speed s0 / t0 (the law of rigid slides, e.g. Heinrich
// 1992, Grilli & Watts 2005).
#include "surge/core/error.hpp"
#include "surge/motion/motion_law.hpp"

#include <cmath>

namespace surge::motion {
namespace {
class LnCosh final : public MotionLaw {
public:
  LnCosh(const Vec3d& d, double s0, double t0) : d_(d), s0_(s0), t0_(t0) {}
  [[nodiscard]] Pose at(double tau) const override {
    const double x = tau / t0_;
    // ln cosh x = x + ln(1 + e^-2x) - ln 2 for x >= 0: no overflow at large x.
    const double lc = x + std::log1p(std::exp(-2 * x)) - std::log(2.0);
    return along(d_, s0_ * lc, s0_ / t0_ * std::tanh(x));
  }

private:
  Vec3d d_;
  double s0_, t0_;
};
} // namespace

std::unique_ptr<MotionLaw> make_ln_cosh(const MotionSpec& s, const MotionContext& ctx) {
  if (!(s.s0 > 0)) throw InputError(ctx.source, s.line, ctx.key + ".s0", "must be positive");
  if (!(s.t0 > 0)) throw InputError(ctx.source, s.line, ctx.key + ".t0", "must be positive");
  return std::make_unique<LnCosh>(unit(s.direction, ctx, s, "direction"), s.s0, s.t0);
}
} // namespace surge::motion
