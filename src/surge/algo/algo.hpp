// Sorting: the only place Thrust/CUB appear. Implemented in algo.cpp, compiled with
// Thrust's OpenMP backend on the CPU build and as CUB's radix sort under nvcc.
#pragma once
#include "surge/par/parallel.hpp"

#include <cstdint>

namespace surge::algo {

// Stable sort of keys[0,n) carrying values along; every key is <= max_key (the GPU
// sort only looks at the bits max_key needs). The GPU path keeps its scratch between
// calls: no allocation once the particle count has been reached.
void sort_by_key(std::uint32_t* keys, std::uint32_t* values, int n, std::uint32_t max_key);
// The same with 64-bit keys: (cell key << 32 | particle id) orders each cell's particles
// by id, an order that does not depend on how the particles were stored before.
void sort_by_key(std::uint64_t* keys, std::uint32_t* values, int n, std::uint64_t max_key);
// out[i] = in[0] + ... + in[i-1]; returns the sum of all n (a copy to the host: a
// synchronisation on the GPU). out may be in.
std::uint32_t exclusive_scan(const std::uint32_t* in, std::uint32_t* out, int n);
// values[i] = i
void iota(std::uint32_t* values, int n);

} // namespace surge::algo
