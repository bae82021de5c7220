// mpr-view's test helper: compares a rectangle of two PNGs (screenshots of the window).
//   png_compare differ|same A.png B.png [picture|hud|X,Y,W,H]
// "picture" is everything above the HUD bar, "hud" the bar (its height as overlay.hpp's
// hud_height). Exits 0 when the rectangles differ (differ) or are identical (same), 1 otherwise,
// printing how many pixels differ.
#include "../font.hpp"

#include <mpr/io/image_io.hpp>

#include <cstdio>
#include <exception>
#include <string>

int main(int argc, char** argv) try {
  if (argc < 4 || argc > 5 || (std::string(argv[1]) != "differ" && std::string(argv[1]) != "same")) {
    std::fprintf(stderr, "usage: png_compare differ|same A.png B.png [picture|hud|X,Y,W,H]\n");
    return 2;
  }
  const mpr::Image<mpr::Rgb8> a = mpr::read_rgb8(argv[2]), b = mpr::read_rgb8(argv[3]);
  if (a.width() != b.width() || a.height() != b.height()) {
    std::printf("sizes differ: %dx%d and %dx%d\n", a.width(), a.height(), b.width(), b.height());
    return std::string(argv[1]) == "differ" ? 0 : 1;
  }
  int x = 0, y = 0, w = a.width(), h = a.height();
  const std::string region = argc == 5 ? argv[4] : "all";
  const int bar = mpr_view::hud_height(a.width());
  if (region == "picture") {
    h -= bar;
  } else if (region == "hud") {
    y = h - bar;
    h = bar;
  } else if (region != "all" && std::sscanf(region.c_str(), "%d,%d,%d,%d", &x, &y, &w, &h) != 4) {
    std::fprintf(stderr, "png_compare: bad region '%s'\n", region.c_str());
    return 2;
  }
  long differing = 0;
  for (int py = std::max(y, 0); py < std::min(y + h, a.height()); ++py)
    for (int px = std::max(x, 0); px < std::min(x + w, a.width()); ++px)
      if (!(a(px, py) == b(px, py))) ++differing;
  std::printf("%s %s (%s): %ld pixels differ\n", argv[2], argv[3], region.c_str(), differing);
  return (differing > 0) == (std::string(argv[1]) == "differ") ? 0 : 1;
} catch (const std::exception& e) {
  std::fprintf(stderr, "png_compare: %s\n", e.what());
  return 2;
}
