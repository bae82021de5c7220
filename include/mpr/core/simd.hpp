#pragma once
/// \file
/// Run-time choice of instruction set for the few inner loops that are compiled more than once
/// (light-field row kernels, the sRGB row encoder): the baseline of the build and, on x86 with
/// GCC or Clang, AVX2+FMA and AVX-512 through `__attribute__((target))`, so that a default
/// build with no `-march` flag still runs the widest kernels the CPU has. `simd_level()` picks
/// them once; the environment variable `MPR_SIMD` (`portable`, `avx2`, `avx512`) can lower
/// that choice, e.g. to compare kernels or to match a machine without AVX-512.

#include <mpr/core/config.hpp>

#include <cstdlib>
#include <cstring>

#if defined(MPR_SIMD_X86)
#include <immintrin.h>
#endif

namespace mpr::detail {

/// The instruction sets the kernels are compiled for, widest last.
enum class SimdLevel { portable = 0, avx2 = 1, avx512 = 2 };

/// The widest kernel set this CPU runs, lowered by `MPR_SIMD` when set (checked once).
/// `MPR_SIMD` only ever lowers the choice: `avx512` (or `avx2` on a CPU without AVX-512) and any
/// other value leave it as detected. It is read on the render path, which must not throw, so an
/// unrecognised value is not an error; `simd_level_name()` tells what was chosen.
[[nodiscard]] inline SimdLevel simd_level() noexcept {
  static const SimdLevel level = [] {
    SimdLevel best = SimdLevel::portable;
#if defined(MPR_SIMD_X86)
    if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) best = SimdLevel::avx2;
    if (best == SimdLevel::avx2 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
        __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq"))
      best = SimdLevel::avx512;
#endif
    const char* limit = std::getenv("MPR_SIMD");
    if (limit != nullptr) {
      if (std::strcmp(limit, "portable") == 0) return SimdLevel::portable;
      if (std::strcmp(limit, "avx2") == 0 && best == SimdLevel::avx512) return SimdLevel::avx2;
    }
    return best;
  }();
  return level;
}

/// The name of `simd_level()`: "avx512", "avx2+fma" or "portable" (the build's baseline, which
/// is SSE2 on x86-64).
[[nodiscard]] inline const char* simd_level_name() noexcept {
  switch (simd_level()) {
  case SimdLevel::avx512:
    return "avx512";
  case SimdLevel::avx2:
    return "avx2+fma";
  default:
    return "portable";
  }
}

#if defined(MPR_SIMD_X86)
template <class Body>
MPR_TARGET_AVX2 void run_avx2(const Body& body) noexcept {
  body();
}
template <class Body>
MPR_TARGET_AVX512 void run_avx512(const Body& body) noexcept {
  body();
}
#endif

/// Calls `body()` compiled for `level`: the body (a lambda marked `MPR_INLINE_LAMBDA` whose
/// callees are `MPR_ALWAYS_INLINE`) is inlined into a function built for that instruction set,
/// so the compiler vectorises its loops at that width. One plain C++ body thus gives every
/// variant of a kernel. Precondition: the CPU runs `level` (any level up to `simd_level()`).
template <class Body>
void run_at(SimdLevel level, const Body& body) noexcept {
#if defined(MPR_SIMD_X86)
  if (level == SimdLevel::avx512) return run_avx512(body);
  if (level == SimdLevel::avx2) return run_avx2(body);
#endif
  (void)level;
  body();
}

} // namespace mpr::detail
