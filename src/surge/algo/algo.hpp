// Sorting and scans: the only place Thrust/CUB appear. Implemented in algo.cpp: the sort is
// CUB's radix sort under nvcc and surge's own radix sort on CPUs (Thrust's OpenMP sort took
// twice as long and allocated its scratch on every call); the scan is Thrust's on CPUs.
#pragma once
#include "surge/par/parallel.hpp"

#include <cstddef>
#include <cstdint>

namespace surge::algo {

// Stable sort of keys[0,n) carrying values along; every key is <= max_key (the sorts
// only look at the bits max_key needs). The GPU path keeps its scratch between calls: no
// allocation once the particle count has been reached. The CPU path (a least-significant-
// digit radix sort, 11-bit digits, a block of the array per thread) works in `scratch` when
// it holds `scratch_bytes` >= n keys and n values, else in memory of its own for the call.
void sort_by_key(std::uint32_t* keys, std::uint32_t* values, int n, std::uint32_t max_key, void* scratch = nullptr,
                 std::size_t scratch_bytes = 0);
// The same with 64-bit keys: (cell key << 32 | particle id) orders each cell's particles
// by id, an order that does not depend on how the particles were stored before.
void sort_by_key(std::uint64_t* keys, std::uint32_t* values, int n, std::uint64_t max_key, void* scratch = nullptr,
                 std::size_t scratch_bytes = 0);
// out[i] = in[0] + ... + in[i-1]; returns the sum of all n (a copy to the host: a
// synchronisation on the GPU). out may be in.
std::uint32_t exclusive_scan(const std::uint32_t* in, std::uint32_t* out, int n);
// values[i] = i
void iota(std::uint32_t* values, int n);

} // namespace surge::algo
