#include <catch2/catch.hpp>

#include <mpr/lightfield/kernels/unit_acos.hpp>

#include <cmath>
#include <cstring>
#include <vector>

namespace {

#if defined(MPR_SIMD_X86)
MPR_TARGET_AVX512 void acos16(const float* x, float* out) {
  _mm512_storeu_ps(out, mpr::detail::unit_acos16(_mm512_loadu_ps(x)));
}
#endif

} // namespace

TEST_CASE("unit_acos is within 2 ulp of acos on [0, 1], and its lanes give the same bits", "[depth_proxy][simd]") {
  // Every 97th float in [0, 1] (about 11 million values), and the ends.
  std::vector<float> xs{0.0f, 0.5f, std::nextafter(0.5f, 0.0f), 1.0f, std::nextafter(1.0f, 0.0f)};
  for (float x = 1e-30f; x < 1.0f;) {
    xs.push_back(x);
    std::uint32_t bits;
    std::memcpy(&bits, &x, 4);
    bits += 97;
    std::memcpy(&x, &bits, 4);
  }
  double worst = 0;
  for (const float x : xs) {
    const double exact = std::acos(static_cast<double>(x));
    const float got = mpr::detail::unit_acos(x);
    const double ulp = std::nextafter(static_cast<float>(exact), 4.0f) - static_cast<float>(exact);
    worst = std::max(worst, std::abs(got - exact) / ulp);
  }
  INFO("largest error " << worst << " ulp");
  CHECK(worst <= 2.0);
  CHECK(mpr::detail::unit_acos(1.0f) == 0.0f);
  CHECK(mpr::detail::unit_acos(0.25) == std::acos(0.25)); // doubles: std::acos
#if defined(MPR_SIMD_X86)
  if (mpr::detail::simd_level() >= mpr::detail::SimdLevel::avx512) {
    std::size_t differ = 0;
    for (std::size_t i = 0; i + 16 <= xs.size(); i += 16) {
      float lanes[16];
      acos16(xs.data() + i, lanes);
      for (int l = 0; l < 16; ++l) differ += lanes[l] != mpr::detail::unit_acos(xs[i + static_cast<std::size_t>(l)]);
    }
#if defined(__FMA__) || defined(__FP_FAST_FMAF)
    CHECK(differ <= xs.size() / 100); // the scalar polynomial may be contracted
#else
    CHECK(differ == 0);
#endif
  }
#endif
}
