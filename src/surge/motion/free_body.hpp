// A rigid body that moves under forces (walls[].body): gravity and a force and moment from
// outside (the water's, summed over the body's wall particles), in 6 degrees of freedom or
// along a line with Coulomb friction against it. Host code, double precision, one step per
// SPH step:
//   v+ = v + dt (F / m + g),  x+ = x + dt v+                         (symplectic Euler)
//   L+ = L + dt M,  w+ = R I0^-1 R^T L+,  q+ = exp(w+ dt / 2) q      (angular momentum kept)
// On a line only the force along it accelerates the body; the rest is the rail's reaction
// N = |F_perp|, and friction holds the body while |F_line| <= mu_s N, else acts against the
// motion with mu_k N (a body whose speed would change sign stops and sticks); with a travel,
// it stops for good at the rail's end.
#pragma once
#include "surge/core/case.hpp"
#include "surge/motion/pose.hpp"

#include <array>
#include <string>

namespace surge::motion {

using Matrix3 = std::array<std::array<double, 3>, 3>;

class FreeBody {
public:
  // centre: the centre of mass as placed (absolute); inertia about it, in the axes as placed.
  FreeBody(const BodySpec& spec, double mass, const Vec3d& centre, const Matrix3& inertia, const Vec3d& gravity);
  // One step of dt under `force` and `moment` (about the centre of mass) from outside.
  void advance(const Vec3d& force, const Vec3d& moment, double dt);
  // The pose since placement (the pivot is the centre of mass).
  [[nodiscard]] Pose pose() const;
  [[nodiscard]] double mass() const { return mass_; }
  [[nodiscard]] Vec3d centre() const { return x_; }
  [[nodiscard]] Vec3d momentum() const { return v_ * mass_; }
  [[nodiscard]] Vec3d angular_momentum() const { return l_; } // about the centre of mass
  // The state as bytes (checkpoints: state_bytes each) and back.
  static constexpr std::size_t state_bytes = 13 * sizeof(double);
  [[nodiscard]] std::string save() const;
  void restore(const std::string& bytes);

private:
  [[nodiscard]] Vec3d omega() const; // R I0^-1 R^T L
  void advance_on_line(const Vec3d& force, double dt);
  bool line_ = false;
  Vec3d d_{};
  double mu_s_ = 0, mu_k_ = 0, travel_ = 0;
  double mass_ = 0;
  Vec3d g_{}, x0_{};
  Matrix3 inv_i0_{};
  Vec3d x_{}, v_{}, l_{};
  Quat q_{};
};

// The inverse of a symmetric positive definite 3 x 3 matrix.
[[nodiscard]] Matrix3 inverse(const Matrix3& m);

} // namespace surge::motion
