// A symmetric 3 x 3 tensor by its six components: the strain rate S or the SPS stress
// tau/rho (sph/sps_turbulence.hpp). T = Real, or a batch of Reals (core/lanes.hpp).
#pragma once
#include "surge/core/types.hpp"

namespace surge {

template <class T>
struct SymTensorT {
  T xx{}, yy{}, zz{}, xy{}, xz{}, yz{};
  // The tensor times the vector g.
  [[nodiscard]] SURGE_HD Vec3T<T> dot(const Vec3T<T>& g) const {
    return {xx * g.x + xy * g.y + xz * g.z, xy * g.x + yy * g.y + yz * g.z, xz * g.x + yz * g.y + zz * g.z};
  }
  // The tensor seen in a frame mirrored on the axes whose bits are set in `m` (1 x,
  // 2 y, 4 z): an off-diagonal component changes sign when one of its two axes is mirrored.
  [[nodiscard]] SURGE_HD SymTensorT mirrored(unsigned m) const {
    const auto sign = [m](unsigned a, unsigned b) { return ((m >> a) ^ (m >> b)) & 1U ? T{} - 1 : T{} + 1; };
    return {xx, yy, zz, xy * sign(0, 1), xz * sign(0, 2), yz * sign(1, 2)};
  }
};

using SymTensor = SymTensorT<Real>;

} // namespace surge
