// Piston and flap wave-makers: with f(t) = sin(w t + phase) - sin(phase), w = 2 pi / period,
// the pivot moves by amplitude f(t) and the body turns by angle f(t) about axis through the
// pivot (either or both). Starts where the case placed it.
#include "surge/core/error.hpp"
#include "surge/motion/motion_law.hpp"

#include <cmath>

namespace surge::motion {
namespace {
class Sinusoidal final : public MotionLaw {
public:
  Sinusoidal(const Vec3d& amplitude, double angle, const Vec3d& axis, double period, double phase)
      : a_(amplitude), angle_(angle), axis_(axis), w_(2 * M_PI / period), phase_(phase) {}
  [[nodiscard]] Pose at(double tau) const override {
    const double f = std::sin(w_ * tau + phase_) - std::sin(phase_), df = w_ * std::cos(w_ * tau + phase_);
    Pose p;
    p.shift = a_ * f;
    p.vel = a_ * df;
    if (angle_ != 0) {
      p.q = axis_angle(axis_, angle_ * f);
      p.omega = axis_ * (angle_ * df);
    }
    return p;
  }

private:
  Vec3d a_;
  double angle_;
  Vec3d axis_;
  double w_, phase_;
};
} // namespace

std::unique_ptr<MotionLaw> make_sinusoidal(const MotionSpec& s, const MotionContext& ctx) {
  if (!(s.period > 0)) throw InputError(ctx.source, s.line, ctx.key + ".period", "must be positive");
  if (norm(s.amplitude) == 0 && s.angle == 0)
    throw InputError(ctx.source, s.line, ctx.key,
                     "a sinusoidal motion needs an amplitude (a piston) or an angle (a flap), not zero");
  const Vec3d axis = s.angle != 0 ? unit(s.axis, ctx, s, "axis") : s.axis;
  return std::make_unique<Sinusoidal>(s.amplitude, s.angle * M_PI / 180, axis, s.period, s.phase * M_PI / 180);
}
} // namespace surge::motion
