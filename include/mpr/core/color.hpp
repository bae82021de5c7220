#pragma once
/// \file
/// Colour types and the exact conversions between linear `Color` and 8-bit sRGB `Rgb8`.
///
/// Conventions:
/// - `mpr::Color` is *linear* RGB (radiance-proportional), nominally in [0, 1]; samplers average
///   and interpolate in this space.
/// - `mpr::Rgb8` is 8-bit *sRGB-encoded* RGB, the encoding of ordinary PNG/JPEG files.
/// - `to_rgb8(Color)` clamps to [0, 1] (NaN becomes 0), applies the sRGB transfer function
///   (IEC 61966-2-1) and rounds to nearest. It is exact: the result equals
///   `round(255 * encode(x))` evaluated in real arithmetic, and `to_rgb8(to_color(p)) == p` for
///   every 8-bit value.

#include <Eigen/Core>
#include <mpr/core/kernels/srgb_encode.hpp>
#include <mpr/core/simd.hpp>

#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>

namespace mpr {

/// Linear RGB colour.
using Color = Eigen::Array3f;

/// An 8-bit sRGB-encoded RGB pixel.
struct Rgb8 {
  std::uint8_t r = 0;
  std::uint8_t g = 0;
  std::uint8_t b = 0;
  friend constexpr bool operator==(const Rgb8&, const Rgb8&) = default;
};

/// sRGB decoding of an encoded value in [0, 1] to linear, in double precision.
[[nodiscard]] inline double srgb_decode(double encoded) noexcept {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

/// sRGB encoding of a linear value in [0, 1], in double precision.
[[nodiscard]] inline double srgb_encode(double linear) noexcept {
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

namespace detail {

/// Tables for the exact 8-bit conversions (built once at start-up).
struct SrgbTables {
  /// Linear value of each 8-bit code.
  std::array<float, 256> decoded{};
  /// threshold[k]: the smallest float x with round(255 * encode(x)) > k; +inf for k = 255.
  std::array<float, 256> threshold{};
  /// bin_start[i]: the 8-bit code of the lower edge i / kBins of bin i.
  static constexpr int kBins = 8192;
  std::array<std::uint8_t, kBins> bin_start{};
  /// bin_entry[i]: bin i's code at its lower edge (bits 0-7) and, in bits 8-31, where in the bin
  /// its threshold lies as a fraction f of the bin in units of 2^-23 (2^23 when the bin holds
  /// none): x of bin i is above the threshold exactly when trunc((x kBins - i) 2^23) >= f. Exact
  /// because x kBins - i is computed without rounding and, for i >= 1 (x >= 2^-13, so x has no
  /// bits below 2^-36), is a multiple of 2^-23; bin 0 holds no threshold (the first is 1.5e-4).
  /// The AVX2 encoder reads one such entry (one gather) per channel, the AVX-512 one only for
  /// the channels its polynomial leaves undecided.
  std::array<std::uint32_t, kBins> bin_entry{};
  /// The AVX-512 encoder's estimate of 255 encode(x) above the linear segment (x > 0.0031308):
  /// per half octave i = 2 (e + 9) + h of x = 2^e m (e in [-9, -1], m in [1, 2), h = 1 when m >=
  /// 1.5), a degree-4 polynomial in t = m - 1.25 - h / 2 (t in [-0.25, 0.25)), poly[d][i] the
  /// coefficient of t^d, interpolating at the Chebyshev nodes (i = 0, wholly in the linear
  /// segment, is zero; i = 1 from 0.0031308 on). Within 2e-4 of a code (evaluated in float,
  /// checked over every float in tests/core/kernels/srgb_encode_test.cpp), so away from k + 1/2
  /// its nearest integer is the code.
  static constexpr int kPolyDegree = 4, kHalfOctaves = 18;
  std::array<std::array<float, 32>, kPolyDegree + 1> poly{};

  SrgbTables() noexcept {
    for (int k = 0; k < 256; ++k) decoded[k] = static_cast<float>(srgb_decode(k / 255.0));
    for (int k = 0; k < 255; ++k) {
      // The real boundary between codes k and k+1, rounded *up* to a float, so that the float
      // comparison `x >= threshold[k]` is the exact real comparison.
      const double boundary = srgb_decode((k + 0.5) / 255.0);
      float f = static_cast<float>(boundary);
      if (static_cast<double>(f) < boundary) f = std::nextafter(f, std::numeric_limits<float>::infinity());
      threshold[k] = f;
    }
    threshold[255] = std::numeric_limits<float>::infinity();
    // Thresholds are at least 1/255/12.92 = 3.0e-4 apart, wider than a bin (1.2e-4), so each bin
    // holds at most one threshold and one comparison finishes the lookup.
    int k = 0;
    for (int i = 0; i < kBins; ++i) {
      const float edge = static_cast<float>(i) / kBins;
      while (edge >= threshold[k]) ++k;
      bin_start[i] = static_cast<std::uint8_t>(k);
    }
    for (int i = 0; i < kBins; ++i) {
      const int code = bin_start[static_cast<std::size_t>(i)];
      const float t = threshold[static_cast<std::size_t>(code)];
      std::uint32_t split = 1u << 23;
      if (t < static_cast<float>(i + 1) / kBins) // the threshold lies in bin i (exact products)
        split = static_cast<std::uint32_t>((t * kBins - static_cast<float>(i)) * 0x1p23f);
      bin_entry[static_cast<std::size_t>(i)] = static_cast<std::uint32_t>(code) | (split << 8);
    }
    for (int i = 1; i < kHalfOctaves; ++i) fit_half_octave(i);
  }

private:
  // poly[.][i]: the polynomial through 255 encode(x) at the kPolyDegree + 1 Chebyshev nodes of
  // the used part of half octave i (see `poly`), solved in double (Gauss-Jordan).
  void fit_half_octave(int i) noexcept {
    constexpr int n = kPolyDegree + 1;
    const int e = i / 2 - 9, h = i % 2;
    const double centre = 1.25 + 0.5 * h, lo = i == 1 ? std::ldexp(0.0031308, -e) : centre - 0.25;
    const double hi = centre + 0.25, pi = 3.14159265358979323846;
    std::array<std::array<double, n + 1>, n> a{};
    for (int r = 0; r < n; ++r) {
      const double m = 0.5 * (lo + hi) + 0.5 * (hi - lo) * std::cos(pi * (r + 0.5) / n);
      double power = 1;
      for (int d = 0; d < n; ++d, power *= m - centre) a[r][d] = power;
      a[r][n] = 255 * srgb_encode(std::ldexp(m, e));
    }
    for (int c = 0; c < n; ++c) // the nodes are distinct: no pivot is zero
      for (int r = 0; r < n; ++r)
        if (r != c) {
          const double f = a[r][c] / a[c][c];
          for (int k = c; k <= n; ++k) a[r][k] -= f * a[c][k];
        }
    for (int d = 0; d < n; ++d) poly[d][i] = static_cast<float>(a[d][n] / a[d][d]);
  }
};

inline const SrgbTables srgb_tables{};

} // namespace detail

/// Exact linear-to-8-bit sRGB conversion of one channel (see the file comment).
[[nodiscard]] inline std::uint8_t linear_to_srgb8(float linear) noexcept {
  if (!(linear > 0.0f)) return 0; // also NaN
  if (linear >= 1.0f) return 255;
  const auto& t = detail::srgb_tables;
  // linear < 1, so linear * kBins < kBins exactly (a power-of-two scaling).
  const int k = t.bin_start[static_cast<int>(linear * static_cast<float>(detail::SrgbTables::kBins))];
  return static_cast<std::uint8_t>(k + (linear >= t.threshold[k] ? 1 : 0));
}

/// `linear_to_srgb8` over m channels (`out[j]` from `in[j]`), compiled for `level` (default:
/// the widest this CPU runs); 16 channels at a time with AVX-512, 8 with AVX2
/// (core/kernels/srgb_encode.hpp). The same codes at every level.
inline void linear_to_srgb8_row(const float* in, std::uint8_t* out, std::size_t m,
                                detail::SimdLevel level = detail::dispatch_level()) noexcept {
  detail::run_at(level, [&](auto tag) MPR_INLINE_LAMBDA {
    const auto& t = detail::srgb_tables;
    std::size_t j =
        detail::linear_to_srgb8_step(tag, in, out, m, t.bin_entry.data(), detail::SrgbTables::kBins, t.poly[0].data());
    for (; j < m; ++j) out[j] = linear_to_srgb8(in[j]);
  });
}

/// 8-bit sRGB to linear conversion of one channel (a table lookup).
[[nodiscard]] inline float srgb8_to_linear(std::uint8_t code) noexcept { return detail::srgb_tables.decoded[code]; }

/// Linear `Color` to 8-bit sRGB, clamping to [0, 1]; NaN channels become 0.
[[nodiscard]] inline Rgb8 to_rgb8(const Color& c) noexcept {
  return {linear_to_srgb8(c[0]), linear_to_srgb8(c[1]), linear_to_srgb8(c[2])};
}

/// 8-bit sRGB to linear `Color`.
[[nodiscard]] inline Color to_color(const Rgb8& p) noexcept {
  return {srgb8_to_linear(p.r), srgb8_to_linear(p.g), srgb8_to_linear(p.b)};
}

/// Converts what a sampler returns into a stored pixel. Specialise it (or add `from_color`
/// overloads) to store another pixel type or to accept a sampler's own colour type. A
/// specialisation may also offer `from_colors(const C*, Px*, std::size_t n)`, the same
/// conversion for n pixels at once, which the renderer then uses for whole rows.
template <class Px>
struct PixelTraits;

/// 8-bit sRGB pixels: linear colour is encoded with `to_rgb8`; a whole row at once with
/// `linear_to_srgb8_row` (the same codes, vectorised).
template <>
struct PixelTraits<Rgb8> {
  [[nodiscard]] static Rgb8 from_color(const Color& c) noexcept { return to_rgb8(c); }
  static void from_colors(const Color* colors, Rgb8* out, std::size_t n) noexcept {
    // Both are packed channel triples: one flat conversion of 3n channels, into the row as bytes
    // (`&out[0].r` names a one-byte member, against which GCC 12 checks the 3n writes).
    static_assert(sizeof(Rgb8) == 3 && sizeof(Color) == 3 * sizeof(float));
    if (n > 0) linear_to_srgb8_row(colors[0].data(), reinterpret_cast<std::uint8_t*>(out), 3 * n);
  }
};

/// Linear float pixels: stored unchanged (no clamping, so HDR values survive).
template <>
struct PixelTraits<Color> {
  [[nodiscard]] static Color from_color(const Color& c) noexcept { return c; }
};

/// Scalar float pixels (depth, luminance, masks): a sampler whose colour type is `float` stores
/// it unchanged; a linear `Color` is stored as its Rec. 709 luminance.
template <>
struct PixelTraits<float> {
  [[nodiscard]] static float from_color(float value) noexcept { return value; }
  [[nodiscard]] static float from_color(const Color& c) noexcept {
    return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
  }
};

/// `Px` can store the colour type `C`.
template <class Px, class C>
concept StorableAs = requires(const C& c) {
  { PixelTraits<Px>::from_color(c) } -> std::same_as<Px>;
};

} // namespace mpr
