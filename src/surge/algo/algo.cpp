#include "surge/algo/algo.hpp"

#include <bit>

#if defined(SURGE_BACKEND_CUDA)
#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_scan.cuh>
#else
#include <thrust/execution_policy.h>
#include <thrust/scan.h>

#include <algorithm>
#include <memory>
#include <utility>
#include <vector>
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

void sort_by_key(std::uint32_t* keys, std::uint32_t* values, int n, std::uint32_t max_key, void* /*scratch*/,
                 std::size_t /*scratch_bytes*/) {
  radix_sort(keys, values, n, max_key);
}
void sort_by_key(std::uint64_t* keys, std::uint32_t* values, int n, std::uint64_t max_key, void* /*scratch*/,
                 std::size_t /*scratch_bytes*/) {
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
// One pass of the radix sort: the digit (key >> shift) & mask of every key, counted per
// block of the array, gives each (digit, block) its first place in the output; each block
// then moves its elements there in order. Stable, and the same result for any number of
// blocks or threads.
template <class K>
void radix_pass(const K* keys, const std::uint32_t* values, K* keys_out, std::uint32_t* values_out, int n, int shift,
                int digits, int blocks, std::uint32_t* count) {
  const K mask = static_cast<K>(digits - 1);
  const int per = (n + blocks - 1) / blocks;
  par::parallel_for(blocks, [=](int b) {
    std::uint32_t* c = count + static_cast<std::ptrdiff_t>(b) * digits;
    for (int d = 0; d < digits; ++d) c[d] = 0;
    const int lo = b * per, hi = std::min(n, lo + per);
    for (int i = lo; i < hi; ++i) ++c[(keys[i] >> shift) & mask];
  });
  std::uint32_t at = 0;
  for (int d = 0; d < digits; ++d)
    for (int b = 0; b < blocks; ++b) {
      std::uint32_t& c = count[static_cast<std::ptrdiff_t>(b) * digits + d];
      const std::uint32_t k = c;
      c = at;
      at += k;
    }
  par::parallel_for(blocks, [=](int b) {
    std::uint32_t* c = count + static_cast<std::ptrdiff_t>(b) * digits;
    const int lo = b * per, hi = std::min(n, lo + per);
    for (int i = lo; i < hi; ++i) {
      const std::uint32_t to = c[(keys[i] >> shift) & mask]++;
      keys_out[to] = keys[i];
      values_out[to] = values[i];
    }
  });
}

template <class K>
void radix_sort(K* keys, std::uint32_t* values, int n, K max_key, void* scratch, std::size_t scratch_bytes) {
  if (n <= 1) return;
  const par::devcheck::Open access;
  const auto un = static_cast<std::size_t>(n);
  const std::size_t need = un * (sizeof(K) + sizeof(std::uint32_t));
  std::unique_ptr<unsigned char[]> own;
  if (!scratch || scratch_bytes < need) {
    own.reset(new unsigned char[need]); // new[]: aligned for any key
    scratch = own.get();
  }
  // Scratch keys first (8-byte aligned for 64-bit keys: Buffer memory is 64-byte aligned).
  K* tk = static_cast<K*>(scratch);
  auto* tv = reinterpret_cast<std::uint32_t*>(tk + un);
  const int bits = std::max(1, static_cast<int>(std::bit_width(max_key)));
  const int passes = (bits + 10) / 11;
  const int width = (bits + passes - 1) / passes; // digits as even as the passes allow
  const int digits = 1 << width;
  const int blocks = std::max(1, std::min(4 * par::threads(), n / 4096));
  std::vector<std::uint32_t> count(static_cast<std::size_t>(blocks) * static_cast<std::size_t>(digits));
  K* from_k = keys;
  std::uint32_t* from_v = values;
  K* to_k = tk;
  std::uint32_t* to_v = tv;
  for (int p = 0; p < passes; ++p) {
    radix_pass(from_k, from_v, to_k, to_v, n, p * width, digits, blocks, count.data());
    std::swap(from_k, to_k);
    std::swap(from_v, to_v);
  }
  if (from_k != keys) {
    par::parallel_for(n, [=](int i) {
      keys[i] = from_k[i];
      values[i] = from_v[i];
    });
  }
}
} // namespace

void sort_by_key(std::uint32_t* keys, std::uint32_t* values, int n, std::uint32_t max_key, void* scratch,
                 std::size_t scratch_bytes) {
  radix_sort(keys, values, n, max_key, scratch, scratch_bytes);
}
void sort_by_key(std::uint64_t* keys, std::uint32_t* values, int n, std::uint64_t max_key, void* scratch,
                 std::size_t scratch_bytes) {
  radix_sort(keys, values, n, max_key, scratch, scratch_bytes);
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
