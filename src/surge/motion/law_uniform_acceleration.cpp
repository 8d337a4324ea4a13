// x = v0 t + a t^2 / 2.
#include "surge/motion/motion_law.hpp"

namespace surge::motion {
namespace {
class UniformAcceleration final : public MotionLaw {
public:
  UniformAcceleration(const Vec3d& v0, const Vec3d& a) : v0_(v0), a_(a) {}
  [[nodiscard]] Pose at(double tau) const override {
    Pose p;
    p.shift = v0_ * tau + a_ * (tau * tau / 2);
    p.vel = v0_ + a_ * tau;
    return p;
  }

private:
  Vec3d v0_, a_;
};
} // namespace

std::unique_ptr<MotionLaw> make_uniform_acceleration(const MotionSpec& s, const MotionContext& /*ctx*/) {
  return std::make_unique<UniformAcceleration>(s.velocity, s.acceleration);
}
} // namespace surge::motion
