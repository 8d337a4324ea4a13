#include "surge/dem/dem_simd.hpp"

#include "surge/dem/integration.hpp"
#include "surge/dem/pair_terms.hpp"
#include "surge/par/simd_isa.hpp"

#include <cstdint>
#include <cstring>
#include <immintrin.h>

// Each instruction set's copy lives in its own namespace, compiled under its own target
// options, with everything it calls inlined into it (SURGE_INLINE), as in
// sph/wcsph_rates_simd.cpp.
namespace surge::dem {

// Built with GCC only (CMakeLists.txt); the Clang branch lets clang-tidy read the file.
#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2"))), apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx2")
#endif
namespace avx2 {
#define SURGE_BATCH_AVX2 1
#include "surge/dem/dem_batched.inc"
#undef SURGE_BATCH_AVX2
} // namespace avx2
#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif

namespace sse2 {
#include "surge/dem/dem_batched.inc"
} // namespace sse2

PairPassFn batched_pair_pass(int law, const char* isa) {
  if (!par::simd_isa_here(isa)) return nullptr;
  return std::strcmp(isa, "avx2") == 0 ? avx2::pass_of(law, ContactLaws{}) : sse2::pass_of(law, ContactLaws{});
}

IntegrateFn batched_integrate(const char* isa) {
  if (!par::simd_isa_here(isa)) return nullptr;
  return std::strcmp(isa, "avx2") == 0 ? &avx2::integrate_range : &sse2::integrate_range;
}

} // namespace surge::dem
