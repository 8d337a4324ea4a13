// Where a moving body is at one time (host, double): its pivot's displacement from where
// the case placed it and a rotation about the pivot, with their rates. A point X0 of the
// body as placed is at pivot0 + shift + R(q) (X0 - pivot0), moving at vel + omega x arm.
#pragma once
#include "surge/core/rigid_state.hpp"
#include "surge/core/types.hpp"

#include <cmath>

namespace surge::motion {

struct Quat {
  double w = 1, x = 0, y = 0, z = 0;
};

// The rotation by `angle` radians about the unit vector `axis`.
inline Quat axis_angle(const Vec3d& axis, double angle) {
  const double s = std::sin(angle / 2);
  return {std::cos(angle / 2), axis.x * s, axis.y * s, axis.z * s};
}
// a then b: the rotation b a.
inline Quat after(const Quat& b, const Quat& a) {
  return {b.w * a.w - b.x * a.x - b.y * a.y - b.z * a.z, b.w * a.x + b.x * a.w + b.y * a.z - b.z * a.y,
          b.w * a.y - b.x * a.z + b.y * a.w + b.z * a.x, b.w * a.z + b.x * a.y - b.y * a.x + b.z * a.w};
}
inline Vec3d rotate(const Quat& q, const Vec3d& v) {
  const Vec3d u{q.x, q.y, q.z};
  const Vec3d t = cross(u, v) * 2.0;
  return v + t * q.w + cross(u, t);
}
inline Vec3d rotate_back(const Quat& q, const Vec3d& v) { return rotate(Quat{q.w, -q.x, -q.y, -q.z}, v); }

struct Pose {
  Vec3d shift{}, vel{}; // the pivot's displacement and velocity
  Quat q{};             // the rotation about the pivot since placement
  Vec3d omega{};        // angular velocity
  [[nodiscard]] bool turned() const { return q.x != 0 || q.y != 0 || q.z != 0; }
  // Where the body point placed at x0 is now (pivot0: the pivot as placed).
  [[nodiscard]] Vec3d place(const Vec3d& pivot0, const Vec3d& x0) const {
    return pivot0 + shift + rotate(q, x0 - pivot0);
  }
  // Where a point now at x was when the body was placed.
  [[nodiscard]] Vec3d unplace(const Vec3d& pivot0, const Vec3d& x) const {
    return pivot0 + rotate_back(q, x - pivot0 - shift);
  }
};

// The pose as the kernels read it: the pivot now (local coordinates) and the rotation.
[[nodiscard]] inline RigidState rigid_state(const Pose& s, const Vec3d& pivot0_local) {
  RigidState r;
  r.pos = Vec3(pivot0_local + s.shift);
  r.vel = Vec3(s.vel);
  r.omega = Vec3(s.omega);
  r.q[0] = static_cast<Real>(s.q.w);
  r.q[1] = static_cast<Real>(s.q.x);
  r.q[2] = static_cast<Real>(s.q.y);
  r.q[3] = static_cast<Real>(s.q.z);
  return r;
}

} // namespace surge::motion
