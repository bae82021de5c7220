#pragma once
// Runs a kernel test at every SIMD level this machine has (core/simd.hpp), portable first, with
// the level named in every failure: the one place tests learn which levels exist.
#include <catch2/catch.hpp>

#include <mpr/core/simd.hpp>

#include <vector>

namespace mpr_test {

using mpr::detail::SimdLevel;

/// The levels the CPU runs, portable first (detected; `MPR_SIMD` does not lower them).
inline std::vector<SimdLevel> simd_levels() {
  std::vector<SimdLevel> out{SimdLevel::portable};
  if (mpr::detail::cpu_simd_level() >= SimdLevel::avx2) out.push_back(SimdLevel::avx2);
  if (mpr::detail::cpu_simd_level() >= SimdLevel::avx512) out.push_back(SimdLevel::avx512);
  return out;
}

/// Whether the CPU runs `level`.
inline bool runs(SimdLevel level) { return level <= mpr::detail::cpu_simd_level(); }

/// `body(level)` for every level of `simd_levels()`, in order, each failure naming the level.
template <class Body>
void for_each_simd_level(Body&& body) {
  for (const SimdLevel level : simd_levels()) {
    INFO("SIMD level " << mpr::detail::simd_level_name(level));
    body(level);
  }
}

} // namespace mpr_test
