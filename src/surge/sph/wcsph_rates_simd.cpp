#include "surge/sph/wcsph_rates_simd.hpp"

#include "surge/par/simd_isa.hpp"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <immintrin.h>
#include <limits>
#include <vector>

// Each instruction set's copy lives in its own namespace, compiled under its own target
// options; everything it calls from the headers above is inlined into it (SURGE_INLINE),
// so no function compiled for AVX2 can be picked by the linker for code that runs on a CPU
// without it.
namespace surge::sph {

// Built with GCC only (CMakeLists.txt); the Clang branch lets clang-tidy read the file.
#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2"))), apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx2")
#endif
namespace avx2 {
#define SURGE_BATCH_AVX2 1
#include "surge/sph/wcsph_rates_batched.inc"
#undef SURGE_BATCH_AVX2
} // namespace avx2
#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif

namespace sse2 {
#include "surge/sph/wcsph_rates_batched.inc"
} // namespace sse2

RatesFn batched_rates(const char* isa) {
  if (!par::simd_isa_here(isa)) return nullptr;
  return std::strcmp(isa, "avx2") == 0 ? &avx2::rates_range : &sse2::rates_range;
}

const char* batched_rates_name() { return par::simd_isa(); }

RatesFn batched_rates() {
  static const RatesFn f = batched_rates(batched_rates_name());
  return f;
}

} // namespace surge::sph
