#include <mpr/mpr.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <vector>

namespace {

/// A pattern whose point() may throw: not a PixelSamplePattern.
struct ThrowingPattern {
  int count() const noexcept { return 1; }
  mpr::SamplePoint point(mpr::Pixel, int) const { return {}; }
};
/// A pattern with the wrong return type.
struct PairPattern {
  int count() const noexcept { return 1; }
  double point(mpr::Pixel, int) const noexcept { return 0; }
};
/// A filter without a radius.
struct NoRadiusFilter {
  double evaluate(double, double) const noexcept { return 1; }
};

using Plane = mpr::PlanarSurface<double>;
using Glc = mpr::GlcSelector<double>;
using Board = mpr::CheckerboardPlane<double>;

template <class S>
concept RendererAccepts = requires {
  typename mpr::Renderer<Plane, Glc, Board, S>;
};

} // namespace

TEST_CASE("pixel-sampling concepts accept the shipped policies and refuse the rest", "[sampling]") {
  STATIC_REQUIRE(mpr::PixelSamplePattern<mpr::Stratified>);
  STATIC_REQUIRE(mpr::PixelSamplePattern<mpr::OwenSobol>);
  STATIC_REQUIRE_FALSE(mpr::PixelSamplePattern<ThrowingPattern>);
  STATIC_REQUIRE_FALSE(mpr::PixelSamplePattern<PairPattern>);
  STATIC_REQUIRE_FALSE(mpr::PixelSamplePattern<mpr::BoxFilter>);
  STATIC_REQUIRE_FALSE(mpr::PixelSamplePattern<int>);

  STATIC_REQUIRE(mpr::ReconstructionFilter<mpr::BoxFilter>);
  STATIC_REQUIRE(mpr::ReconstructionFilter<mpr::TentFilter>);
  STATIC_REQUIRE(mpr::ReconstructionFilter<mpr::GaussianFilter>);
  STATIC_REQUIRE(mpr::ReconstructionFilter<mpr::MitchellFilter>);
  STATIC_REQUIRE(mpr::ReconstructionFilter<mpr::LanczosFilter>);
  STATIC_REQUIRE(mpr::ReconstructionFilter<mpr::AnyFilter>);
  STATIC_REQUIRE_FALSE(mpr::ReconstructionFilter<NoRadiusFilter>);
  STATIC_REQUIRE_FALSE(mpr::ReconstructionFilter<mpr::OwenSobol>);

  STATIC_REQUIRE(mpr::PixelSampling<mpr::PixelCentre>);
  STATIC_REQUIRE(mpr::PixelSampling<mpr::Supersample<mpr::Stratified>>);
  STATIC_REQUIRE(mpr::PixelSampling<mpr::Supersample<mpr::OwenSobol, mpr::MitchellFilter>>);
  STATIC_REQUIRE(mpr::PixelSampling<mpr::Supersample<mpr::OwenSobol, mpr::AnyFilter>>);
  STATIC_REQUIRE_FALSE(mpr::PixelSampling<mpr::OwenSobol>); // a bare pattern has no filter
  STATIC_REQUIRE_FALSE(mpr::PixelSampling<mpr::BoxFilter>);
  STATIC_REQUIRE_FALSE(mpr::PixelSampling<int>);

  STATIC_REQUIRE(RendererAccepts<mpr::PixelCentre>);
  STATIC_REQUIRE(RendererAccepts<mpr::Supersample<mpr::Stratified, mpr::TentFilter>>);
  STATIC_REQUIRE_FALSE(RendererAccepts<mpr::Stratified>);
  STATIC_REQUIRE_FALSE(RendererAccepts<double>);
  // The default is the pixel centre, and the empty policy takes no storage.
  STATIC_REQUIRE(std::is_same_v<mpr::Renderer<Plane, Glc, Board>::sampling_type, mpr::PixelCentre>);
  STATIC_REQUIRE(sizeof(mpr::Renderer<Plane, Glc, Board>) ==
                 sizeof(mpr::Renderer<Plane, Glc, Board, mpr::PixelCentre>));
}

TEST_CASE("the box filter: weight 1 on its closed square, 0 outside; bad radii throw", "[sampling]") {
  const mpr::BoxFilter box;
  CHECK(box.radius() == 0.5);
  CHECK(box.evaluate(0, 0) == 1);
  CHECK(box.evaluate(0.5, -0.5) == 1);
  CHECK(box.evaluate(0.5000001, 0) == 0);
  CHECK(box.evaluate(0, -0.51) == 0);
  CHECK(mpr::BoxFilter(2).evaluate(1.9, 1.9) == 1);
  for (const double bad :
       {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()})
    CHECK_THROWS_AS(mpr::BoxFilter(bad), mpr::argument_error);
  try {
    (void)mpr::BoxFilter(-1);
  } catch (const mpr::argument_error& e) {
    CHECK(e.parameter() == "filter radius");
  }
}

TEST_CASE("pixel seeds differ between neighbouring pixels and seeds, and are reproducible", "[sampling]") {
  const std::uint32_t a = mpr::detail::pixel_seed({3, 4}, 0);
  CHECK(a == mpr::detail::pixel_seed({3, 4}, 0));
  CHECK(a != mpr::detail::pixel_seed({4, 3}, 0));
  CHECK(a != mpr::detail::pixel_seed({3, 5}, 0));
  CHECK(a != mpr::detail::pixel_seed({3, 4}, 1));
  CHECK(mpr::detail::unit_from_bits(0) == 0);
  CHECK(mpr::detail::unit_from_bits(0xffffffffU) < 1);
  CHECK(mpr::detail::unit_from_bits(0x80000000U) == 0.5);
}

TEST_CASE("shuffle_index is a permutation of [0, count) for every count, different per seed", "[sampling]") {
  for (const std::uint32_t count : {1U, 2U, 3U, 7U, 16U, 100U, 256U, 1000U}) {
    for (const std::uint32_t seed : {0U, 1U, 0xdeadbeefU}) {
      std::vector<int> seen(count, 0);
      for (std::uint32_t i = 0; i < count; ++i) {
        const std::uint32_t j = mpr::detail::shuffle_index(i, count, seed);
        REQUIRE(j < count);
        ++seen[j];
      }
      for (const int s : seen) REQUIRE(s == 1);
    }
  }
  int moved = 0;
  for (std::uint32_t i = 0; i < 64; ++i)
    moved += mpr::detail::shuffle_index(i, 64, 5) != mpr::detail::shuffle_index(i, 64, 6) ? 1 : 0;
  CHECK(moved > 16);
}
