#include <mpr/core/image_metrics.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>

TEST_CASE("compare_images: RMSE, PSNR and percentiles", "[metrics]") {
  mpr::Image<mpr::Rgb8> a(10, 10, mpr::Rgb8{100, 100, 100});
  mpr::Image<mpr::Rgb8> b = a;
  const mpr::ImageError same = mpr::compare_images(a.view(), b.view());
  CHECK(same.rmse == 0);
  CHECK(std::isinf(same.psnr));
  CHECK(same.pixels == 100);

  // One pixel off by 30 in every channel: per-pixel error 30, RMSE = sqrt(900/100) = 3.
  b(4, 7) = {130, 70, 130};
  const mpr::ImageError one = mpr::compare_images(a.view(), b.view());
  CHECK(one.rmse == Approx(3.0));
  CHECK(one.psnr == Approx(20 * std::log10(255.0 / 3.0)));
  CHECK(one.max == Approx(30.0));
  CHECK(one.p99 == Approx(0.0)); // 99 of 100 pixels are exact

  // Two bad pixels: the 99th percentile is now the smaller of them.
  b(0, 0) = {110, 110, 110};
  CHECK(mpr::compare_images(a.view(), b.view()).p99 == Approx(10.0));

  // A mask limits the comparison.
  mpr::Image<std::uint8_t> mask(10, 10, 1);
  mask(4, 7) = 0;
  mask(0, 0) = 0;
  CHECK(mpr::compare_images(a.view(), b.view(), mpr::ImageView<const std::uint8_t>(mask.view())).rmse == 0);
  CHECK_THROWS_WITH(mpr::compare_images(a.view(), mpr::Image<mpr::Rgb8>(9, 10).view()),
                    Catch::Contains("sizes differ"));
  const mpr::Image<std::uint8_t> none(10, 10, 0);
  CHECK_THROWS_WITH(mpr::compare_images(a.view(), b.view(), mpr::ImageView<const std::uint8_t>(none.view())),
                    Catch::Contains("mask"));
}

TEST_CASE("ssim is 1 for identical images and drops with noise", "[metrics]") {
  mpr::Image<mpr::Rgb8> a(32, 32), b(32, 32);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      const auto v = static_cast<std::uint8_t>((x * 8 + y * 3) % 256);
      a(x, y) = {v, v, v};
      const auto w = static_cast<std::uint8_t>(std::clamp(v + ((x * 7 + y * 13) % 9 - 4) * 6, 0, 255));
      b(x, y) = {w, w, w};
    }
  CHECK(mpr::ssim(a.view(), a.view()) == Approx(1.0));
  const double noisy = mpr::ssim(a.view(), b.view());
  CHECK(noisy < 0.99);
  CHECK(noisy > 0.3);
}

TEST_CASE("ssim of two aligned checkerboards equals the closed form", "[metrics]") {
  // Grey 1-pixel checkerboards a in {50, 150} and b in {100, 140}, same phase: every 8 x 8 window
  // holds 32 of each value, so every window has the same means (100, 120), variances
  // (50^2, 20^2) and covariance 50 * 20, and the mean SSIM is that of one window.
  mpr::Image<mpr::Rgb8> a(24, 16), b(24, 16);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 24; ++x) {
      const bool odd = (x + y) % 2 == 1;
      const std::uint8_t va = odd ? 150 : 50, vb = odd ? 140 : 100;
      a(x, y) = {va, va, va};
      b(x, y) = {vb, vb, vb};
    }
  const double c1 = (0.01 * 255) * (0.01 * 255), c2 = (0.03 * 255) * (0.03 * 255);
  const double ma = 100, mb = 120, va = 2500, vb = 400, cov = 1000;
  const double expected = ((2 * ma * mb + c1) * (2 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
  CHECK(expected == Approx(0.68439).epsilon(1e-4)); // worked out by hand
  CHECK(mpr::ssim(a.view(), b.view()) == Approx(expected).epsilon(1e-9));
  // Symmetric in its arguments; identical images give exactly 1.
  CHECK(mpr::ssim(b.view(), a.view()) == Approx(expected).epsilon(1e-9));
  CHECK(mpr::ssim(b.view(), b.view()) == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("ssim of coloured images weighs the channels by Rec. 601 luma (hand-worked)", "[metrics]") {
  // Uniform windows: variances and covariance are 0, so SSIM = (2 a b + C1) / (a^2 + b^2 + C1)
  // with C1 = (0.01 * 255)^2 = 6.5025 and a, b the lumas: red 0.299 * 255 = 76.245, green
  // 0.587 * 255 = 149.685, blue 0.114 * 255 = 29.07.
  const mpr::Image<mpr::Rgb8> red(8, 8, mpr::Rgb8{255, 0, 0}), green(8, 8, mpr::Rgb8{0, 255, 0}),
      blue(8, 8, mpr::Rgb8{0, 0, 255});
  // (2 * 76.245 * 149.685 + 6.5025) / (76.245^2 + 149.685^2 + 6.5025) = 22832.38 / 28225.76
  CHECK(mpr::ssim(red.view(), green.view()) == Approx(0.8089156).epsilon(1e-6));
  // (2 * 76.245 * 29.07 + 6.5025) / (76.245^2 + 29.07^2 + 6.5025) = 4439.387 / 6664.913; an
  // unweighted channel mean (85 for both) would give 1.
  CHECK(mpr::ssim(red.view(), blue.view()) == Approx(0.6660878).epsilon(1e-6));
  // Columns alternating red and blue against grey 53: a has mean (76.245 + 29.07) / 2 = 52.6575
  // and variance 23.5875^2 = 556.3702, b none; C2 = (0.03 * 255)^2 = 58.5225.
  // (2 * 52.6575 * 53 + C1) * C2 / ((52.6575^2 + 53^2 + C1) * (556.3702 + C2)) = 0.0951732.
  mpr::Image<mpr::Rgb8> stripes(12, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 12; ++x) stripes(x, y) = x % 2 == 0 ? mpr::Rgb8{255, 0, 0} : mpr::Rgb8{0, 0, 255};
  const mpr::Image<mpr::Rgb8> grey(12, 8, mpr::Rgb8{53, 53, 53});
  CHECK(mpr::ssim(stripes.view(), grey.view()) == Approx(0.0951732).epsilon(1e-5));
}
