#pragma once
/// \file
/// `mpr::CameraFrameSet`: calibrated cameras and the images they took (a light field captured
/// by a camera array, a gantry or a multi-view rig), the data behind `CameraFrameSampler`.

#include <mpr/camera/pinhole_camera.hpp>
#include <mpr/core/color.hpp>
#include <mpr/core/detail/huge_page_allocator.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>
#include <mpr/core/simd.hpp>
#include <mpr/geometry/plane.hpp>
#include <mpr/lightfield/frame_linear16.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace mpr {

/// A linear RGB colour stored as three floats (12 bytes): the sampling-time form of linear
/// (`Color`) frames, which may hold any finite value (HDR, negative). Texels are packed with no
/// padding, so a row of texels is also a flat array of channels (r g b r g b ...): the
/// shift-and-add kernels stream it as such, at any SIMD width.
struct LinearTexel {
  using channel_type = float;
  /// Stored channel value times `scale` is the linear colour.
  static constexpr float scale = 1.0f;
  float c[3];
};

/// An 8-bit sRGB texel as the frame holds it (3 bytes), packed like `LinearTexel`: the
/// sampling-time form of 8-bit frames. Samplers decode each code exactly while reading, through
/// `linear16()`: the code's linear value (the exact table of core/color.hpp) in 16-bit fixed
/// point, colour = `linear16()[c[k]] * scale`, an error below 7.7e-6 (1/500 of the smallest step
/// between sRGB codes in linear), so colours still round-trip through `to_rgb8` exactly. Half the
/// bytes of the 16-bit linear texels it replaced, which matters because a full synthetic
/// aperture reads every texel of every frame and is bound by memory bandwidth; the decode costs
/// a table lookup (vector permutes on AVX-512, see lightfield/kernels/sampler_rows.hpp).
struct Srgb8Texel {
  using channel_type = std::uint8_t;
  /// Decoded value times `scale` is the linear colour.
  static constexpr float scale = 1.0f / 65535.0f;
  std::uint8_t c[3];

  /// The decode table: `linear16()[code]` = round(65535 x linear value of `code`), 256 entries.
  [[nodiscard]] static const std::uint16_t* linear16() noexcept {
    static const std::array<std::uint16_t, 256> table = [] {
      std::array<std::uint16_t, 256> t{};
      for (int v = 0; v < 256; ++v)
        t[static_cast<std::size_t>(v)] = static_cast<std::uint16_t>(
            std::lround(static_cast<double>(srgb8_to_linear(static_cast<std::uint8_t>(v))) * 65535.0));
      return t;
    }();
    return table.data();
  }
};

/// The decode table of a texel type's channels: `Srgb8Texel::linear16()`, or nullptr when the
/// stored channel is the value (`LinearTexel`).
template <class Texel>
[[nodiscard]] const std::uint16_t* texel_decode_table() noexcept {
  if constexpr (std::is_same_v<typename Texel::channel_type, std::uint8_t>)
    return Texel::linear16();
  else
    return nullptr;
}

static_assert(sizeof(LinearTexel) == 3 * sizeof(float) && sizeof(Srgb8Texel) == 3,
              "texels are packed: a texel row is a flat channel array");

/// Camera `i` took image `i`. Images are 8-bit sRGB (`Rgb8`, the default: 3 bytes per pixel,
/// decoded to linear with the exact table of core/color.hpp while sampling) or linear `Color`.
/// Every image has exactly its camera's width and height; different cameras may differ in size.
/// At construction every image is also decoded once into linear texels, which the samplers read:
/// `Srgb8Texel` (3 bytes per pixel) for 8-bit frames, `LinearTexel` (12 bytes) for linear ones;
/// this is the bulk of the memory a frame set takes. An 8-bit image that borrows its pixels
/// (`Image::borrow`, e.g. a numpy array) is not copied at all when its memory allows: its pixels
/// are its texels (the same 3 bytes), read in place (`shares_image`). Below the VBMI level every
/// 8-bit image, borrowed or not, is also held as 16-bit linear values (`linear16`, 6 bytes a
/// pixel), which the synthetic aperture's shift tiles read. Optionally the set carries
/// one depth map per camera (`with_depth`), read only by geometry-aware interpolations
/// (`DepthProxy`). Images, texels and depth maps are immutable once in a set (borrowed memory
/// must not change while a render reads it) and shared: a copy, `without(i)` and `cast<U>()`
/// copy no pixel.
template <std::floating_point T, class Px = Rgb8>
class CameraFrameSet {
  static_assert(std::is_same_v<Px, Rgb8> || std::is_same_v<Px, Color>, "frames are Rgb8 or linear Color");

public:
  using scalar_type = T;
  using pixel_type = Px;
  using camera_type = PinholeCamera<T>;
  /// The texel type the samplers read (see `Srgb8Texel`, `LinearTexel`).
  using texel_type = std::conditional_t<std::is_same_v<Px, Rgb8>, Srgb8Texel, LinearTexel>;
  /// The decoded images, one after another in one buffer (huge pages where the system offers
  /// them, whatever the size of each image).
  using texel_vector = std::vector<texel_type, detail::HugePageAllocator<texel_type>>;

  CameraFrameSet() = default;

  /// Borrowed images are kept borrowed (their owner handles live as long as the set); see
  /// `shares_image` for when their texels are read in place. Throws `argument_error` ("frames")
  /// when the lists differ in length, when `names` is neither
  /// empty nor of the same length, or when an image's size differs from its camera's.
  /// Empty `names` are replaced by "frame <i>".
  CameraFrameSet(std::vector<camera_type> cameras, std::vector<Image<Px>> images, std::vector<std::string> names = {})
      : cameras_(std::move(cameras)), names_(std::move(names)) {
    if (cameras_.size() != images.size())
      throw argument_error("frames", std::to_string(cameras_.size()) + " cameras but " + std::to_string(images.size()) +
                                         " images");
    if (names_.empty())
      for (std::size_t i = 0; i < cameras_.size(); ++i) names_.push_back("frame " + std::to_string(i));
    if (names_.size() != cameras_.size()) throw argument_error("frames", "names and cameras differ in number");
    for (std::size_t i = 0; i < cameras_.size(); ++i)
      if (images[i].width() != cameras_[i].width() || images[i].height() != cameras_[i].height())
        throw argument_error("frames", names_[i] + ": image is " + std::to_string(images[i].width()) + "x" +
                                           std::to_string(images[i].height()) + " but its camera expects " +
                                           std::to_string(cameras_[i].width()) + "x" +
                                           std::to_string(cameras_[i].height()));
    images_.reserve(images.size());
    for (Image<Px>& image : images) images_.push_back(std::make_shared<const Image<Px>>(std::move(image)));
    texels_ = decode(images_, texel_data_);
    if (holds_linear16()) linear16_ = decode_linear16(images_, texel_data_, linear16_data_);
  }

  [[nodiscard]] std::size_t size() const noexcept { return cameras_.size(); }
  [[nodiscard]] bool empty() const noexcept { return cameras_.empty(); }
  [[nodiscard]] const camera_type& camera(std::size_t i) const noexcept { return cameras_[i]; }
  [[nodiscard]] const Image<Px>& image(std::size_t i) const noexcept { return *images_[i]; }
  [[nodiscard]] const std::string& name(std::size_t i) const noexcept { return names_[i]; }
  [[nodiscard]] const std::vector<camera_type>& cameras() const noexcept { return cameras_; }
  [[nodiscard]] const std::vector<std::string>& names() const noexcept { return names_; }
  /// Image `i` as the samplers read it, row-major, `width * height` texels, with at least 64
  /// readable bytes after the last: decoded by the set (starting on a 64-byte boundary), or the
  /// image's own pixels when `shares_image(i)`.
  [[nodiscard]] std::span<const texel_type> texels(std::size_t i) const noexcept {
    return {texel_data_[i],
            static_cast<std::size_t>(images_[i]->width()) * static_cast<std::size_t>(images_[i]->height())};
  }

  /// Image `i`'s channels as 16-bit linear values (`Srgb8Texel::linear16()` of each code of
  /// `texels(i)`, in the same order: 3 per texel), with at least 32 readable values after the
  /// last; nullptr when the set holds none (`holds_linear16`). The shift-and-add kernels read
  /// these instead of decoding codes where no byte-permute decode is available.
  [[nodiscard]] const std::uint16_t* linear16(std::size_t i) const noexcept {
    return linear16_data_.empty() ? nullptr : linear16_data_[i];
  }

  /// Whether a set built at `level` holds its 8-bit frames a second time as 16-bit linear values
  /// (`linear16`, decoded once at construction; 6 more bytes a pixel): for `Rgb8` frames when
  /// Highway is present and `level` is below `avx512vbmi` (the level whose kernels decode codes
  /// with byte permutes, faster than reading twice the bytes). At `portable` and `avx2` a full
  /// Chess refocus takes about 1/2 to 1/3 of the time with them (docs/simd.md).
  [[nodiscard]] static bool holds_linear16(detail::SimdLevel level = detail::dispatch_level()) noexcept {
    return std::is_same_v<Px, Rgb8> && MPR_HAVE_HWY && level < detail::SimdLevel::avx512vbmi;
  }

  /// True when the samplers read image `i`'s pixels in place: the set holds no copy of it, and a
  /// change to the borrowed memory shows in later renders. So for every 8-bit image that borrows
  /// its pixels (`Image::borrow`) and that `can_share`; every other image is decoded into the
  /// set's buffer at construction.
  [[nodiscard]] bool shares_image(std::size_t i) const noexcept {
    return static_cast<const void*>(texel_data_[i]) == static_cast<const void*>(images_[i]->data());
  }

  /// Whether a set would read `image` in place (`shares_image`): an 8-bit image that borrows its
  /// pixels, non-empty, whose 64 bytes after the last pixel are readable. The kernels load whole
  /// words from a texel and may read that far past the last one; the bytes are known readable
  /// when they lie in the 4 KiB block of the last pixel (memory is mapped in pages of 4 KiB or
  /// multiples), so an image is shared unless its end lies in the last 64 bytes of such a block
  /// (1 image in 64 at random addresses), and then decoded like an owned one. Never under
  /// AddressSanitizer (`MPR_ADDRESS_SANITIZER`), which reports reads past an allocation even
  /// within its page.
  [[nodiscard]] static bool can_share(const Image<Px>& image) noexcept {
    if constexpr (!std::is_same_v<Px, Rgb8> || MPR_ADDRESS_SANITIZER) {
      return false;
    } else {
      if (!image.borrowed() || image.empty()) return false;
      constexpr std::uintptr_t kBlock = 4096, kPadding = 64;
      const auto end = reinterpret_cast<std::uintptr_t>(image.data() + static_cast<std::size_t>(image.width()) *
                                                                           static_cast<std::size_t>(image.height()));
      return (end - 1) / kBlock == (end + kPadding - 1) / kBlock;
    }
  }

  /// The plane every camera centre lies on, when whoever built the set knows it (the Stanford
  /// and LFCA loaders build rectified planar arrays on z = 0); the samplers then use it instead
  /// of fitting one. nullopt for general rigs (their planarity is tested by a fit).
  [[nodiscard]] const std::optional<Plane<T>>& array_plane() const noexcept { return array_plane_; }

  /// This set, declaring that every camera centre lies on `plane` (normal of any non-zero
  /// length). Throws `argument_error` ("array plane") when the normal is zero or not finite, or a
  /// centre lies off the plane by more than 1e-6 of the array's extent (its largest distance from
  /// the plane's point) -- a loader bug, not a data error.
  [[nodiscard]] CameraFrameSet on_plane(const Plane<T>& plane) && {
    const Vec3<double> n = plane.normal.template cast<double>();
    if (!(n.norm() > 0) || !n.allFinite() || !plane.point.allFinite())
      throw argument_error("array plane", "normal must be non-zero and finite");
    double extent = 0, off = 0;
    for (const camera_type& c : cameras_) {
      const Vec3<double> d = c.centre().template cast<double>() - plane.point.template cast<double>();
      extent = std::max(extent, d.norm());
      off = std::max(off, std::abs(n.normalized().dot(d)));
    }
    if (!(off <= 1e-6 * extent))
      throw argument_error("array plane", "a camera centre lies " + std::to_string(off) + " off the declared plane");
    array_plane_ = plane;
    return std::move(*this);
  }

  /// True when the set carries a depth map per camera (`with_depth`).
  [[nodiscard]] bool has_depth() const noexcept { return !depths_.empty(); }
  /// Camera `i`'s depth map (precondition: `has_depth()`): per pixel, the depth of the surface
  /// the pixel sees along the camera's optical axis (camera-space z, world units, > 0), +inf
  /// where nothing was seen. Same size as image `i`.
  [[nodiscard]] const Image<float>& depth(std::size_t i) const noexcept { return *depths_[i]; }
  /// The smallest depth in camera `i`'s map (precondition: `has_depth()`), +inf when the camera
  /// saw nothing: no surface lies nearer to camera `i` along its axis, so a search for one can
  /// start there.
  [[nodiscard]] float depth_near(std::size_t i) const noexcept { return depth_near_[i]; }
  /// The lower and upper corner (world units) of an axis-aligned box holding every surface point
  /// the depth maps show (each finite depth at its pixel, the point `ray_through(pixel).at(depth)`),
  /// widened on every side by two pixels' width at the farthest depth of each map: no surface
  /// a map shows lies outside it, between pixel centres or at an image's border included
  /// (computed in double, rounded outward). A search that accepts points within a depth
  /// tolerance of a map's surface (`DepthProxy`) may find one that far outside the box at an
  /// image's border; searched inside the box, it finds the same surface from the box's face. Empty
  /// (lower corner +inf, upper -inf) when no map has a finite depth or the set carries none.
  [[nodiscard]] const std::array<Vec3<T>, 2>& depth_bounds() const noexcept { return depth_bounds_; }

  /// This set, carrying `depths[i]` as camera `i`'s depth map (see `depth`); an empty list drops
  /// the depth maps. Throws `argument_error` ("depth maps") naming the camera when the counts
  /// differ, a map's size differs from its camera's, or a depth is NaN, zero, negative or -inf.
  /// Samplers that do not read depth never look at the maps.
  [[nodiscard]] CameraFrameSet with_depth(std::vector<Image<float>> depths) && {
    std::vector<std::shared_ptr<const Image<float>>> shared;
    shared.reserve(depths.size());
    for (Image<float>& d : depths) shared.push_back(std::make_shared<const Image<float>>(std::move(d)));
    return std::move(*this).with_shared_depth(std::move(shared));
  }

  /// The same frames without frame `i` (for leave-one-out evaluation).
  [[nodiscard]] CameraFrameSet without(std::size_t i) const {
    if (i >= size()) throw argument_error("frame index", "out of range");
    CameraFrameSet out = *this;
    out.cameras_.erase(out.cameras_.begin() + static_cast<std::ptrdiff_t>(i));
    out.images_.erase(out.images_.begin() + static_cast<std::ptrdiff_t>(i));
    out.names_.erase(out.names_.begin() + static_cast<std::ptrdiff_t>(i));
    out.texel_data_.erase(out.texel_data_.begin() + static_cast<std::ptrdiff_t>(i)); // the buffer is shared
    if (!out.linear16_data_.empty())
      out.linear16_data_.erase(out.linear16_data_.begin() + static_cast<std::ptrdiff_t>(i));
    if (!out.depths_.empty()) {
      out.depths_.erase(out.depths_.begin() + static_cast<std::ptrdiff_t>(i));
      out.depth_near_.erase(out.depth_near_.begin() + static_cast<std::ptrdiff_t>(i));
      out.depth_boxes_.erase(out.depth_boxes_.begin() + static_cast<std::ptrdiff_t>(i));
      out.depth_bounds_ = union_box(out.depth_boxes_);
    }
    return out;
  }

  /// The frames with their cameras converted to scalar `U`; the images, texels and depth maps
  /// are shared, not copied (the depth maps' bounds are computed again in `U`).
  template <std::floating_point U>
  [[nodiscard]] CameraFrameSet<U, Px> cast() const {
    std::vector<PinholeCamera<U>> cameras;
    cameras.reserve(size());
    for (const camera_type& c : cameras_)
      cameras.emplace_back(
          c.K().template cast<U>(), c.R().template cast<U>(), c.t().template cast<U>(), c.width(), c.height(),
          typename PinholeCamera<U>::Distortion{static_cast<U>(c.distortion().k1), static_cast<U>(c.distortion().k2)},
          std::is_same_v<U, float> ? U(1e-4) : PinholeCamera<U>::default_rotation_tolerance());
    CameraFrameSet<U, Px> out;
    out.cameras_ = std::move(cameras);
    out.images_ = images_;
    out.names_ = names_;
    out.texels_ = texels_;
    out.texel_data_ = texel_data_;
    out.linear16_ = linear16_;
    out.linear16_data_ = linear16_data_;
    out = std::move(out).with_shared_depth(depths_);
    if (array_plane_)
      return std::move(out).on_plane(
          Plane<U>{array_plane_->point.template cast<U>(), array_plane_->normal.template cast<U>()});
    return out;
  }

private:
  template <std::floating_point, class>
  friend class CameraFrameSet;

  // `with_depth` for maps already shared.
  [[nodiscard]] CameraFrameSet with_shared_depth(std::vector<std::shared_ptr<const Image<float>>> depths) && {
    if (!depths.empty() && depths.size() != cameras_.size())
      throw argument_error("depth maps", std::to_string(cameras_.size()) + " cameras but " +
                                             std::to_string(depths.size()) + " depth maps");
    std::vector<float> near(depths.size(), std::numeric_limits<float>::infinity());
    std::vector<std::array<Vec3<T>, 2>> boxes(depths.size());
    for (std::size_t i = 0; i < depths.size(); ++i) {
      const Image<float>& d = *depths[i];
      if (d.width() != cameras_[i].width() || d.height() != cameras_[i].height())
        throw argument_error("depth maps", names_[i] + ": depth map is " + std::to_string(d.width()) + "x" +
                                               std::to_string(d.height()) + " but its camera expects " +
                                               std::to_string(cameras_[i].width()) + "x" +
                                               std::to_string(cameras_[i].height()));
      int bad_x = -1, bad_y = -1;
      boxes[i] = surface_box(cameras_[i], d, near[i], bad_x, bad_y);
      if (bad_x >= 0)
        throw argument_error("depth maps", names_[i] + ": depth " + std::to_string(d(bad_x, bad_y)) + " at pixel (" +
                                               std::to_string(bad_x) + ", " + std::to_string(bad_y) +
                                               ") (depths are positive, +inf where nothing was seen)");
    }
    depths_ = std::move(depths);
    depth_near_ = std::move(near);
    depth_boxes_ = std::move(boxes);
    depth_bounds_ = union_box(depth_boxes_);
    return std::move(*this);
  }

  using Box = std::array<Vec3<T>, 2>;

  [[nodiscard]] static Box empty_box() noexcept {
    return {Vec3<T>::Constant(std::numeric_limits<T>::infinity()),
            Vec3<T>::Constant(-std::numeric_limits<T>::infinity())};
  }

  // One pass over camera c's map `d`: the box of its surface points (see `depth_bounds`), its
  // nearest depth (`near`, lowered), and the first pixel whose depth is not positive (bad_x,
  // bad_y; left as they are when there is none). Without distortion a pixel's direction is
  // affine in the pixel, so a point costs a few multiply-adds; in double, so that the steps'
  // rounding stays far below the margin on frames of any size, and rounded outward to T.
  [[nodiscard]] static Box surface_box(const camera_type& c, const Image<float>& d, float& near, int& bad_x,
                                       int& bad_y) noexcept {
    constexpr double inf = std::numeric_limits<double>::infinity();
    Vec3<double> lo = Vec3<double>::Constant(inf), hi = Vec3<double>::Constant(-inf);
    double far = 0;
    const Vec3<double> o = c.centre().template cast<double>();
    const Mat3<double> M = c.R().template cast<double>().transpose() * c.K().template cast<double>().inverse();
    const Vec3<double> base = M.col(2), step_x = M.col(0), step_y = M.col(1); // R^T K^-1 (x, y, 1)
    for (int y = 0; y < d.height(); ++y) {
      const Vec3<double> row = base + static_cast<double>(y) * step_y;
      const float* line = &d(0, y);
      for (int x = 0; x < d.width(); ++x) {
        const float depth = line[x];
        if (!(depth > 0)) {
          bad_x = x;
          bad_y = y;
          return empty_box();
        }
        near = std::min(near, depth);
        if (depth == std::numeric_limits<float>::infinity()) continue;
        const Vec3<double> v =
            c.has_distortion()
                ? Vec3<double>(
                      c.ray_through(Vec2<T>(static_cast<T>(x), static_cast<T>(y))).direction.template cast<double>())
                : Vec3<double>(row + static_cast<double>(x) * step_x);
        const Vec3<double> p = o + static_cast<double>(depth) * v;
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
        far = std::max(far, static_cast<double>(depth));
      }
    }
    if (!(far > 0)) return empty_box();
    const double margin = 2 * far / std::min(std::abs(c.K()(0, 0)), std::abs(c.K()(1, 1)));
    Box box;
    for (int a = 0; a < 3; ++a) {
      box[0][a] = outward(lo[a] - margin, -inf);
      box[1][a] = outward(hi[a] + margin, inf);
    }
    return box;
  }

  // v rounded to T toward `toward` (a box corner that holds v).
  [[nodiscard]] static T outward(double v, double toward) noexcept {
    const T r = static_cast<T>(v);
    return static_cast<double>(r) == v ? r : std::nextafter(r, static_cast<T>(toward));
  }

  [[nodiscard]] static Box union_box(const std::vector<Box>& boxes) noexcept {
    Box out = empty_box();
    for (const Box& b : boxes) {
      out[0] = out[0].cwiseMin(b[0]);
      out[1] = out[1].cwiseMax(b[1]);
    }
    return out;
  }

  // Every image the set does not share (`can_share`) decoded into one buffer, each from a multiple
  // of 64 texels (64-byte aligned, as the buffer is); the images that follow and the buffer's
  // padding keep at least 64 bytes readable after each. One buffer rather than one per image:
  // frames each under the allocator's huge-page threshold are in huge pages too, and a render
  // that reads a few rows of each of many frames misses the TLB far less often. `at[i]` receives
  // image i's first texel (its own pixels when shared). Null when every image is shared.
  [[nodiscard]] static std::shared_ptr<const texel_vector>
  decode(const std::vector<std::shared_ptr<const Image<Px>>>& images, std::vector<const texel_type*>& at) {
    constexpr std::size_t kAlign = 64;
    static_assert(!std::is_same_v<Px, Rgb8> ||
                      (sizeof(Rgb8) == sizeof(Srgb8Texel) && alignof(Rgb8) == alignof(Srgb8Texel) &&
                       std::is_standard_layout_v<Rgb8> && std::is_trivially_copyable_v<Rgb8>),
                  "an 8-bit pixel is its texel: r, g, b bytes");
    std::vector<std::size_t> offsets(images.size(), 0);
    std::vector<bool> shared(images.size(), false);
    std::size_t total = 0;
    for (std::size_t i = 0; i < images.size(); ++i) {
      shared[i] = can_share(*images[i]);
      if (shared[i]) continue;
      offsets[i] = total;
      const std::size_t n =
          static_cast<std::size_t>(images[i]->width()) * static_cast<std::size_t>(images[i]->height());
      total += (n + kAlign) / kAlign * kAlign; // at least one texel of gap, a multiple of kAlign
    }
    auto out = total == 0 ? nullptr : std::make_shared<texel_vector>(total);
    at.assign(images.size(), nullptr);
    for (std::size_t i = 0; i < images.size(); ++i) {
      const Px* p = images[i]->data();
      if (shared[i]) { // the same bytes: r, g, b of each pixel (see the static_assert)
        at[i] = reinterpret_cast<const texel_type*>(p);
        continue;
      }
      texel_type* t = out->data() + offsets[i];
      at[i] = t;
      const std::size_t n =
          static_cast<std::size_t>(images[i]->width()) * static_cast<std::size_t>(images[i]->height());
      if constexpr (std::is_same_v<Px, Rgb8>) {
        for (std::size_t k = 0; k < n; ++k) t[k] = {{p[k].r, p[k].g, p[k].b}};
      } else {
        for (std::size_t k = 0; k < n; ++k) t[k] = {{p[k][0], p[k][1], p[k][2]}};
      }
    }
    return out;
  }

  using linear16_vector = detail::Linear16Vector;

  // `detail::linear16_copy` of 8-bit frames; null (and `out` empty) for linear frames.
  [[nodiscard]] static std::shared_ptr<const linear16_vector>
  decode_linear16(const std::vector<std::shared_ptr<const Image<Px>>>& images, const std::vector<const texel_type*>& at,
                  std::vector<const std::uint16_t*>& out) {
    out.clear();
    if constexpr (std::is_same_v<Px, Rgb8>)
      return detail::linear16_copy(images, at, Srgb8Texel::linear16(), out);
    else
      return nullptr;
  }

  std::vector<camera_type> cameras_;
  std::vector<std::shared_ptr<const Image<Px>>> images_;
  std::vector<std::string> names_;
  std::shared_ptr<const texel_vector> texels_;      // the decoded images; null when none is (or the set is empty)
  std::vector<const texel_type*> texel_data_;       // image i's first texel: in *texels_, or its own pixels
  std::shared_ptr<const linear16_vector> linear16_; // the 16-bit linear copy (`linear16`); null when none
  std::vector<const std::uint16_t*> linear16_data_; // image i's first value in *linear16_; empty when none
  std::vector<std::shared_ptr<const Image<float>>> depths_;
  std::vector<float> depth_near_;
  std::vector<Box> depth_boxes_;
  Box depth_bounds_ = empty_box();
  std::optional<Plane<T>> array_plane_;
};

} // namespace mpr
