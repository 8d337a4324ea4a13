// Sorting and scans: the only place Thrust/CUB appear. Implemented in algo.cpp,
// compiled with the OpenMP backend on the CPU build and with nvcc under CUDA.
#pragma once
#include "surge/par/parallel.hpp"

#include <cstdint>

namespace surge::algo {

// Stable sort of keys[0,n) carrying values along.
void sort_by_key(std::uint32_t* keys, std::uint32_t* values, int n);
// values[i] = i
void iota(std::uint32_t* values, int n);
// out[i] = sum of in[0..i) ; returns the total.
std::uint64_t exclusive_scan(const std::uint32_t* in, std::uint32_t* out, int n);

} // namespace surge::algo
