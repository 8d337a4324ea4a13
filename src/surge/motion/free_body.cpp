#include "surge/motion/free_body.hpp"

#include <cmath>
#include <cstring>
#include <stdexcept>

namespace surge::motion {

namespace {
Vec3d times(const Matrix3& m, const Vec3d& v) {
  return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
          m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}
Quat normalised(const Quat& q) {
  const double n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  return {q.w / n, q.x / n, q.y / n, q.z / n};
}
} // namespace

Matrix3 inverse(const Matrix3& m) {
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  if (!(std::fabs(det) > 0)) throw std::invalid_argument("a body's inertia is singular");
  Matrix3 r;
  r[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) / det;
  r[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
  r[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
  r[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) / det;
  r[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
  r[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
  r[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) / det;
  r[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
  r[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
  return r;
}

FreeBody::FreeBody(const BodySpec& spec, double mass, const Vec3d& centre, const Matrix3& inertia, const Vec3d& gravity)
    : line_(spec.constraint == "line"), mu_s_(spec.mu_static), mu_k_(spec.mu_kinetic), travel_(spec.travel),
      mass_(mass), g_(gravity), x0_(centre), inv_i0_(inverse(inertia)), x_(centre) {
  if (line_) {
    d_ = spec.direction * (1 / norm(spec.direction));
    v_ = d_ * dot(spec.velocity, d_);
  } else {
    v_ = spec.velocity;
    // L = I0 w at placement (body and world axes agree then).
    for (int i = 0; i < 3; ++i)
      l_[i] = inertia[i][0] * spec.spin.x + inertia[i][1] * spec.spin.y + inertia[i][2] * spec.spin.z;
  }
}

Vec3d FreeBody::omega() const {
  // w = R I0^-1 R^T L
  return rotate(q_, times(inv_i0_, rotate_back(q_, l_)));
}

void FreeBody::advance_on_line(const Vec3d& force, double dt) {
  const Vec3d f = force + g_ * mass_;
  const double along = dot(f, d_);
  const double normal = norm(f - d_ * along);
  double v = dot(v_, d_);
  if (travel_ > 0 && dot(x_ - x0_, d_) >= travel_) return; // at the rail's end
  if (v == 0) {
    if (std::fabs(along) <= mu_s_ * normal) return; // held by static friction
    v = dt * (along - std::copysign(mu_k_ * normal, along)) / mass_;
    if (v * along < 0) v = 0; // friction cannot drive it backwards
  } else {
    const double v1 = v + dt * (along - std::copysign(mu_k_ * normal, v)) / mass_;
    v = v1 * v < 0 ? 0 : v1; // stops where the speed would change sign
  }
  v_ = d_ * v;
  x_ += v_ * dt;
  if (travel_ > 0 && dot(x_ - x0_, d_) >= travel_) { // at the rail's end: stopped there
    x_ = x0_ + d_ * travel_;
    v_ = {};
  }
}

void FreeBody::advance(const Vec3d& force, const Vec3d& moment, double dt) {
  if (line_) {
    advance_on_line(force, dt);
    return;
  }
  v_ += (force * (1 / mass_) + g_) * dt;
  x_ += v_ * dt;
  l_ += moment * dt;
  const Vec3d w = omega();
  const double angle = norm(w) * dt;
  if (angle > 0) q_ = normalised(after(axis_angle(w * (1 / norm(w)), angle), q_));
}

Pose FreeBody::pose() const {
  Pose p;
  p.shift = x_ - x0_;
  p.vel = v_;
  p.q = q_;
  p.omega = line_ ? Vec3d{} : omega();
  return p;
}

std::string FreeBody::save() const {
  const double s[13] = {x_.x, x_.y, x_.z, v_.x, v_.y, v_.z, l_.x, l_.y, l_.z, q_.w, q_.x, q_.y, q_.z};
  return {reinterpret_cast<const char*>(s), sizeof s};
}

void FreeBody::restore(const std::string& bytes) {
  double s[13];
  static_assert(sizeof s == state_bytes);
  if (bytes.size() != sizeof s) throw std::invalid_argument("a free body's state has the wrong size");
  std::memcpy(s, bytes.data(), sizeof s);
  x_ = {s[0], s[1], s[2]};
  v_ = {s[3], s[4], s[5]};
  l_ = {s[6], s[7], s[8]};
  q_ = {s[9], s[10], s[11], s[12]};
}

} // namespace surge::motion
