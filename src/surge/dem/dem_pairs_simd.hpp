// The DEM's pair pass (pass 1 of a step, dem_solver.cpp) on CPUs, with the touching pairs
// evaluated 8 at a time (dem_pairs_batched.inc) by the same pair_terms template as the
// scalar pass, lane by lane with its bits: results do not depend on which pass ran.
// Built where SURGE_SIMD is defined (GCC on x86-64, float, not CUDA).
#pragma once
#include "surge/dem/dem_solver.hpp"

namespace surge::dem {

// The batched pass of contact law `law` (an index into ContactLaws) for instruction set
// `isa` ("avx2" or "sse2"); null for a set this CPU lacks or any other name ("off").
PairPassFn batched_pair_pass(int law, const char* isa);

} // namespace surge::dem
