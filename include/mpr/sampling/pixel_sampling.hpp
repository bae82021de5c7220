#pragma once
/// \file
/// Pixel sampling, the fourth compile-time policy of `mpr::Renderer`: where in each pixel the
/// rays start and how their colours combine into the pixel's colour.
///
/// - `PixelCentre` (the default): one ray through the pixel centre, today's images bit for bit.
/// - `Supersample<Pattern, Filter>`: `pattern.count()` rays per pixel at the pattern's points,
///   spread over the reconstruction filter's footprint (the square of half-width
///   `filter.radius()` pixels about the pixel centre, clipped to the view's region), combined as
///   the weighted average `sum(w_i f_i) / sum(w_i)` with `w_i = filter.evaluate(dx_i, dy_i)`, the
///   filter at the sample's offset from the pixel centre in pixels. Every pixel gathers its own
///   samples, so an image is identical for every thread count and tile size.
///
/// Patterns (`PixelSamplePattern`): `Stratified` (stratified.hpp) and `OwenSobol` (sobol.hpp).
/// Filters (`ReconstructionFilter`): filters.hpp and any_filter.hpp.

#include <mpr/core/error.hpp>
#include <mpr/core/pixel.hpp>
#include <mpr/core/ray.hpp>
#include <mpr/core/vec.hpp>

#include <concepts>
#include <cstdint>
#include <type_traits>
#include <utility>

namespace mpr {

/// A sample position in the unit square [0, 1)^2 of a pixel's sampling domain, x to the right,
/// y down.
struct SamplePoint {
  double x = 0.5;
  double y = 0.5;
  friend constexpr bool operator==(const SamplePoint&, const SamplePoint&) = default;
};

// clang-format off

/// A pixel sample pattern: `count()` points per pixel (>= 1), `point(pixel, i)` the i-th of them
/// for `i` in [0, count()), in [0, 1)^2. `pixel` is relative to the view's region (its top-left
/// pixel is (0, 0)), so a view samples the same wherever it is placed. Deterministic: the same
/// arguments always give the same point (no state, no thread dependence).
template <class P>
concept PixelSamplePattern = std::copy_constructible<P> && requires(const P& p, Pixel px, int i) {
  { p.count() } noexcept -> std::same_as<int>;
  { p.point(px, i) } noexcept -> std::same_as<SamplePoint>;
};

/// A pattern that also gives each sample a second 2-D point, `lens_point(pixel, i)` in [0, 1)^2,
/// for selectors that integrate over an aperture (`LensRaySelector`). The lens points of a pixel
/// are spread as well as its image points and decorrelated from them.
template <class P>
concept LensSamplePattern = PixelSamplePattern<P> && requires(const P& p, Pixel px, int i) {
  { p.lens_point(px, i) } noexcept -> std::same_as<SamplePoint>;
};

/// A ray selector with a finite aperture: `ray_at(pixel, uv, point, lens)` is the ray of the
/// aperture sample `lens` (in [0, 1)^2) and `ray_at(pixel, uv, point)` its central (pinhole) ray,
/// used under `PixelCentre`. Under a `Supersample` policy the renderer passes each sample's
/// `lens_point`.
template <class S>
concept LensRaySelector = requires(const S& s, Pixel px, const Vec2<typename S::scalar_type>& uv,
                                   const Vec3<typename S::scalar_type>& point, SamplePoint lens) {
  { s.ray_at(px, uv, point, lens) } noexcept -> std::same_as<Ray<typename S::scalar_type>>;
};

/// A reconstruction filter: `radius()` (pixels, > 0) is the half-width of its square support and
/// `evaluate(dx, dy)` its weight at offset (dx, dy) pixels from the pixel centre (0 outside the
/// support; may be negative, e.g. Mitchell's lobes).
template <class F>
concept ReconstructionFilter = std::copy_constructible<F> && requires(const F& f, double dx, double dy) {
  { f.radius() } noexcept -> std::same_as<double>;
  { f.evaluate(dx, dy) } noexcept -> std::same_as<double>;
};

/// A supersampling policy: a pattern and a filter (as `Supersample` holds them).
template <class S>
concept SupersamplingPolicy = requires(const S& s) {
  { s.pattern() } noexcept;
  { s.filter() } noexcept;
} && PixelSamplePattern<std::remove_cvref_t<decltype(std::declval<const S&>().pattern())>>
  && ReconstructionFilter<std::remove_cvref_t<decltype(std::declval<const S&>().filter())>>;

// clang-format on

/// The default pixel sampling: one ray through each pixel centre (uv of `Region::pixel_to_uv`).
struct PixelCentre {};

/// The pixel-sampling role of `mpr::Renderer`: `PixelCentre` or a `SupersamplingPolicy`.
template <class S>
concept PixelSampling = std::same_as<S, PixelCentre> || SupersamplingPolicy<S>;

/// The box filter of radius 0.5: every sample in the pixel weighs 1 (the plain pixel average).
/// (The other filters and their pbrt-v4 defaults are in filters.hpp.)
class BoxFilter {
public:
  static constexpr bool nonnegative = true;
  /// Throws `argument_error` naming "filter radius" unless `radius` is finite and > 0.
  explicit BoxFilter(double radius = 0.5) : radius_(radius) {
    if (!(radius > 0) || !(radius < 1e6)) throw argument_error("filter radius", "must be finite and > 0");
  }
  [[nodiscard]] double radius() const noexcept { return radius_; }
  [[nodiscard]] double evaluate(double dx, double dy) const noexcept {
    return (dx >= -radius_ && dx <= radius_ && dy >= -radius_ && dy <= radius_) ? 1.0 : 0.0;
  }

private:
  double radius_;
};

/// `pattern.count()` samples per pixel over the footprint of `filter`, combined by the filter's
/// weights (see the file comment). Holds both by value.
template <PixelSamplePattern Pattern, ReconstructionFilter Filter = BoxFilter>
class Supersample {
public:
  using pattern_type = Pattern;
  using filter_type = Filter;

  explicit Supersample(Pattern pattern, Filter filter = Filter())
      : pattern_(std::move(pattern)), filter_(std::move(filter)) {}

  [[nodiscard]] const Pattern& pattern() const noexcept { return pattern_; }
  [[nodiscard]] const Filter& filter() const noexcept { return filter_; }

private:
  Pattern pattern_;
  Filter filter_;
};

namespace detail {

/// A 32-bit integer hash with good avalanche (xor-shift-multiply finaliser).
[[nodiscard]] constexpr std::uint32_t mix32(std::uint32_t x) noexcept {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

/// The seed of pixel `px` (region coordinates) for a pattern seeded with `seed`.
[[nodiscard]] constexpr std::uint32_t pixel_seed(Pixel px, std::uint32_t seed) noexcept {
  return mix32(static_cast<std::uint32_t>(px.x) * 0x9e3779b1U ^ mix32(static_cast<std::uint32_t>(px.y) + seed));
}

/// The low `bits` bits of `v` in reverse order (bit 0 becomes bit `bits - 1`).
[[nodiscard]] constexpr std::uint32_t reverse_low_bits(std::uint32_t v, int bits) noexcept {
  std::uint32_t r = 0;
  for (int b = 0; b < bits; ++b) r |= ((v >> b) & 1U) << (bits - 1 - b);
  return r;
}

/// A permutation of [0, count) chosen by `seed` (1 <= count <= 2^30, i < count): within the next
/// power of two 2^m, the index's m bits reversed, hashed so that each bit depends only on the
/// bits below it (addition and multiplication by even constants: a bijection on the low m bits,
/// nested like Owen scrambling), reversed back; then cycle-walked into [0, count) (repeating a
/// bijection from a point inside the range returns inside it, so the result is a bijection).
[[nodiscard]] constexpr std::uint32_t shuffle_index(std::uint32_t i, std::uint32_t count, std::uint32_t seed) noexcept {
  int bits = 0;
  while ((std::uint32_t{1} << bits) < count) ++bits;
  if (bits == 0) return 0;
  const std::uint32_t mask = (std::uint32_t{1} << bits) - 1;
  do {
    std::uint32_t r = reverse_low_bits(i, bits) + seed;
    r ^= r * 0x6c50b47cU;
    r ^= r * 0xb82f1e52U;
    r ^= r * 0xc7afe638U;
    r ^= r * 0x8d22f6e6U;
    i = reverse_low_bits(r & mask, bits);
  } while (i >= count);
  return i;
}

/// `bits` / 2^32: a double in [0, 1), exact.
[[nodiscard]] constexpr double unit_from_bits(std::uint32_t bits) noexcept {
  return static_cast<double>(bits) * (1.0 / 4294967296.0);
}

} // namespace detail

} // namespace mpr
