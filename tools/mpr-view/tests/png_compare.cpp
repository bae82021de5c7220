// mpr-view's test helper: compares a rectangle of two PNGs (screenshots of the window).
//   png_compare differ|same|sharper A.png B.png [picture|hud|X:Y:W:H]
//   png_compare size A.png WxH
// "picture" is everything above the HUD bar, "hud" the bar (its height as font.hpp's
// hud_height). Exits 0 when the rectangles differ (differ), are identical (same), or A's has
// more detail than B's (sharper: the sum of squared differences between neighbouring pixels),
// 1 otherwise, printing the figures.
#include "../font.hpp"

#include <mpr/io/image_io.hpp>

#include <cstdio>
#include <exception>
#include <string>

int main(int argc, char** argv) try {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "size" && argc == 4) { // exit 0 when A.png is W x H pixels
    const mpr::Image<mpr::Rgb8> a = mpr::read_rgb8(argv[2]);
    const std::string size = std::to_string(a.width()) + "x" + std::to_string(a.height());
    std::printf("%s: %s, expected %s\n", argv[2], size.c_str(), argv[3]);
    return size == argv[3] ? 0 : 1;
  }
  if (argc < 4 || argc > 5 || (mode != "differ" && mode != "same" && mode != "sharper")) {
    std::fprintf(stderr, "usage: png_compare differ|same|sharper A.png B.png [picture|hud|X:Y:W:H]\n");
    return 2;
  }
  const mpr::Image<mpr::Rgb8> a = mpr::read_rgb8(argv[2]), b = mpr::read_rgb8(argv[3]);
  if (a.width() != b.width() || a.height() != b.height()) {
    std::printf("sizes differ: %dx%d and %dx%d\n", a.width(), a.height(), b.width(), b.height());
    return mode == "differ" ? 0 : 1;
  }
  int x = 0, y = 0, w = a.width(), h = a.height();
  const std::string region = argc == 5 ? argv[4] : "all";
  const int bar = mpr_view::hud_height(a.width());
  if (region == "picture") {
    h -= bar;
  } else if (region == "hud") {
    y = h - bar;
    h = bar;
  } else if (region != "all" && std::sscanf(region.c_str(), "%d:%d:%d:%d", &x, &y, &w, &h) != 4) {
    std::fprintf(stderr, "png_compare: bad region '%s'\n", region.c_str());
    return 2;
  }
  if (mode == "sharper") {
    const auto detail = [&](const mpr::Image<mpr::Rgb8>& im) {
      double sum = 0;
      const auto luma = [&](int px, int py) {
        const mpr::Rgb8 p = im(px, py);
        return 0.25 * p.r + 0.5 * p.g + 0.25 * p.b;
      };
      for (int py = std::max(y, 0); py + 1 < std::min(y + h, im.height()); ++py)
        for (int px = std::max(x, 0); px + 1 < std::min(x + w, im.width()); ++px) {
          const double dx = luma(px + 1, py) - luma(px, py), dy = luma(px, py + 1) - luma(px, py);
          sum += dx * dx + dy * dy;
        }
      return sum;
    };
    const double da = detail(a), db = detail(b);
    std::printf("%s %s (%s): detail %.0f and %.0f\n", argv[2], argv[3], region.c_str(), da, db);
    return da > db ? 0 : 1;
  }
  long differing = 0;
  for (int py = std::max(y, 0); py < std::min(y + h, a.height()); ++py)
    for (int px = std::max(x, 0); px < std::min(x + w, a.width()); ++px)
      if (!(a(px, py) == b(px, py))) ++differing;
  std::printf("%s %s (%s): %ld pixels differ\n", argv[2], argv[3], region.c_str(), differing);
  return (differing > 0) == (mode == "differ") ? 0 : 1;
} catch (const std::exception& e) {
  std::fprintf(stderr, "png_compare: %s\n", e.what());
  return 2;
}
