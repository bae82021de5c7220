#pragma once
/// \file
/// Image error metrics for comparing renders against ground truth: RMSE, PSNR, per-pixel error
/// percentiles and SSIM, on 8-bit sRGB images (the form in which results are published).

#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

namespace mpr {

/// Errors of an image against a reference, in 8-bit code units (0..255).
struct ImageError {
  /// Root mean square of the channel differences over all compared pixels.
  double rmse = 0;
  /// 20 log10(255 / rmse) in dB; +infinity for identical images.
  double psnr = std::numeric_limits<double>::infinity();
  /// 99th percentile of the per-pixel error (RMS over the three channels).
  double p99 = 0;
  /// Largest per-pixel error.
  double max = 0;
  /// Number of pixels compared.
  long long pixels = 0;
};

namespace detail {
inline void require_same_size(int aw, int ah, int bw, int bh) {
  if (aw != bw || ah != bh) throw argument_error("image", "sizes differ: compared images must have the same size");
  if (aw == 0 || ah == 0) throw argument_error("image", "empty");
}
} // namespace detail

/// Errors of `image` against `reference`, optionally only where `mask` is non-zero (e.g. pixels
/// that a held-out camera actually sees). Throws `argument_error` for different sizes, empty
/// images or an empty mask.
[[nodiscard]] inline ImageError compare_images(ImageView<const Rgb8> image, ImageView<const Rgb8> reference,
                                               std::optional<ImageView<const std::uint8_t>> mask = std::nullopt) {
  detail::require_same_size(image.width(), image.height(), reference.width(), reference.height());
  if (mask) detail::require_same_size(image.width(), image.height(), mask->width(), mask->height());
  std::vector<double> per_pixel;
  per_pixel.reserve(static_cast<std::size_t>(image.width()) * image.height());
  double sum = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      if (mask && (*mask)(x, y) == 0) continue;
      const Rgb8 a = image(x, y), b = reference(x, y);
      const double dr = double(a.r) - b.r, dg = double(a.g) - b.g, db = double(a.b) - b.b;
      const double squared = dr * dr + dg * dg + db * db;
      sum += squared;
      per_pixel.push_back(std::sqrt(squared / 3));
    }
  if (per_pixel.empty()) throw argument_error("mask", "selects no pixel");
  ImageError e;
  e.pixels = static_cast<long long>(per_pixel.size());
  e.rmse = std::sqrt(sum / (3.0 * static_cast<double>(per_pixel.size())));
  e.psnr = e.rmse > 0 ? 20 * std::log10(255 / e.rmse) : std::numeric_limits<double>::infinity();
  const std::size_t k = static_cast<std::size_t>(std::ceil(0.99 * static_cast<double>(per_pixel.size()))) - 1;
  std::nth_element(per_pixel.begin(), per_pixel.begin() + static_cast<std::ptrdiff_t>(k), per_pixel.end());
  e.p99 = per_pixel[k];
  e.max = *std::max_element(per_pixel.begin(), per_pixel.end());
  return e;
}

/// Mean structural similarity (Wang, Bovik, Sheikh & Simoncelli, IEEE TIP 2004) of the Rec. 601
/// luma of two 8-bit images, with the usual constants (K1 = 0.01, K2 = 0.03, L = 255) over
/// 8x8 windows stepped by 4 pixels (uniform weights). 1 for identical images.
[[nodiscard]] inline double ssim(ImageView<const Rgb8> image, ImageView<const Rgb8> reference) {
  detail::require_same_size(image.width(), image.height(), reference.width(), reference.height());
  const auto luma = [](const Rgb8& p) { return 0.299 * p.r + 0.587 * p.g + 0.114 * p.b; };
  constexpr int window = 8, step = 4;
  constexpr double c1 = (0.01 * 255) * (0.01 * 255), c2 = (0.03 * 255) * (0.03 * 255);
  if (image.width() < window || image.height() < window)
    throw argument_error("image", "smaller than the 8x8 SSIM window");
  double total = 0;
  long long windows = 0;
  for (int y0 = 0; y0 + window <= image.height(); y0 += step)
    for (int x0 = 0; x0 + window <= image.width(); x0 += step) {
      double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
      for (int y = y0; y < y0 + window; ++y)
        for (int x = x0; x < x0 + window; ++x) {
          const double a = luma(image(x, y)), b = luma(reference(x, y));
          sa += a, sb += b, saa += a * a, sbb += b * b, sab += a * b;
        }
      constexpr double n = window * window;
      const double ma = sa / n, mb = sb / n;
      const double va = saa / n - ma * ma, vb = sbb / n - mb * mb, cov = sab / n - ma * mb;
      total += ((2 * ma * mb + c1) * (2 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
      ++windows;
    }
  return total / static_cast<double>(windows);
}

} // namespace mpr
