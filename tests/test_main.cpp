// Catch2's main for every test program. A ctest entry that runs a program at one SIMD level
// (tests/CMakeLists.txt: MPR_SIMD=<level> with MPR_TEST_SIMD_EXACT=1) names the level it runs
// at, and is reported as skipped where the CPU lacks that level (instead of repeating a lower one)
// or where it is the CPU's widest (the plain entry runs that one).
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <mpr/core/simd.hpp>

#include <cstdio>
#include <cstdlib>
#include <optional>

int main(int argc, char* argv[]) {
  if (std::getenv("MPR_TEST_SIMD_EXACT") != nullptr) {
    const char* asked = std::getenv("MPR_SIMD");
    const std::optional<mpr::detail::SimdLevel> level = asked ? mpr::detail::parse_simd_level(asked) : std::nullopt;
    if (!level) {
      std::fprintf(stderr, "MPR_TEST_SIMD_EXACT needs MPR_SIMD set to a level name (got '%s')\n", asked ? asked : "");
      return 2;
    }
    const mpr::detail::SimdLevel widest = mpr::detail::cpu_simd_level();
    if (*level >= widest) {
      // Above the CPU's widest level it cannot run; at it, the plain ctest entry already runs it.
      std::printf("SIMD level %s: %s (the CPU's widest is %s): level entry skipped\n", asked,
                  *level > widest ? "not run by this CPU" : "run by the plain entry",
                  mpr::detail::simd_level_name(widest));
      return 0;
    }
    std::printf("SIMD level: %s\n", mpr::detail::simd_level_name());
  }
  return Catch::Session().run(argc, argv);
}
