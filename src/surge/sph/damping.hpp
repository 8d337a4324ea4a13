// Absorbing zones (damping): near a domain face the water's velocity relaxes towards zero,
// so that a wave running into the zone leaves no reflection and a long tank can be cut
// short. The law is DualSPHysics's damping zone (Altomare et al. 2017): after every step
// v <- v (1 - dt rate s^2), s the depth into the zone over its length (0 at its inner edge,
// 1 at the face), so the relaxation starts smoothly and reaches `rate` at the face.
#pragma once
#include "surge/core/types.hpp"

namespace surge::sph {

struct DampingZone {
  int axis = 0;
  Real inner = 0;  // the zone's inner edge (local coordinate along axis)
  Real length = 1; // signed: > 0 when the zone lies above `inner` (a face xmax, ymax, zmax)
  Real rate = 10;  // [1/s]
  // The factor of this step's velocity at x.
  [[nodiscard]] SURGE_HD Real factor(const Vec3& x, Real dt) const {
    const Real s = (x[axis] - inner) / length;
    if (!(s > 0)) return 1;
    const Real d = s < 1 ? s : Real(1);
    const Real f = 1 - dt * rate * d * d;
    return f > 0 ? f : Real(0);
  }
};

// Every zone of a case (at most one per face), by value, for a kernel to capture.
struct DampingZones {
  int n = 0;
  DampingZone zone[6];
  [[nodiscard]] SURGE_HD Real factor(const Vec3& x, Real dt) const {
    Real f = 1;
    for (int k = 0; k < n; ++k) f *= zone[k].factor(x, dt);
    return f;
  }
};

} // namespace surge::sph
