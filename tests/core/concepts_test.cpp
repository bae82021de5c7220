// Compile-time checks of the four roles' concepts: shipped policies satisfy them, malformed
// policies are rejected, and stateless policies cost no bytes in a Renderer.
#include <mpr/mpr.hpp>

#include <catch2/catch.hpp>

namespace {

template <class T>
struct ConstantSurface {
  using scalar_type = T;
  mpr::Vec3<T> point_at(const mpr::Vec2<T>&) const noexcept { return mpr::Vec3<T>::Zero(); }
};
template <class T>
struct AlongZ {
  using scalar_type = T;
  mpr::Ray<T> ray_at(mpr::Pixel, const mpr::Vec2<T>&, const mpr::Vec3<T>& p) const noexcept {
    return {p, mpr::Vec3<T>::UnitZ()};
  }
};
template <class T>
struct Black {
  using scalar_type = T;
  mpr::Color sample(const mpr::Ray<T>&) const noexcept { return mpr::Color::Zero(); }
};
template <class T>
struct Depth { // declares its own colour type
  using scalar_type = T;
  using color_type = float;
  float sample(const mpr::Ray<T>& r) const noexcept { return static_cast<float>(r.origin.z()); }
};

// Negative cases.
struct NoScalar {
  mpr::Vec3<double> point_at(const mpr::Vec2<double>&) const noexcept { return {}; }
};
struct IntScalar {
  using scalar_type = int;
};
struct NoPointAt {
  using scalar_type = double;
  mpr::Vec3<double> point(const mpr::Vec2<double>&) const noexcept { return {}; }
};
struct WrongPointType {
  using scalar_type = double;
  mpr::Vec3<float> point_at(const mpr::Vec2<double>&) const noexcept { return {}; }
};
struct ReturnsExpression { // an Eigen expression is not a Vec3: concrete types only
  using scalar_type = double;
  mpr::Vec3<double> a, b;
  auto point_at(const mpr::Vec2<double>&) const noexcept { return a + b; }
};
struct MayThrow {
  using scalar_type = double;
  mpr::Vec3<double> point_at(const mpr::Vec2<double>&) const { return {}; }
};
struct NonConst {
  using scalar_type = double;
  mpr::Vec3<double> point_at(const mpr::Vec2<double>&) noexcept { return {}; }
};
struct SelectorWithoutPixel {
  using scalar_type = double;
  mpr::Ray<double> ray_at(const mpr::Vec2<double>&, const mpr::Vec3<double>&) const noexcept { return {}; }
};
struct SamplerWrongColour { // declares float but returns Color
  using scalar_type = double;
  using color_type = float;
  mpr::Color sample(const mpr::Ray<double>&) const noexcept { return {}; }
};

template <class Su, class Se, class Sa>
concept RendererAccepts = requires {
  typename mpr::Renderer<Su, Se, Sa>;
};

} // namespace

TEMPLATE_TEST_CASE("shipped policies satisfy their concepts", "[concepts]", float, double) {
  using T = TestType;
  STATIC_REQUIRE(mpr::ImageSurface<mpr::PlanarSurface<T>>);
  STATIC_REQUIRE(mpr::RaySelector<mpr::GlcSelector<T>>);
  STATIC_REQUIRE(mpr::RaySampler<mpr::CheckerboardPlane<T>>);
  STATIC_REQUIRE(mpr::ComposablePolicies<mpr::PlanarSurface<T>, mpr::GlcSelector<T>, mpr::CheckerboardPlane<T>>);
  STATIC_REQUIRE(mpr::RaySampler<Depth<T>>);
  STATIC_REQUIRE(std::is_same_v<mpr::sampler_color_t<Depth<T>>, float>);
  STATIC_REQUIRE(std::is_same_v<mpr::sampler_color_t<Black<T>>, mpr::Color>);
  // Roles are distinct: a surface is not a selector or sampler.
  STATIC_REQUIRE_FALSE(mpr::RaySelector<mpr::PlanarSurface<T>>);
  STATIC_REQUIRE_FALSE(mpr::RaySampler<mpr::GlcSelector<T>>);
}

TEST_CASE("malformed policies are rejected", "[concepts]") {
  STATIC_REQUIRE_FALSE(mpr::ImageSurface<NoScalar>);
  STATIC_REQUIRE_FALSE(mpr::ImageSurface<IntScalar>);
  STATIC_REQUIRE_FALSE(mpr::ImageSurface<NoPointAt>);
  STATIC_REQUIRE_FALSE(mpr::ImageSurface<WrongPointType>);
  STATIC_REQUIRE_FALSE(mpr::ImageSurface<ReturnsExpression>);
  STATIC_REQUIRE_FALSE(mpr::ImageSurface<MayThrow>);
  STATIC_REQUIRE_FALSE(mpr::ImageSurface<NonConst>);
  STATIC_REQUIRE_FALSE(mpr::RaySelector<SelectorWithoutPixel>);
  STATIC_REQUIRE_FALSE(mpr::RaySampler<SamplerWrongColour>);
}

TEST_CASE("policies must agree on the scalar type", "[concepts]") {
  STATIC_REQUIRE(RendererAccepts<ConstantSurface<double>, AlongZ<double>, Black<double>>);
  STATIC_REQUIRE_FALSE(mpr::ComposablePolicies<ConstantSurface<float>, AlongZ<double>, Black<double>>);
  STATIC_REQUIRE_FALSE(
      mpr::ComposablePolicies<mpr::PlanarSurface<double>, mpr::GlcSelector<double>, mpr::CheckerboardPlane<float>>);
  STATIC_REQUIRE_FALSE(RendererAccepts<mpr::PlanarSurface<float>, mpr::GlcSelector<double>, Black<double>>);
  STATIC_REQUIRE_FALSE(RendererAccepts<NoPointAt, AlongZ<double>, Black<double>>);
}

TEST_CASE("stateless policies take no bytes", "[concepts]") {
  STATIC_REQUIRE(sizeof(mpr::Renderer<ConstantSurface<float>, AlongZ<float>, Black<float>>) == 1);
  STATIC_REQUIRE(sizeof(mpr::Renderer<mpr::PlanarSurface<float>, AlongZ<float>, Black<float>>) ==
                 sizeof(mpr::PlanarSurface<float>));
  STATIC_REQUIRE(sizeof(mpr::Renderer<ConstantSurface<double>, mpr::GlcSelector<double>, Black<double>>) ==
                 sizeof(mpr::GlcSelector<double>));
}

namespace {
template <class T>
struct BlackRows : Black<T> {
  void sample_rays(std::span<const mpr::Ray<T>>, std::span<mpr::Color> out) const noexcept {
    for (mpr::Color& c : out) c = mpr::Color::Zero();
  }
};
template <class T>
struct BlackTiles : Black<T> {
  void sample_tile(std::span<const mpr::Ray<T>>, int, std::span<mpr::Color> out) const noexcept {
    for (mpr::Color& c : out) c = mpr::Color::Zero();
  }
};
template <class T>
struct BlackGrids : BlackTiles<T> {
  template <class ExactRay>
  bool sample_grid(const mpr::RayGrid<T, ExactRay>&, std::span<mpr::Color>) const noexcept {
    return false;
  }
};
template <class T>
struct GridWithoutTiles : Black<T> { // a grid path needs the tile path to fall back on
  template <class ExactRay>
  bool sample_grid(const mpr::RayGrid<T, ExactRay>&, std::span<mpr::Color>) const noexcept {
    return false;
  }
};
template <class T>
struct GridReturnsVoid : BlackTiles<T> {
  template <class ExactRay>
  void sample_grid(const mpr::RayGrid<T, ExactRay>&, std::span<mpr::Color>) const noexcept {}
};
template <class T>
struct ThrowingRows : Black<T> { // not noexcept: not a batch sampler
  void sample_rays(std::span<const mpr::Ray<T>>, std::span<mpr::Color>) const {}
};
} // namespace

TEMPLATE_TEST_CASE("optional batch and tile interfaces are detected from core/concepts.hpp", "[concepts]", float,
                   double) {
  using T = TestType;
  STATIC_REQUIRE(mpr::BatchRaySampler<BlackRows<T>>);
  STATIC_REQUIRE_FALSE(mpr::TileRaySampler<BlackRows<T>>);
  STATIC_REQUIRE(mpr::TileRaySampler<BlackTiles<T>>);
  STATIC_REQUIRE_FALSE(mpr::BatchRaySampler<BlackTiles<T>>);
  STATIC_REQUIRE_FALSE(mpr::BatchRaySampler<Black<T>>);
  STATIC_REQUIRE_FALSE(mpr::BatchRaySampler<ThrowingRows<T>>);
  STATIC_REQUIRE_FALSE(mpr::TileRaySampler<Depth<T>>);
  STATIC_REQUIRE(mpr::GridRaySampler<BlackGrids<T>>);
  STATIC_REQUIRE_FALSE(mpr::GridRaySampler<BlackTiles<T>>);
  STATIC_REQUIRE_FALSE(mpr::GridRaySampler<GridWithoutTiles<T>>);
  STATIC_REQUIRE_FALSE(mpr::GridRaySampler<GridReturnsVoid<T>>);
  // Affine surfaces and selectors: the plane and the GLC; a curved or projective surface is not.
  STATIC_REQUIRE(mpr::AffineSurface<mpr::PlanarSurface<T>>);
  STATIC_REQUIRE_FALSE(mpr::AffineSurface<ConstantSurface<T>>);
  STATIC_REQUIRE_FALSE(mpr::AffineSurface<mpr::HomographySurface<T>>);
  STATIC_REQUIRE(mpr::AffineSelector<mpr::GlcSelector<T>>);
  STATIC_REQUIRE_FALSE(mpr::AffineSelector<AlongZ<T>>);
  STATIC_REQUIRE(mpr::kBatchRays == 256);
  STATIC_REQUIRE(mpr::kTileRows == 8);
}
