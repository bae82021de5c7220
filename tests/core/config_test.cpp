// core/config.hpp: every macro is defined as its table says, and the derived ones agree with the
// compiler they are derived from.
#include <catch2/catch.hpp>

#include <mpr/core/config.hpp>

namespace {

// Attributes expand to something a declaration accepts.
MPR_ALWAYS_INLINE int twice(int x) noexcept { return 2 * x; }
MPR_FLATTEN int twice_flat(int x) noexcept { return twice(x); }
[[maybe_unused]] void copy(const int* MPR_RESTRICT from, int* MPR_RESTRICT to) noexcept { *to = *from; }

} // namespace

TEST_CASE("configuration macros: settings are 0 or 1", "[config]") {
  STATIC_REQUIRE((MPR_BVH_SSE == 0 || MPR_BVH_SSE == 1));
  STATIC_REQUIRE((MPR_PARALLEL_OPENMP == 0 || MPR_PARALLEL_OPENMP == 1));
#if defined(_OPENMP) && !defined(MPR_NO_OPENMP)
  STATIC_REQUIRE(MPR_PARALLEL_OPENMP == 1);
#else
  STATIC_REQUIRE(MPR_PARALLEL_OPENMP == 0);
#endif
}

TEST_CASE("configuration macros: instruction sets follow the compiler", "[config]") {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  STATIC_REQUIRE(MPR_SIMD_X86 == 1);
  STATIC_REQUIRE(MPR_BVH_SSE == 1); // SSE2 is part of x86-64
#endif
#if defined(MPR_SIMD_X86)
  // The target attributes exist exactly where the run-time levels do.
  struct Probe {
    MPR_TARGET_AVX2 static int avx2() noexcept { return 2; }
    MPR_TARGET_AVX512 static int avx512() noexcept { return 3; }
  };
  STATIC_REQUIRE(noexcept(Probe::avx2()));
  STATIC_REQUIRE(noexcept(Probe::avx512()));
#endif
  const auto lambda = [](int x) MPR_INLINE_LAMBDA { return x + 1; };
  CHECK(lambda(1) == 2);
  CHECK(twice_flat(3) == 6);
}
