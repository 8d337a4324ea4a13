// The rigid-body state of one body as other modules see it: a DEM sphere (for the SPH-DEM
// coupling) or a moving wall (motion/): its reference point, velocities and orientation, and
// the rotation a unit quaternion applies. One view for SPH, DEM and coupling.
#pragma once
#include "surge/core/types.hpp"

namespace surge {

struct RigidState {
  Vec3 pos{}, vel{}, omega{};
  Real q[4] = {1, 0, 0, 0}; // (w, x, y, z), body frame -> world frame
};

// q v q*: rotates a body-frame vector into the world frame (q of unit length).
// Written as v + w t + u x t with t = 2 u x v, which needs no matrix.
[[nodiscard]] SURGE_HD inline Vec3 rotate(const Real* q, const Vec3& v) {
  const Vec3 u{q[1], q[2], q[3]};
  const Vec3 t = cross(u, v) * Real(2);
  return v + t * q[0] + cross(u, t);
}

// World-frame position and velocity of a point attached to the body at body-frame
// offset r0 (SPEC §4, Eq. 25-26 with the exact rigid transform).
struct RigidPoint {
  Vec3 pos, vel;
};
[[nodiscard]] SURGE_HD inline RigidPoint rigid_point(const RigidState& s, const Vec3& r0) {
  const Vec3 arm = rotate(s.q, r0);
  return {s.pos + arm, s.vel + cross(s.omega, arm)};
}

} // namespace surge
