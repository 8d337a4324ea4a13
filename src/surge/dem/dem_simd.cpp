#include "surge/dem/dem_simd.hpp"

#include "surge/dem/integration.hpp"
#include "surge/dem/pair_terms.hpp"
#include "surge/par/simd_isa.hpp"

#include <cstdint>
#include <cstring>
#include <immintrin.h>

// One copy per instruction set (par/simd_copies.inc).
namespace surge::dem {

#define SURGE_BATCH_FILE "surge/dem/dem_batched.inc"
#include "surge/par/simd_copies.inc"
#undef SURGE_BATCH_FILE

PairPassFn batched_pair_pass(int law, const char* isa) {
  if (!par::simd_isa_here(isa)) return nullptr;
  return std::strcmp(isa, "avx2") == 0 ? avx2::pass_of(law, ContactLaws{}) : sse2::pass_of(law, ContactLaws{});
}

IntegrateFn batched_integrate(const char* isa) {
  if (!par::simd_isa_here(isa)) return nullptr;
  return std::strcmp(isa, "avx2") == 0 ? &avx2::integrate_range : &sse2::integrate_range;
}

} // namespace surge::dem
