#include "surge/core/error.hpp"
#include "surge/motion/motion_law.hpp"

namespace surge::motion {

// Each law's factory, in its own file law_<name>.cpp.
std::unique_ptr<MotionLaw> make_constant_velocity(const MotionSpec&, const MotionContext&);
std::unique_ptr<MotionLaw> make_uniform_acceleration(const MotionSpec&, const MotionContext&);
std::unique_ptr<MotionLaw> make_ln_cosh(const MotionSpec&, const MotionContext&);
std::unique_ptr<MotionLaw> make_capped_acceleration(const MotionSpec&, const MotionContext&);
std::unique_ptr<MotionLaw> make_sinusoidal(const MotionSpec&, const MotionContext&);
std::unique_ptr<MotionLaw> make_solitary(const MotionSpec&, const MotionContext&);
std::unique_ptr<MotionLaw> make_time_series(const MotionSpec&, const MotionContext&);

const std::vector<LawEntry>& motion_laws() {
  static const std::vector<LawEntry> laws{
      {"constant_velocity",
       {"velocity"},
       {},
       make_constant_velocity,
       "translation at a constant velocity (a gate lifted)"},
      {"uniform_acceleration",
       {"acceleration"},
       {"velocity"},
       make_uniform_acceleration,
       "translation x = v t + a t^2 / 2"},
      {"ln_cosh",
       {"direction", "s0", "t0"},
       {},
       make_ln_cosh,
       "s = s0 ln cosh(t / t0) along direction: the terminal-velocity law of rigid slides (speed s0 / t0)"},
      {"capped_acceleration",
       {"direction", "accel", "terminal"},
       {},
       make_capped_acceleration,
       "s = accel t^2 / 2 along direction until the speed reaches terminal, then constant speed"},
      {"sinusoidal",
       {"period"},
       {"amplitude", "angle", "axis", "phase"},
       make_sinusoidal,
       "piston (amplitude) or flap (angle about axis through pivot): A (sin(2 pi t / period + phase) - sin phase)"},
      {"solitary",
       {"height", "depth"},
       {"direction"},
       make_solitary,
       "a piston's stroke that makes a solitary wave of that height on still water of that depth (Goring 1978)"},
      {"time_series",
       {"csv"},
       {},
       make_time_series,
       "piecewise linear from a CSV file: t, dx, dy, dz [, rx, ry, rz in degrees about pivot, x then y then z]"},
  };
  return laws;
}

const LawEntry* find_law(const std::string& name) {
  for (const auto& e : motion_laws())
    if (name == e.name) return &e;
  return nullptr;
}

Vec3d unit(const Vec3d& v, const MotionContext& ctx, const MotionSpec& s, const std::string& key) {
  const double n = norm(v);
  if (!(n > 0)) throw InputError(ctx.source, s.line, ctx.key + "." + key, "must not be zero");
  return v * (1 / n);
}

Motion::Motion(const MotionSpec& spec, const MotionContext& ctx) : start_(spec.start) {
  const LawEntry* e = find_law(spec.law);
  if (!e) throw InputError(ctx.source, spec.line, ctx.key + ".law", "unknown motion law '" + spec.law + "'");
  law_ = e->make(spec, ctx);
}

Pose Motion::at(double t) const {
  if (!(t > start_)) return {};
  return law_->at(t - start_);
}

} // namespace surge::motion
