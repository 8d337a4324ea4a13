#include "surge/algo/algo.hpp"

#include <bit>

#if defined(SURGE_BACKEND_CUDA)
#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_scan.cuh>
#else
#include <thrust/execution_policy.h>
#include <thrust/scan.h>
#include <thrust/sort.h>
#endif

namespace surge::algo {

#if defined(SURGE_BACKEND_CUDA)
namespace {
// Scratch of the radix sort, grown to the largest sort seen and kept.
template <class K>
struct SortScratch {
  par::Buffer<K> keys;
  par::Buffer<std::uint32_t> values;
  par::Buffer<unsigned char> temp;
};
template <class K>
SortScratch<K>& scratch() {
  static auto* s = new SortScratch<K>; // never freed: device memory goes with the process
  return *s;
}

template <class K>
void radix_sort(K* keys, std::uint32_t* values, int n, K max_key) {
  if (n <= 1) return;
  SortScratch<K>& s = scratch<K>();
  const auto un = static_cast<std::size_t>(n);
  if (s.keys.size() < un) {
    s.keys.resize(un);
    s.values.resize(un);
  }
  const int end_bit = std::max(1, static_cast<int>(std::bit_width(max_key)));
  // Double buffers: CUB ping-pongs between the caller's arrays and the scratch, so its
  // temporary storage stays small (no third copy of keys and values).
  cub::DoubleBuffer<K> k(keys, s.keys.data());
  cub::DoubleBuffer<std::uint32_t> v(values, s.values.data());
  std::size_t temp_bytes = 0;
  par::check_cuda(cub::DeviceRadixSort::SortPairs(nullptr, temp_bytes, k, v, n, 0, end_bit), "radix sort size");
  if (s.temp.size() < temp_bytes) s.temp.resize(temp_bytes);
  par::check_cuda(cub::DeviceRadixSort::SortPairs(s.temp.data(), temp_bytes, k, v, n, 0, end_bit), "radix sort");
  // The callers own their arrays: copy back when the result ended in the scratch.
  if (k.Current() != keys)
    par::check_cuda(cudaMemcpyAsync(keys, k.Current(), un * sizeof(K), cudaMemcpyDeviceToDevice), "radix sort copy");
  if (v.Current() != values)
    par::check_cuda(cudaMemcpyAsync(values, v.Current(), un * sizeof(std::uint32_t), cudaMemcpyDeviceToDevice),
                    "radix sort copy");
}
} // namespace

void sort_by_key(std::uint32_t* keys, std::uint32_t* values, int n, std::uint32_t max_key) {
  radix_sort(keys, values, n, max_key);
}
void sort_by_key(std::uint64_t* keys, std::uint32_t* values, int n, std::uint64_t max_key) {
  radix_sort(keys, values, n, max_key);
}

std::uint32_t exclusive_scan(const std::uint32_t* in, std::uint32_t* out, int n) {
  if (n <= 0) return 0;
  std::uint32_t last_in = 0, last_out = 0;
  par::check_cuda(cudaMemcpy(&last_in, in + n - 1, sizeof last_in, cudaMemcpyDeviceToHost), "scan");
  static auto* temp = new par::Buffer<unsigned char>; // kept, like the sort's scratch
  std::size_t bytes = 0;
  par::check_cuda(cub::DeviceScan::ExclusiveSum(nullptr, bytes, in, out, n), "scan size");
  if (temp->size() < bytes) temp->resize(bytes);
  par::check_cuda(cub::DeviceScan::ExclusiveSum(temp->data(), bytes, in, out, n), "scan");
  par::check_cuda(cudaMemcpy(&last_out, out + n - 1, sizeof last_out, cudaMemcpyDeviceToHost), "scan");
  return last_out + last_in;
}
#else
namespace {
template <class K>
void thrust_sort(K* keys, std::uint32_t* values, int n) {
  if (n <= 1) return;
  const par::devcheck::Open access;
  thrust::stable_sort_by_key(thrust::device, keys, keys + n, values);
}
} // namespace

void sort_by_key(std::uint32_t* keys, std::uint32_t* values, int n, std::uint32_t /*max_key*/) {
  thrust_sort(keys, values, n);
}
void sort_by_key(std::uint64_t* keys, std::uint32_t* values, int n, std::uint64_t /*max_key*/) {
  thrust_sort(keys, values, n);
}

std::uint32_t exclusive_scan(const std::uint32_t* in, std::uint32_t* out, int n) {
  if (n <= 0) return 0;
  const par::devcheck::Open access;
  const std::uint32_t last_in = in[n - 1];
  thrust::exclusive_scan(thrust::device, in, in + n, out);
  return out[n - 1] + last_in;
}
#endif

void iota(std::uint32_t* values, int n) {
  par::parallel_for(
      n, SURGE_LAMBDA(int i) { values[i] = static_cast<std::uint32_t>(i); });
}

} // namespace surge::algo
