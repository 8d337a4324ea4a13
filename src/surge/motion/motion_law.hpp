// Prescribed motion laws, chosen by name (walls[].motion.law). A law is a pure function of
// time: the pose of its body (pose.hpp) at any t, so a restart at t places the body as the
// straight run did, bit for bit, and nothing is integrated or drifts.
//
// Adding a law: one file `law_<name>.cpp` with its class and its `make_<name>` factory, and
// one line in the registry (motion_laws.cpp: its name, the keys it requires and the ones
// it accepts, a line of help). The reader checks the keys against the entry, `surge keys`
// and docs/case_reference.md list it.
#pragma once
#include "surge/core/case.hpp"
#include "surge/motion/pose.hpp"

#include <memory>
#include <string>
#include <vector>

namespace surge::motion {

// What a law may need beyond its keys.
struct MotionContext {
  double g = 9.81;    // gravity's magnitude (the solitary wave's celerity)
  std::string source; // the case file, for messages
  std::string key;    // "walls.2.motion", for messages
};

class MotionLaw {
public:
  virtual ~MotionLaw() = default;
  // The pose tau = t - start after the motion began (tau >= 0).
  [[nodiscard]] virtual Pose at(double tau) const = 0;
};

struct LawEntry {
  const char* name;
  std::vector<std::string> required, optional; // keys of walls[].motion besides law, start and pivot
  std::unique_ptr<MotionLaw> (*make)(const MotionSpec&, const MotionContext&);
  const char* help;
};
// Every law, in the order of the reference.
const std::vector<LawEntry>& motion_laws();
[[nodiscard]] const LawEntry* find_law(const std::string& name);

// A wall's motion as the run reads it: at rest (the identity pose) before `start`.
class Motion {
public:
  Motion(const MotionSpec& spec, const MotionContext& ctx);
  [[nodiscard]] Pose at(double t) const;

private:
  double start_ = 0;
  std::unique_ptr<MotionLaw> law_;
};

// The pivot of a wall moved by a law (an SPH wall or a DEM plane or mesh): as given, else
// the centre of what it fills as placed (a free body's pivot is its centre of mass).
[[nodiscard]] inline Vec3d law_pivot(const MotionSpec& m, const Box& placed) {
  return m.pivot_given ? m.pivot : (placed.min + placed.max) * 0.5;
}

// Shared by the laws that move along a line: the pose of displacement s and speed v along
// the unit vector d.
[[nodiscard]] inline Pose along(const Vec3d& d, double s, double v) {
  Pose p;
  p.shift = d * s;
  p.vel = d * v;
  return p;
}
// The unit vector of `v`; throws InputError naming `key` when it is zero.
[[nodiscard]] Vec3d unit(const Vec3d& v, const MotionContext& ctx, const MotionSpec& s, const std::string& key);

} // namespace surge::motion
