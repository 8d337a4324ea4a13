// x = v t.
#include "surge/motion/motion_law.hpp"

namespace surge::motion {
namespace {
class ConstantVelocity final : public MotionLaw {
public:
  explicit ConstantVelocity(const Vec3d& v) : v_(v) {}
  [[nodiscard]] Pose at(double tau) const override {
    Pose p;
    p.shift = v_ * tau;
    p.vel = v_;
    return p;
  }

private:
  Vec3d v_;
};
} // namespace

std::unique_ptr<MotionLaw> make_constant_velocity(const MotionSpec& s, const MotionContext& /*ctx*/) {
  return std::make_unique<ConstantVelocity>(s.velocity);
}
} // namespace surge::motion
