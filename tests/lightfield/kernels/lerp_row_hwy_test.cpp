#include <mpr/core/config.hpp>

#include <catch2/catch.hpp>

#if MPR_HAVE_HWY
#include "lightfield/kernels/lerp_row_cases.hpp"

#include <mpr/lightfield/kernels/lerp_row_hwy.hpp>

// Every level the CPU runs, avx512vbmi (the AVX3_DL target) included.
TEST_CASE("lerp_row_hwy: the fractional-shift row at every level", "[lerp_row_hwy]") {
  mpr_test::check_lerp_row_kernel([](const std::uint8_t* a, const std::uint16_t* lut, float ax, float scale, float* h,
                                     std::size_t m, const std::uint8_t* ahead, mpr::detail::SimdLevel level) {
    mpr::kernels::lerp_row_hwy(a, lut, ax, scale, h, m, ahead, level);
  });
}

#else
TEST_CASE("lerp_row_hwy: Highway not found", "[lerp_row_hwy]") { SUCCEED("Highway not found: kernel not built"); }
#endif
