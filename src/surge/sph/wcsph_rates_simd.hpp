// The CPU's pair loop, 8 pairs at a time (wcsph_rates_batched.inc), for the instruction set
// this CPU has: chosen once at run time, so that one binary uses AVX2 where it exists and
// SSE2 (every x86-64 CPU) elsewhere. Both give the same bits (no fused multiply-adds).
// Built where SURGE_SIMD is defined (GCC on x86-64, float, not CUDA).
#pragma once
#include "surge/sph/wcsph_rates.hpp"

#include <cstdint>

namespace surge::sph {

// Computes and stores (store_rates) the rates of particles [begin, end).
using RatesFn = void (*)(const WcsphParams&, const neighbour::GridView&, const particles::ParticleView&,
                         const WallHoldView&, const RatesOut& out, int begin, int end);
// The blocks of particles the solver hands to one call.
constexpr int rates_block = 16;
// Calls f(begin, end) for the blocks of rates_block consecutive particles of [0, n), as the
// batched passes take them (dynamic chunks: a particle's cost varies along the sorted index).
template <class F>
void for_each_rates_block(int n, F f) {
  const int blocks = (n + rates_block - 1) / rates_block;
  par::parallel_for_uneven(blocks, [=](int b) { f(b * rates_block, b + 1 < blocks ? (b + 1) * rates_block : n); });
}

// The batched rates for one instruction set: "avx2" or "sse2"; null for a set this CPU
// lacks or an unknown name.
RatesFn batched_rates(const char* isa);
// What the solver runs: the widest set the CPU has, unless the environment variable
// SURGE_SIMD asks for "sse2" or for the scalar loop ("off": null).
RatesFn batched_rates();
// The name of what batched_rates() runs ("avx2", "sse2" or "off"), for benchmark reports.
const char* batched_rates_name();

// mDBC's boundary densities (mdbc_density.hpp) of the boundary particles among [begin, end),
// their ghost sums 8 neighbours at a time; `offset`: the ghost offsets by id - first_id.
using MdbcFn = void (*)(const WcsphParams&, const neighbour::GridView&, const particles::ParticleView&,
                        const Vec3* offset, std::uint32_t first_id, int begin, int end);
// As batched_rates, for mDBC's densities (the same instruction set).
MdbcFn batched_mdbc(const char* isa);
MdbcFn batched_mdbc();

} // namespace surge::sph
