#pragma once
/// \file
/// Run-time choice of instruction set for the inner loops that are compiled more than once
/// (light-field row kernels, the plane sweep, the sRGB row encoder, the BVH packet walk): the
/// baseline of the build and, on x86 with GCC or Clang, AVX2+FMA, AVX-512 and AVX-512 with VBMI
/// through `__attribute__((target))`, so that a default build with no `-march` flag still runs
/// the widest kernels the CPU has.
///
/// The one place that decides: `simd_level()` detects the CPU's widest level (`cpu_simd_level`:
/// the feature checks of each level), lowers it by the environment variable `MPR_SIMD` and caches
/// the answer. Kernels take that answer through `dispatch_level()` (usually as the default of a
/// `SimdLevel level` argument, so tests can call every level) and never check CPU features
/// themselves.
///
/// | level        | `MPR_SIMD` names          | instruction sets                                  |
/// |--------------|---------------------------|---------------------------------------------------|
/// | `portable`   | `portable`, `sse2`, `neon`| the build's baseline: SSE2 on x86-64, NEON on     |
/// |              |                           | AArch64 (there the level is named `neon`)         |
/// | `avx2`       | `avx2`, `avx2+fma`        | AVX2 + FMA (Haswell, Zen 1 and later)             |
/// | `avx512`     | `avx512`                  | AVX-512 F/BW/DQ/VL, without VBMI (Skylake-X)      |
/// | `avx512vbmi` | `avx512vbmi`              | the same plus VBMI byte permutes (Ice Lake, Zen 4)|

#include <mpr/core/config.hpp>

#include <array>
#include <cstdlib>
#include <optional>
#include <string_view>
#include <type_traits>

#if defined(MPR_SIMD_X86)
#include <immintrin.h>
#endif

namespace mpr::detail {

/// The instruction sets the kernels are compiled for, widest last: each level runs on every CPU
/// that runs a wider one, so `level >= SimdLevel::avx512` asks "at least AVX-512".
enum class SimdLevel { portable = 0, avx2 = 1, avx512 = 2, avx512vbmi = 3 };

/// Every level, narrowest first.
inline constexpr std::array<SimdLevel, 4> kSimdLevels{SimdLevel::portable, SimdLevel::avx2, SimdLevel::avx512,
                                                      SimdLevel::avx512vbmi};

/// The name of `level`: "portable" ("neon" on AArch64, where NEON is the baseline), "avx2+fma",
/// "avx512" (without VBMI) or "avx512vbmi".
[[nodiscard]] constexpr const char* simd_level_name(SimdLevel level) noexcept {
  switch (level) {
  case SimdLevel::avx512vbmi:
    return "avx512vbmi";
  case SimdLevel::avx512:
    return "avx512";
  case SimdLevel::avx2:
    return "avx2+fma";
  default:
#if defined(MPR_SIMD_NEON)
    return "neon";
#else
    return "portable";
#endif
  }
}

/// The bytes of a vector register at `level`: 64 at AVX-512, 32 at AVX2, 16 at the portable
/// level (SSE2, NEON). Kernels written with the compiler's vector types size their lanes by it: a
/// vector type wider than the level's registers is lowered to scalar code at AVX2 and below.
[[nodiscard]] constexpr int simd_register_bytes(SimdLevel level) noexcept {
  return level >= SimdLevel::avx512 ? 64 : level == SimdLevel::avx2 ? 32 : 16;
}

/// The level a value of `MPR_SIMD` names, or nothing for an unknown name. Accepted: the names of
/// `simd_level_name`, and `portable`, `sse2`, `neon`, `baseline` (the baseline) and `avx2`.
[[nodiscard]] constexpr std::optional<SimdLevel> parse_simd_level(std::string_view name) noexcept {
  if (name == "portable" || name == "sse2" || name == "neon" || name == "baseline") return SimdLevel::portable;
  if (name == "avx2" || name == "avx2+fma") return SimdLevel::avx2;
  if (name == "avx512") return SimdLevel::avx512;
  if (name == "avx512vbmi") return SimdLevel::avx512vbmi;
  return std::nullopt;
}

/// The level kernels run at on a CPU whose widest level is `best` when `MPR_SIMD` is `limit`
/// (null: unset): the narrower of the two. `limit` only ever lowers the choice; an unknown
/// name leaves `best` (the render path must not throw; `simd_level_name()` tells the choice).
[[nodiscard]] constexpr SimdLevel limit_simd_level(SimdLevel best, const char* limit) noexcept {
  if (limit == nullptr) return best;
  const std::optional<SimdLevel> asked = parse_simd_level(limit);
  return asked && *asked < best ? *asked : best;
}

/// The widest level this CPU runs, as detected (checked once; `MPR_SIMD` is ignored): what
/// `simd_level()` starts from, and what tests run every level up to. Each level needs the one
/// below it and its own features.
[[nodiscard]] inline SimdLevel cpu_simd_level() noexcept {
  static const SimdLevel level = [] {
    SimdLevel best = SimdLevel::portable;
#if defined(MPR_SIMD_X86)
    __builtin_cpu_init();
    const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    const bool avx512 = avx2 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                        __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq");
    const bool vbmi = avx512 && __builtin_cpu_supports("avx512vbmi");
    best = vbmi ? SimdLevel::avx512vbmi : avx512 ? SimdLevel::avx512 : avx2 ? SimdLevel::avx2 : SimdLevel::portable;
#endif
    return best;
  }();
  return level;
}

/// The level kernels run at: `cpu_simd_level()` lowered by `MPR_SIMD` (read once, cached). The
/// one place the choice is made; kernels read it through `dispatch_level()`.
[[nodiscard]] inline SimdLevel simd_level() noexcept {
  static const SimdLevel level = limit_simd_level(cpu_simd_level(), std::getenv("MPR_SIMD"));
  return level;
}

/// The cached answer of `simd_level()`, for kernels to dispatch on (the default of their
/// `SimdLevel level` argument): they ask this instead of checking the CPU.
[[nodiscard]] inline SimdLevel dispatch_level() noexcept { return simd_level(); }

/// The name of `simd_level()`.
[[nodiscard]] inline const char* simd_level_name() noexcept { return simd_level_name(simd_level()); }

/// The level a body is being compiled for, as a type: `run_at` hands it to bodies that take one,
/// so that a kernel can add a hand-written step for one level (`if constexpr`) to its plain
/// loop; the x86 steps live in each module's kernels/ folder.
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
/// to `simd_level()`). `avx512vbmi` runs the `avx512` body: VBMI steps are kernels of their own.
template <class Body>
void run_at(SimdLevel level, const Body& body) noexcept {
#if defined(MPR_SIMD_X86)
  if (level >= SimdLevel::avx512) return run_avx512(body);
  if (level == SimdLevel::avx2) return run_avx2(body);
#endif
  (void)level;
  call_at<SimdLevel::portable>(body);
}

} // namespace mpr::detail
