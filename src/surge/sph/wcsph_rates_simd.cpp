#include "surge/sph/wcsph_rates_simd.hpp"

#include "surge/par/simd_isa.hpp"
#include "surge/sph/boundary/mdbc_density.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <immintrin.h>
#include <limits>
#include <new>
#include <vector>

// One copy per instruction set (par/simd_copies.inc).
namespace surge::sph {

#define SURGE_BATCH_FILE "surge/sph/wcsph_rates_batched.inc"
#include "surge/par/simd_copies.inc"
#undef SURGE_BATCH_FILE

RatesFn batched_rates(const char* isa) {
  if (!par::simd_isa_here(isa)) return nullptr;
  return std::strcmp(isa, "avx2") == 0 ? &avx2::rates_range : &sse2::rates_range;
}

const char* batched_rates_name() { return par::simd_isa(); }

RatesFn batched_rates() {
  static const RatesFn f = batched_rates(batched_rates_name());
  return f;
}

MdbcFn batched_mdbc(const char* isa) {
  if (!par::simd_isa_here(isa)) return nullptr;
  return std::strcmp(isa, "avx2") == 0 ? &avx2::mdbc_range : &sse2::mdbc_range;
}

MdbcFn batched_mdbc() {
  static const MdbcFn f = batched_mdbc(batched_rates_name());
  return f;
}

} // namespace surge::sph
