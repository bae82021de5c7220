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
#include <type_traits>

#if defined(MPR_SIMD_X86)
#include <immintrin.h>
#endif

namespace mpr::detail {

/// The instruction sets the kernels are compiled for, widest last.
enum class SimdLevel { portable = 0, avx2 = 1, avx512 = 2 };

/// The widest kernel set this CPU runs, as detected (checked once; `MPR_SIMD` is ignored): what
/// `simd_level()` starts from, and what tests run every level up to.
[[nodiscard]] inline SimdLevel cpu_simd_level() noexcept {
  static const SimdLevel level = [] {
    SimdLevel best = SimdLevel::portable;
#if defined(MPR_SIMD_X86)
    if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) best = SimdLevel::avx2;
    if (best == SimdLevel::avx2 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
        __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq"))
      best = SimdLevel::avx512;
#endif
    return best;
  }();
  return level;
}

/// Whether the CPU has AVX-512 VBMI (byte permutes) on top of the `avx512` level (checked once).
/// Kernels that use it take it as an extra step of that level and fall back without it.
[[nodiscard]] inline bool cpu_has_avx512_vbmi() noexcept {
#if defined(MPR_SIMD_X86)
  static const bool vbmi = cpu_simd_level() == SimdLevel::avx512 && __builtin_cpu_supports("avx512vbmi");
  return vbmi;
#else
  return false;
#endif
}

/// The widest kernel set this CPU runs, lowered by `MPR_SIMD` when set (checked once).
/// `MPR_SIMD` only ever lowers the choice: `avx512` (or `avx2` on a CPU without AVX-512) and any
/// other value leave it as detected. It is read on the render path, which must not throw, so an
/// unrecognised value is not an error; `simd_level_name()` tells what was chosen.
[[nodiscard]] inline SimdLevel simd_level() noexcept {
  static const SimdLevel level = [] {
    const SimdLevel best = cpu_simd_level();
    const char* limit = std::getenv("MPR_SIMD");
    if (limit != nullptr) {
      if (std::strcmp(limit, "portable") == 0) return SimdLevel::portable;
      if (std::strcmp(limit, "avx2") == 0 && best == SimdLevel::avx512) return SimdLevel::avx2;
    }
    return best;
  }();
  return level;
}

/// The name of `level`: "avx512", "avx2+fma" or "portable" (the build's baseline, which is SSE2
/// on x86-64).
[[nodiscard]] constexpr const char* simd_level_name(SimdLevel level) noexcept {
  switch (level) {
  case SimdLevel::avx512:
    return "avx512";
  case SimdLevel::avx2:
    return "avx2+fma";
  default:
    return "portable";
  }
}

/// The name of `simd_level()`.
[[nodiscard]] inline const char* simd_level_name() noexcept { return simd_level_name(simd_level()); }

/// The level a body is being compiled for, as a type: `run_at` hands it to bodies that take one,
/// so that a kernel can add a hand-written step for one level (`if constexpr`) to its plain
/// loop; the x86 steps live in each module's detail/kernels.hpp.
template <SimdLevel L>
using SimdTag = std::integral_constant<SimdLevel, L>;

/// `body(SimdTag<L>{})` when the body takes the tag, else `body()`.
template <SimdLevel L, class Body>
MPR_ALWAYS_INLINE void call_at(const Body& body) noexcept {
  if constexpr (std::is_invocable_v<const Body&, SimdTag<L>>)
    body(SimdTag<L>{});
  else
    body();
}

#if defined(MPR_SIMD_X86)
template <class Body>
MPR_TARGET_AVX2 void run_avx2(const Body& body) noexcept {
  call_at<SimdLevel::avx2>(body);
}
template <class Body>
MPR_TARGET_AVX512 void run_avx512(const Body& body) noexcept {
  call_at<SimdLevel::avx512>(body);
}
#endif

/// Calls `body()` (or `body(SimdTag<level>{})`) compiled for `level`: the body (a lambda marked
/// `MPR_INLINE_LAMBDA` whose callees are `MPR_ALWAYS_INLINE`) is inlined into a function built
/// for that instruction set, so the compiler vectorises its loops at that width. One plain C++
/// body thus gives every variant of a kernel. Precondition: the CPU runs `level` (any level up
/// to `simd_level()`).
template <class Body>
void run_at(SimdLevel level, const Body& body) noexcept {
#if defined(MPR_SIMD_X86)
  if (level == SimdLevel::avx512) return run_avx512(body);
  if (level == SimdLevel::avx2) return run_avx2(body);
#endif
  (void)level;
  call_at<SimdLevel::portable>(body);
}

} // namespace mpr::detail
