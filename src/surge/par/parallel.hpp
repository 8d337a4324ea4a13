// The single-source parallel layer: one loop body, run as an OpenMP loop on the
// CPU build and as a kernel launch in the CUDA build. Loop bodies are lambdas
// written with SURGE_LAMBDA and see only plain views (pointers and sizes).
#pragma once
#include "surge/core/types.hpp"
#include "surge/par/devcheck.hpp"

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#if defined(SURGE_BACKEND_CUDA)
#include <cuda_runtime.h>
// Device-only lambdas: nvcc wraps a [=] __host__ __device__ lambda in a type-erased
// holder whose host function pointer can be null when it is copied into a launch (the
// segfault of the first GPU run). Loop bodies run only in kernels, so they need no host
// side; the one consequence is that host code may not ask for their result type, which
// is why parallel_reduce takes the type from its init value.
#define SURGE_LAMBDA [=] __device__
#else
#include <omp.h>
#define SURGE_LAMBDA [=]
#endif

namespace surge::par {

#if defined(SURGE_BACKEND_CUDA)
inline void check_cuda(cudaError_t e, const char* what) {
  if (e != cudaSuccess) throw std::runtime_error(std::string(what) + ": " + cudaGetErrorString(e));
}
template <class F>
__global__ void for_kernel(int n, F f) {
  const int i = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  if (i < n) f(i);
}

inline constexpr int reduce_block = 256;
inline constexpr int reduce_max_blocks = 1024;

// One block's op-reduction of f(i) over a grid-stride range, into partial[block]. The tree
// has a fixed shape, so a reduction gives the same bits on every run (no atomics).
template <class T, class F, class Op>
__global__ void reduce_kernel(int n, T init, F f, Op op, T* partial) {
  __shared__ alignas(16) unsigned char raw[reduce_block * sizeof(T)];
  T* s = reinterpret_cast<T*>(raw);
  T acc = init;
  for (int i = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x); i < n;
       i += static_cast<int>(gridDim.x * blockDim.x))
    acc = op(acc, f(i));
  s[threadIdx.x] = acc;
  __syncthreads();
  for (unsigned w = reduce_block / 2; w > 0; w /= 2) {
    if (threadIdx.x < w) s[threadIdx.x] = op(s[threadIdx.x], s[threadIdx.x + w]);
    __syncthreads();
  }
  if (threadIdx.x == 0) partial[blockIdx.x] = s[0];
}

template <class T>
struct ReadPartial {
  const T* p;
  __device__ T operator()(int i) const { return p[i]; }
};
#endif

// Waits for every launched loop to finish (timing; the CPU build's loops are synchronous).
inline void synchronize() {
#if defined(SURGE_BACKEND_CUDA)
  check_cuda(cudaDeviceSynchronize(), "synchronize");
#endif
}

inline const char* backend_name() {
#if defined(SURGE_BACKEND_CUDA)
  return "cuda";
#else
  return "openmp";
#endif
}

// Number of CPU threads used by parallel loops (ignored by the CUDA backend).
inline void set_threads(int n) {
#if !defined(SURGE_BACKEND_CUDA)
  if (n > 0) omp_set_num_threads(n);
#else
  (void)n;
#endif
}
inline int threads() {
#if !defined(SURGE_BACKEND_CUDA)
  return omp_get_max_threads();
#else
  return 1;
#endif
}

// f(i) for i in [0, n). Each i must write only to its own outputs.
template <class F>
void parallel_for(int n, F f) {
  if (n <= 0) return;
#if defined(SURGE_BACKEND_CUDA)
  constexpr int block = 256;
  for_kernel<<<(n + block - 1) / block, block>>>(n, f);
  check_cuda(cudaGetLastError(), "kernel launch");
#else
  const devcheck::Open access;
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) f(i);
#endif
}

// Like parallel_for, for loops whose cost per index varies a lot (neighbour sums: a
// fluid particle has ~60 neighbours, a wall particle far from water none). Particles
// sorted by cell put the water in one part of the index range, so equal static halves
// leave one CPU thread idle; dynamic chunks balance them. Results do not depend on the
// schedule, since each i writes only to itself. `chunk`: the indices a thread takes at
// a time (fewer where each index is a block of particles).
template <class F>
void parallel_for_uneven(int n, F f, int chunk = 256) {
#if defined(SURGE_BACKEND_CUDA)
  (void)chunk;
  parallel_for(n, f);
#else
  if (n <= 0) return;
  const devcheck::Open access;
#pragma omp parallel for schedule(dynamic, chunk)
  for (int i = 0; i < n; ++i) f(i);
#endif
}

// op-reduction of f(i) over [0, n), returned to the host (the one host synchronisation a
// reduction costs on the GPU). op must be associative and commutative; for floating-point
// sums the rounding depends on the thread count. T is the type of init (f's result is
// converted to it): nvcc does not let host code ask a device lambda for its result type.
template <class T, class F, class Op>
T parallel_reduce(int n, T init, F f, Op op) {
  if (n <= 0) return init;
#if defined(SURGE_BACKEND_CUDA)
  // Partials and the host result live as long as the program: no allocation per call.
  static T* partial = nullptr;
  static T* result = nullptr;
  if (!partial) {
    check_cuda(cudaMalloc(reinterpret_cast<void**>(&partial), (reduce_max_blocks + 1) * sizeof(T)), "cudaMalloc");
    check_cuda(cudaMallocHost(reinterpret_cast<void**>(&result), sizeof(T)), "cudaMallocHost");
  }
  const int blocks = std::min(reduce_max_blocks, (n + reduce_block - 1) / reduce_block);
  reduce_kernel<<<blocks, reduce_block>>>(n, init, f, op, partial);
  check_cuda(cudaGetLastError(), "reduction launch");
  reduce_kernel<<<1, reduce_block>>>(blocks, init, ReadPartial<T>{partial}, op, partial + blocks);
  check_cuda(cudaGetLastError(), "reduction launch");
  check_cuda(cudaMemcpy(result, partial + blocks, sizeof(T), cudaMemcpyDeviceToHost), "reduction result");
  return *result;
#else
  const devcheck::Open access;
  T result = init;
#pragma omp parallel
  {
    T local = init;
#pragma omp for schedule(static) nowait
    for (int i = 0; i < n; ++i) local = op(local, f(i));
#pragma omp critical
    result = op(result, local);
  }
  return result;
#endif
}

struct Min {
  template <class T>
  SURGE_HD T operator()(T a, T b) const {
    return b < a ? b : a;
  }
};
struct Max {
  template <class T>
  SURGE_HD T operator()(T a, T b) const {
    return a < b ? b : a;
  }
};
struct Sum {
  template <class T>
  SURGE_HD T operator()(T a, T b) const {
    return a + b;
  }
};

// Memory in the execution space: device memory under CUDA, host memory on the
// CPU build. Host data reaches it only through the explicit copies below.
template <class T>
class Buffer {
public:
  Buffer() = default;
  explicit Buffer(std::size_t n) { resize(n); }
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
  Buffer(Buffer&& o) noexcept : ptr_(o.ptr_), size_(o.size_), cap_(o.cap_) {
    o.ptr_ = nullptr;
    o.size_ = o.cap_ = 0;
  }
  Buffer& operator=(Buffer&& o) noexcept {
    if (this != &o) {
      release();
      ptr_ = o.ptr_;
      size_ = o.size_;
      cap_ = o.cap_;
      o.ptr_ = nullptr;
      o.size_ = o.cap_ = 0;
    }
    return *this;
  }
  ~Buffer() { release(); }

  // Grows capacity without keeping contents; shrinking only changes size.
  void resize(std::size_t n) {
    if (n > cap_) {
      release();
#if defined(SURGE_BACKEND_CUDA)
      check_cuda(cudaMalloc(reinterpret_cast<void**>(&ptr_), n * sizeof(T)), "cudaMalloc");
#elif defined(SURGE_DEVCHECK)
      ptr_ = static_cast<T*>(devcheck::allocate(n * sizeof(T)));
#else
      ptr_ = static_cast<T*>(::operator new (n * sizeof(T), std::align_val_t{64}));
#endif
      cap_ = n;
    }
    size_ = n;
  }
  // Grows to n keeping the first size() elements (capacity with a quarter to spare, so that
  // a run's particle count creeping up does not reallocate every step).
  void resize_keep(std::size_t n) {
    if (n <= cap_) {
      size_ = n;
      return;
    }
    Buffer grown(n + n / 4);
    if (size_ > 0) {
#if defined(SURGE_BACKEND_CUDA)
      check_cuda(cudaMemcpy(grown.ptr_, ptr_, size_ * sizeof(T), cudaMemcpyDeviceToDevice), "resize_keep");
#else
      const devcheck::Open access;
      std::copy(ptr_, ptr_ + size_, grown.ptr_);
#endif
    }
    grown.size_ = n;
    swap(grown);
  }
  // Shrinks the logical size, keeping contents.
  void truncate(std::size_t n) {
    if (n < size_) size_ = n;
  }

  [[nodiscard]] T* data() { return ptr_; }
  [[nodiscard]] const T* data() const { return ptr_; }
  [[nodiscard]] std::size_t size() const { return size_; }
  [[nodiscard]] std::size_t bytes() const { return cap_ * sizeof(T); }
  void swap(Buffer& o) noexcept {
    std::swap(ptr_, o.ptr_);
    std::swap(size_, o.size_);
    std::swap(cap_, o.cap_);
  }

private:
  void release() {
    if (!ptr_) return;
#if defined(SURGE_BACKEND_CUDA)
    cudaFree(ptr_);
#elif defined(SURGE_DEVCHECK)
    devcheck::release(ptr_, cap_ * sizeof(T));
#else
    ::operator delete (ptr_, std::align_val_t{64});
#endif
    ptr_ = nullptr;
    cap_ = size_ = 0;
  }
  T* ptr_ = nullptr;
  std::size_t size_ = 0;
  std::size_t cap_ = 0;
};

// Explicit host <-> execution-space copies.
template <class T>
void upload(Buffer<T>& dst, const std::vector<T>& src) {
  dst.resize(src.size());
  if (src.empty()) return;
#if defined(SURGE_BACKEND_CUDA)
  check_cuda(cudaMemcpy(dst.data(), src.data(), src.size() * sizeof(T), cudaMemcpyHostToDevice), "upload");
#else
  const devcheck::Open access;
  std::copy(src.begin(), src.end(), dst.data());
#endif
}
// dst[offset, offset + src.size()) <- src; dst must already hold that range.
template <class T>
void upload_range(Buffer<T>& dst, const std::vector<T>& src, std::size_t offset) {
  if (src.empty()) return;
  if (offset + src.size() > dst.size()) throw std::logic_error("upload_range beyond the buffer");
#if defined(SURGE_BACKEND_CUDA)
  check_cuda(cudaMemcpy(dst.data() + offset, src.data(), src.size() * sizeof(T), cudaMemcpyHostToDevice), "upload");
#else
  const devcheck::Open access;
  std::copy(src.begin(), src.end(), dst.data() + offset);
#endif
}
// dst <- src[0, n), src in the execution space (a view into a Buffer).
template <class T>
void download_ptr(std::vector<T>& dst, const T* src, std::size_t n) {
  dst.resize(n);
  if (n == 0) return;
#if defined(SURGE_BACKEND_CUDA)
  check_cuda(cudaMemcpy(dst.data(), src, n * sizeof(T), cudaMemcpyDeviceToHost), "download");
#else
  const devcheck::Open access;
  std::copy(src, src + n, dst.data());
#endif
}
// dst <- src[offset, offset + n)
template <class T>
void download_range(std::vector<T>& dst, const Buffer<T>& src, std::size_t offset, std::size_t n) {
  download_ptr(dst, src.data() + offset, n);
}
template <class T>
void download(std::vector<T>& dst, const Buffer<T>& src, std::size_t n) {
  download_range(dst, src, 0, n);
}
template <class T>
std::vector<T> download(const Buffer<T>& src) {
  std::vector<T> v;
  download(v, src, src.size());
  return v;
}
// field <- field[perm], moving blocks of `block` consecutive elements (a particle's
// row of per-contact history, say), through tmp; the buffers are swapped, not copied back.
template <class T>
void gather(Buffer<T>& field, Buffer<T>& tmp, const std::uint32_t* perm, int n, int block = 1) {
  tmp.resize(static_cast<std::size_t>(n) * static_cast<std::size_t>(block));
  T* out = tmp.data();
  const T* in = field.data();
  if (block == 1) {
    parallel_for(
        n, SURGE_LAMBDA(int i) { out[i] = in[perm[i]]; });
  } else {
    parallel_for(
        n * block, SURGE_LAMBDA(int k) {
          const int i = k / block;
          out[k] = in[static_cast<std::size_t>(perm[i]) * block + (k - i * block)];
        });
  }
  field.swap(tmp);
}

// dst <- src, in the execution space.
template <class T>
void copy(Buffer<T>& dst, const Buffer<T>& src) {
  dst.resize(src.size());
  T* d = dst.data();
  const T* s = src.data();
  parallel_for(
      static_cast<int>(src.size()), SURGE_LAMBDA(int i) { d[i] = s[i]; });
}

template <class T>
void fill(Buffer<T>& b, T value) {
  T* p = b.data();
  parallel_for(
      static_cast<int>(b.size()), SURGE_LAMBDA(int i) { p[i] = value; });
}

} // namespace surge::par
