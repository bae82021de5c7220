#pragma once
// Small synthetic camera arrays for the light-field tests: cameras on a plane looking at a
// textured plane, their images rendered analytically.

#include <mpr/lightfield.hpp>

#include <cstdint>
#include <memory>
#include <random>
#include <vector>

namespace mpr_test {

/// A smooth texture on the plane z = depth: linear in world x and y (so bilinear
/// reconstruction of a fronto-parallel view of it is exact away from the image border).
inline mpr::Color plane_texture(double x, double y) {
  return mpr::Color(static_cast<float>(0.5 + 0.02 * x), static_cast<float>(0.5 + 0.03 * y),
                    static_cast<float>(0.4 + 0.01 * (x - y)));
}

/// A camera at `centre` (R = I, looking along +z), `width` x `height` pixels, focal length
/// `focal`, principal point at the image centre.
template <class T>
mpr::PinholeCamera<T> camera_at(const mpr::Vec3<T>& centre, int width, int height, double focal) {
  mpr::Mat3<T> K = mpr::Mat3<T>::Identity();
  K(0, 0) = K(1, 1) = static_cast<T>(focal);
  K(0, 2) = static_cast<T>(0.5 * (width - 1));
  K(1, 2) = static_cast<T>(0.5 * (height - 1));
  return mpr::PinholeCamera<T>(K, mpr::Mat3<T>::Identity(), mpr::Vec3<T>(-centre), width, height);
}

/// `nx` x `ny` cameras (R = I, looking along +z) spaced `spacing` apart on the plane z = 0,
/// centred on the origin, `width` x `height` pixels, focal length `focal`.
template <class T>
std::vector<mpr::PinholeCamera<T>> grid_cameras(int nx, int ny, double spacing, int width, int height, double focal) {
  std::vector<mpr::PinholeCamera<T>> cameras;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const mpr::Vec3<T> c(static_cast<T>((i - 0.5 * (nx - 1)) * spacing),
                           static_cast<T>((j - 0.5 * (ny - 1)) * spacing), T(0));
      cameras.push_back(camera_at<T>(c, width, height, focal));
    }
  return cameras;
}

/// `linear` as 8-bit frames with fine detail, so that any misplaced sample shows: each pixel's
/// red, green and blue codes XORed with random bits under `mask_r`, `mask_g`, `mask_b` (one draw
/// of `std::mt19937(seed)` per non-zero mask, in that order, pixel after pixel).
inline std::vector<mpr::Image<mpr::Rgb8>> with_detail(const std::vector<mpr::Image<mpr::Color>>& linear, unsigned seed,
                                                      unsigned mask_r, unsigned mask_g, unsigned mask_b) {
  std::vector<mpr::Image<mpr::Rgb8>> images;
  std::mt19937 rng(seed);
  const auto xored = [&](std::uint8_t code, unsigned mask) {
    return mask == 0 ? code : static_cast<std::uint8_t>(code ^ (rng() & mask));
  };
  for (const auto& img : linear) {
    mpr::Image<mpr::Rgb8> px(img.width(), img.height());
    for (int y = 0; y < img.height(); ++y)
      for (int x = 0; x < img.width(); ++x) {
        mpr::Rgb8 c = mpr::to_rgb8(img(x, y));
        c.r = xored(c.r, mask_r);
        c.g = xored(c.g, mask_g);
        c.b = xored(c.b, mask_b);
        px(x, y) = c;
      }
    images.push_back(std::move(px));
  }
  return images;
}

/// Images of the textured plane z = `depth` seen by `cameras` (linear colour).
template <class T>
std::vector<mpr::Image<mpr::Color>> plane_images(const std::vector<mpr::PinholeCamera<T>>& cameras, double depth) {
  std::vector<mpr::Image<mpr::Color>> images;
  for (const auto& cam : cameras) {
    mpr::Image<mpr::Color> img(cam.width(), cam.height());
    const mpr::PinholeCamera<double> c(cam.K().template cast<double>(), cam.R().template cast<double>(),
                                       cam.t().template cast<double>(), cam.width(), cam.height());
    for (int y = 0; y < cam.height(); ++y)
      for (int x = 0; x < cam.width(); ++x) {
        const mpr::Ray<double> r = c.ray_through({x, y});
        const double t = (depth - r.origin.z()) / r.direction.z();
        const mpr::Vec3<double> p = r.at(t);
        img(x, y) = plane_texture(p.x(), p.y());
      }
    images.push_back(std::move(img));
  }
  return images;
}

/// The tilted plane z = z0 + a x + b y (world frame), carrying `plane_texture`: unlike the plane
/// z = depth its depth varies across every image, so depth maps of it are not constant and a
/// lookup that ignores the position inside a pixel, or a crossing taken at the wrong depth, shows.
struct TiltedPlane {
  double z0 = 5, a = 0.3, b = -0.2;

  /// Closed-form crossing of the ray o + t d with the plane: t = (z0 + a ox + b oy - oz) /
  /// (dz - a dx - b dy); NaN or infinite when the ray is parallel to it.
  [[nodiscard]] double hit_t(const mpr::Vec3<double>& o, const mpr::Vec3<double>& d) const {
    return (z0 + a * o.x() + b * o.y() - o.z()) / (d.z() - a * d.x() - b * d.y());
  }
};

/// Images of `plane` seen by `cameras` (linear colour), each pixel the texture where its centre's
/// ray meets the plane; with `depths`, also each camera's depth map (camera z of that point:
/// the world z, for cameras with R = I on z = 0).
template <class T>
std::vector<mpr::Image<mpr::Color>> tilted_plane_images(const std::vector<mpr::PinholeCamera<T>>& cameras,
                                                        const TiltedPlane& plane,
                                                        std::vector<mpr::Image<float>>* depths = nullptr) {
  std::vector<mpr::Image<mpr::Color>> images;
  for (const auto& cam : cameras) {
    mpr::Image<mpr::Color> img(cam.width(), cam.height());
    mpr::Image<float> depth(cam.width(), cam.height());
    const mpr::PinholeCamera<double> c(cam.K().template cast<double>(), cam.R().template cast<double>(),
                                       cam.t().template cast<double>(), cam.width(), cam.height());
    for (int y = 0; y < cam.height(); ++y)
      for (int x = 0; x < cam.width(); ++x) {
        const mpr::Ray<double> r = c.ray_through({x, y});
        const mpr::Vec3<double> p = r.at(plane.hit_t(r.origin, r.direction));
        img(x, y) = plane_texture(p.x(), p.y());
        depth(x, y) = static_cast<float>(p.z());
      }
    images.push_back(std::move(img));
    if (depths != nullptr) depths->push_back(std::move(depth));
  }
  return images;
}

/// Camera i's constant colour: channels are multiples of 1/16 (exact in float) taken from
/// quadratic and cubic residues of i, so they are neither linear nor symmetric in i. With colours
/// linear in i the mean of a symmetric set of cameras equals the middle camera's colour, and a
/// path that dropped the middle camera (or any symmetric pair) would go unnoticed; here every
/// leave-one-out and leave-two-out mean of the first 4, 9 or 20 cameras differs from the full
/// mean by at least 1/320 in some channel (checked by `constant_colour_is_asymmetric`).
/// For 3 x 3 cameras the mean is exactly (11/24, 4/9, 19/48); for 4 cameras (3/8, 1/2, 3/8).
inline mpr::Color constant_colour(std::size_t i, std::size_t /*n*/ = 0) {
  const auto k = static_cast<long>(i);
  return mpr::Color(static_cast<float>((5 * k * k + 3 * k + 1) % 17) / 16.0f,
                    static_cast<float>((3 * k * k * k + 7) % 13) / 16.0f,
                    static_cast<float>((k * k + 2 * k + 5) % 11) / 16.0f);
}

/// Constant images: camera i shows `constant_colour(i)` everywhere.
template <class T>
std::vector<mpr::Image<mpr::Color>> constant_images(const std::vector<mpr::PinholeCamera<T>>& cameras) {
  std::vector<mpr::Image<mpr::Color>> images;
  for (std::size_t i = 0; i < cameras.size(); ++i)
    images.emplace_back(cameras[i].width(), cameras[i].height(), constant_colour(i));
  return images;
}

/// True when no mean of the first n constant colours with one or two of them left out equals
/// (within `tolerance` in every channel) the mean of all n: the property that makes a dropped
/// camera visible in an average.
inline bool constant_colour_is_asymmetric(std::size_t n, float tolerance) {
  mpr::Color all = mpr::Color::Zero();
  for (std::size_t i = 0; i < n; ++i) all += constant_colour(i);
  const mpr::Color mean = all / static_cast<float>(n);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a; b < n; ++b) {
      const mpr::Color rest = all - constant_colour(a) - (b != a ? constant_colour(b) : mpr::Color::Zero());
      const float left = static_cast<float>(n - (b != a ? 2 : 1));
      if (left > 0 && ((rest / left - mean).abs() <= tolerance).all()) return false;
    }
  return true;
}

} // namespace mpr_test
