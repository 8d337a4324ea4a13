// The DEM's pair pass (pass 1 of a step, dem_solver.cpp) and integration on CPUs, 8 pairs
// or spheres at a time (dem_batched.inc), by the same templates as the scalar passes
// (pair_terms.hpp, integration.hpp), lane by lane with their bits: results do not depend
// on which pass ran.
// Built where SURGE_SIMD is defined (GCC on x86-64, float, not CUDA).
#pragma once
#include "surge/dem/dem_solver.hpp"

namespace surge::dem {

// The batched pair pass of contact law `law` (an index into ContactLaws) for instruction
// set `isa` ("avx2" or "sse2"); null for a set this CPU lacks or any other name ("off").
PairPassFn batched_pair_pass(int law, const char* isa);
// The batched integration, likewise.
IntegrateFn batched_integrate(const char* isa);

} // namespace surge::dem
