// Which copy of the CPU's batched (SIMD) pair loops a run uses: chosen once at run time,
// so that one binary uses AVX2 where the CPU has it and SSE2 (every x86-64 CPU) elsewhere.
// Host code of builds with SURGE_SIMD only (GCC on x86-64).
#pragma once
#include <cstdlib>
#include <cstring>

namespace surge::par {

// "avx2" or "sse2", the widest this CPU has, unless the environment variable SURGE_SIMD
// asks for "sse2" or for the scalar loops ("off").
inline const char* simd_isa() {
  static const char* name = [] {
    const bool avx2_here = __builtin_cpu_supports("avx2") != 0;
    const char* env = std::getenv("SURGE_SIMD");
    if (env && std::strcmp(env, "off") == 0) return "off";
    if (env && std::strcmp(env, "sse2") == 0) return "sse2";
    return avx2_here ? "avx2" : "sse2"; // unset, "avx2" or anything else: the widest there is
  }();
  return name;
}

// Whether this CPU can run the copy for instruction set `isa` ("avx2", "sse2").
inline bool simd_isa_here(const char* isa) {
  if (std::strcmp(isa, "avx2") == 0) return __builtin_cpu_supports("avx2") != 0;
  return std::strcmp(isa, "sse2") == 0;
}

} // namespace surge::par
