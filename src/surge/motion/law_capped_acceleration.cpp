// s = a t^2 / 2 until the speed a t reaches the terminal speed v (at t1 = v / a), then
// s = v^2 / (2 a) + v (t - t1).
#include "surge/core/error.hpp"
#include "surge/motion/motion_law.hpp"

namespace surge::motion {
namespace {
class CappedAcceleration final : public MotionLaw {
public:
  CappedAcceleration(const Vec3d& d, double a, double v) : d_(d), a_(a), v_(v) {}
  [[nodiscard]] Pose at(double tau) const override {
    const double t1 = v_ / a_;
    if (tau < t1) return along(d_, a_ * tau * tau / 2, a_ * tau);
    return along(d_, v_ * t1 / 2 + v_ * (tau - t1), v_);
  }

private:
  Vec3d d_;
  double a_, v_;
};
} // namespace

std::unique_ptr<MotionLaw> make_capped_acceleration(const MotionSpec& s, const MotionContext& ctx) {
  if (!(s.accel > 0)) throw InputError(ctx.source, s.line, ctx.key + ".accel", "must be positive");
  if (!(s.terminal > 0)) throw InputError(ctx.source, s.line, ctx.key + ".terminal", "must be positive");
  return std::make_unique<CappedAcceleration>(unit(s.direction, ctx, s, "direction"), s.accel, s.terminal);
}
} // namespace surge::motion
