#include "surge/algo/algo.hpp"

#include <thrust/execution_policy.h>
#include <thrust/scan.h>
#include <thrust/sequence.h>
#include <thrust/sort.h>

namespace surge::algo {

void sort_by_key(std::uint32_t* keys, std::uint32_t* values, int n) {
  if (n <= 1) return;
  thrust::stable_sort_by_key(thrust::device, keys, keys + n, values);
}

void iota(std::uint32_t* values, int n) {
  if (n <= 0) return;
  thrust::sequence(thrust::device, values, values + n, 0U);
}

std::uint64_t exclusive_scan(const std::uint32_t* in, std::uint32_t* out, int n) {
  if (n <= 0) return 0;
  std::uint32_t last_in = 0;
  std::uint32_t last_out = 0;
  thrust::exclusive_scan(thrust::device, in, in + n, out, 0U);
#if defined(SURGE_BACKEND_CUDA)
  par::check_cuda(cudaMemcpy(&last_in, in + n - 1, sizeof(last_in), cudaMemcpyDeviceToHost), "scan");
  par::check_cuda(cudaMemcpy(&last_out, out + n - 1, sizeof(last_out), cudaMemcpyDeviceToHost), "scan");
#else
  last_in = in[n - 1];
  last_out = out[n - 1];
#endif
  return static_cast<std::uint64_t>(last_in) + last_out;
}

} // namespace surge::algo
