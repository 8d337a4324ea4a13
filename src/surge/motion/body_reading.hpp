// What a body gauge reads (gauges[].type: body) from a body's rigid state and the force and
// moment on it: the pivot's position (absolute) and velocity, the force and moment (about
// the pivot) components, or its tilt. One formula for the water's bodies and the spheres'.
#pragma once
#include "surge/core/rigid_state.hpp"

#include <cmath>
#include <string>

namespace surge::motion {

// Whether the component reads the force or moment (the caller sums those only then).
[[nodiscard]] inline bool reads_load(const std::string& component) {
  return component[0] == 'f' || component[0] == 'm';
}

// component: x|y|z, vx|vy|vz, fx..fz, mx..mz or tilt (the angle between the body's z
// axis as placed and z, in degrees); origin: local -> absolute.
[[nodiscard]] inline double body_reading(const std::string& component, const RigidState& s, const Vec3d& origin,
                                         const Vec3d& force, const Vec3d& moment) {
  if (component == "tilt") {
    const double qx = s.q[1], qy = s.q[2];
    return std::acos(std::fmax(-1.0, std::fmin(1.0, 1 - 2 * (qx * qx + qy * qy)))) * 180 / M_PI;
  }
  const int axis = component.back() - 'x';
  if (component.size() == 1) return static_cast<double>(s.pos[axis]) + origin[axis];
  if (component[0] == 'v') return s.vel[axis];
  return component[0] == 'f' ? force[axis] : moment[axis];
}

} // namespace surge::motion
