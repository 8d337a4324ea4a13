// Scalar and vector value types shared by every module, host and device.
#pragma once
#include <cmath>
#include <cstdint>

#if defined(__CUDACC__)
#define SURGE_HD __host__ __device__
#define SURGE_INLINE __forceinline__
#define SURGE_NOINLINE __noinline__
#else
#define SURGE_HD
// Formulas that SIMD code instantiates on vector types must be inlined into it: a copy of
// their own would be compiled for the baseline instruction set (sph/wcsph_rates_simd.cpp).
#define SURGE_INLINE [[gnu::always_inline]] inline
// Rare branches of hot loops kept out of them, so that the loop body stays small enough
// for the compiler to inline it into the neighbour scan.
#define SURGE_NOINLINE [[gnu::noinline]]
#endif

namespace surge {

#if defined(SURGE_REAL_DOUBLE)
using Real = double;
#else
using Real = float;
#endif

template <class T>
struct Vec3T {
  T x{}, y{}, z{};
  SURGE_HD constexpr Vec3T() = default;
  SURGE_HD constexpr Vec3T(T a, T b, T c) : x(a), y(b), z(c) {}
  template <class U>
  SURGE_HD explicit constexpr Vec3T(const Vec3T<U>& o)
      : x(static_cast<T>(o.x)), y(static_cast<T>(o.y)), z(static_cast<T>(o.z)) {}
  SURGE_HD constexpr Vec3T& operator+=(const Vec3T& o) {
    x += o.x;
    y += o.y;
    z += o.z;
    return *this;
  }
  SURGE_HD constexpr Vec3T& operator-=(const Vec3T& o) {
    x -= o.x;
    y -= o.y;
    z -= o.z;
    return *this;
  }
  SURGE_HD constexpr Vec3T& operator*=(T s) {
    x *= s;
    y *= s;
    z *= s;
    return *this;
  }
  SURGE_HD constexpr T operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  SURGE_HD constexpr T& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
};

template <class T>
SURGE_HD constexpr Vec3T<T> operator+(Vec3T<T> a, const Vec3T<T>& b) {
  return a += b;
}
template <class T>
SURGE_HD constexpr Vec3T<T> operator-(Vec3T<T> a, const Vec3T<T>& b) {
  return a -= b;
}
template <class T>
SURGE_HD constexpr Vec3T<T> operator-(const Vec3T<T>& a) {
  return {-a.x, -a.y, -a.z};
}
template <class T>
SURGE_HD constexpr Vec3T<T> operator*(Vec3T<T> a, T s) {
  return a *= s;
}
template <class T>
SURGE_HD constexpr Vec3T<T> operator*(T s, Vec3T<T> a) {
  return a *= s;
}
template <class T>
SURGE_HD constexpr T dot(const Vec3T<T>& a, const Vec3T<T>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class T>
SURGE_HD constexpr Vec3T<T> cross(const Vec3T<T>& a, const Vec3T<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class T>
SURGE_HD inline T norm(const Vec3T<T>& a) {
  return std::sqrt(dot(a, a));
}

using Vec3 = Vec3T<Real>;    // particle data (positions relative to the case origin)
using Vec3d = Vec3T<double>; // case geometry and absolute positions

// Particle kinds (SPEC §1). Removed particles are sorted to the end and dropped.
enum class Kind : std::uint8_t { Fluid = 0, Wall = 1, Body = 2, Removed = 255 };

} // namespace surge
