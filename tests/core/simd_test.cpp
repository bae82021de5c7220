#include "simd_levels.hpp"

#include <catch2/catch.hpp>

#include <mpr/core/simd.hpp>

#include <cstdlib>
#include <string>

// CHECK, not STATIC_REQUIRE, on the constexpr functions: a broken rule fails the test instead of
// the build (the mutation run counts a build failure as a broken mutation list).

using mpr::detail::SimdLevel;

TEST_CASE("MPR_SIMD names: the old and the new names of each level, unknown names refused", "[simd]") {
  using mpr::detail::parse_simd_level;
  CHECK(parse_simd_level("portable") == SimdLevel::portable);
  CHECK(parse_simd_level("sse2") == SimdLevel::portable);
  CHECK(parse_simd_level("neon") == SimdLevel::portable);
  CHECK(parse_simd_level("avx2") == SimdLevel::avx2);
  CHECK(parse_simd_level("avx2+fma") == SimdLevel::avx2);
  CHECK(parse_simd_level("avx512") == SimdLevel::avx512);
  CHECK(parse_simd_level("avx512vbmi") == SimdLevel::avx512vbmi);
  CHECK(!parse_simd_level("AVX2").has_value());
  CHECK(!parse_simd_level("").has_value());
  CHECK(!parse_simd_level("avx512 ").has_value());
  // Every level's printed name reads back as that level.
  for (const SimdLevel level : mpr::detail::kSimdLevels)
    CHECK(parse_simd_level(mpr::detail::simd_level_name(level)) == level);
}

TEST_CASE("MPR_SIMD only lowers the detected level; unset or unknown leaves it", "[simd]") {
  using mpr::detail::limit_simd_level;
  CHECK(limit_simd_level(SimdLevel::avx512vbmi, nullptr) == SimdLevel::avx512vbmi);
  CHECK(limit_simd_level(SimdLevel::avx512vbmi, "avx512") == SimdLevel::avx512);
  CHECK(limit_simd_level(SimdLevel::avx512vbmi, "avx2") == SimdLevel::avx2);
  CHECK(limit_simd_level(SimdLevel::avx512vbmi, "portable") == SimdLevel::portable);
  CHECK(limit_simd_level(SimdLevel::avx2, "avx512") == SimdLevel::avx2);
  CHECK(limit_simd_level(SimdLevel::avx512, "avx512vbmi") == SimdLevel::avx512);
  CHECK(limit_simd_level(SimdLevel::portable, "avx2") == SimdLevel::portable);
  CHECK(limit_simd_level(SimdLevel::avx512, "fast") == SimdLevel::avx512);
}

TEST_CASE("The chosen level is the detected one lowered by this process's MPR_SIMD", "[simd]") {
  const char* limit = std::getenv("MPR_SIMD");
  INFO("MPR_SIMD=" << (limit ? limit : "(unset)") << ", detected "
                   << mpr::detail::simd_level_name(mpr::detail::cpu_simd_level()) << ", chosen "
                   << mpr::detail::simd_level_name());
  CHECK(mpr::detail::simd_level() == mpr::detail::limit_simd_level(mpr::detail::cpu_simd_level(), limit));
  CHECK(mpr::detail::dispatch_level() == mpr::detail::simd_level());
  // The harness runs every level up to the chosen one, narrowest first, without gaps.
  const auto levels = mpr_test::simd_levels();
  REQUIRE(!levels.empty());
  CHECK(levels.front() == SimdLevel::portable);
  CHECK(levels.back() == mpr::detail::simd_level());
  CHECK(levels.size() == static_cast<std::size_t>(mpr::detail::simd_level()) + 1);
  // A ctest entry that sets MPR_SIMD to a level this CPU runs gets exactly that level.
  if (limit != nullptr && mpr::detail::parse_simd_level(limit) && mpr_test::runs(*mpr::detail::parse_simd_level(limit)))
    CHECK(mpr::detail::simd_level() == *mpr::detail::parse_simd_level(limit));
}
