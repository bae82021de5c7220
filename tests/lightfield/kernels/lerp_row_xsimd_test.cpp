#include <mpr/core/config.hpp>

#include <catch2/catch.hpp>

#if MPR_HAVE_XSIMD
#include "lightfield/kernels/lerp_row_cases.hpp"

#include <mpr/lightfield/kernels/lerp_row_xsimd.hpp>

TEST_CASE("lerp_row_xsimd: the fractional-shift row at every level the build has", "[lerp_row_xsimd]") {
  mpr_test::check_lerp_row_kernel([](const std::uint8_t* a, const std::uint16_t* lut, float ax, float scale, float* h,
                                     std::size_t m, const std::uint8_t* ahead, mpr::detail::SimdLevel level) {
    mpr::kernels::lerp_row_xsimd(a, lut, ax, scale, h, m, ahead, level);
  });
}
#else
TEST_CASE("lerp_row_xsimd: xsimd not found", "[lerp_row_xsimd]") { SUCCEED("xsimd not found: kernel not built"); }
#endif
