#pragma once
// Runs a kernel test at every SIMD level this machine runs (core/simd.hpp), portable first, with
// the level named in every failure: the one place tests learn which levels exist. On a CPU with
// AVX-512 VBMI that is portable, avx2, avx512 (AVX-512 without VBMI) and avx512vbmi. `MPR_SIMD`
// lowers the widest level here as in the library, so that a run with MPR_SIMD=avx2 tests what a
// CPU without AVX-512 runs, and nothing more (the level ctest entries, tests/CMakeLists.txt).
#include <catch2/catch.hpp>

#include <mpr/core/simd.hpp>

#include <vector>

namespace mpr_test {

using mpr::detail::SimdLevel;

/// Whether the CPU runs `level` and `MPR_SIMD` allows it (`level <= simd_level()`).
inline bool runs(SimdLevel level) { return level <= mpr::detail::simd_level(); }

/// The levels `runs`, portable first.
inline std::vector<SimdLevel> simd_levels() {
  std::vector<SimdLevel> out;
  for (const SimdLevel level : mpr::detail::kSimdLevels)
    if (runs(level)) out.push_back(level);
  return out;
}

/// `body(level)` for every level of `simd_levels()`, in order, each failure naming the level.
template <class Body>
void for_each_simd_level(Body&& body) {
  for (const SimdLevel level : simd_levels()) {
    INFO("SIMD level " << mpr::detail::simd_level_name(level));
    body(level);
  }
}

} // namespace mpr_test
