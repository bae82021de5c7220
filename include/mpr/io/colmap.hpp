#pragma once
/// \file
/// A COLMAP sparse model in text form (`cameras.txt`, `images.txt`, see colmap_text.hpp) and its
/// images folder as a `CameraFrameSet`: bring your own calibrated camera array.

#include <mpr/camera/pinhole_camera.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>
#include <mpr/io/colmap_text.hpp>
#include <mpr/io/image_io.hpp>
#include <mpr/io/load_limits.hpp>
#include <mpr/lightfield/frame_set.hpp>

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace mpr {

/// The cameras of a COLMAP model, one per image, with the image names.
template <std::floating_point T = double>
struct ColmapCameras {
  std::vector<PinholeCamera<T>> cameras;
  std::vector<std::string> names;
};

/// The pinhole cameras of the COLMAP model in `model_dir` without loading images, ordered by
/// image id. Throws `io_error` naming `images.txt` and the line when an image names a camera id
/// `cameras.txt` lacks or when K, R or t do not make a camera (PinholeCamera's checks).
template <std::floating_point T = double>
[[nodiscard]] ColmapCameras<T> read_colmap_cameras_of_images(const std::filesystem::path& model_dir,
                                                             const LoadLimits& limits = {}) {
  const std::filesystem::path cameras_txt = model_dir / "cameras.txt", images_txt = model_dir / "images.txt";
  const std::vector<ColmapCamera<T>> intrinsics = read_colmap_cameras<T>(cameras_txt, limits);
  std::vector<ColmapImage<T>> images = read_colmap_images<T>(images_txt, limits);
  if (images.empty()) throw io_error(images_txt.string(), "no images");
  std::ranges::sort(images, {}, &ColmapImage<T>::id);
  std::map<long, const ColmapCamera<T>*> by_id;
  for (const ColmapCamera<T>& c : intrinsics) by_id[c.id] = &c;
  ColmapCameras<T> out;
  for (const ColmapImage<T>& im : images) {
    const auto found = by_id.find(im.camera_id);
    if (found == by_id.end())
      throw io_error(images_txt.string(), "camera id " + std::to_string(im.camera_id) + " is not in cameras.txt",
                     im.line);
    const ColmapCamera<T>& c = *found->second;
    try {
      out.cameras.emplace_back(c.K, im.R, im.t, c.width, c.height, typename PinholeCamera<T>::Distortion{c.k1, c.k2});
    } catch (const argument_error& err) {
      throw io_error(images_txt.string(), err.what(), im.line);
    }
    out.names.push_back(im.name);
  }
  return out;
}

/// Reads the COLMAP text model in `model_dir` (e.g. `project/sparse/0`, holding `cameras.txt`
/// and `images.txt`; `points3D.txt` is not read) and every image it names from `image_dir` (e.g.
/// `project/images`) into a `CameraFrameSet` of 8-bit frames, ordered by image id, named by the
/// image names. Every image must exist, decode and have its camera's width and height. Image
/// headers are read first: sizes and `limits` are checked before any image is decoded. Throws
/// `io_error` naming the file (and line) on any failure.
template <std::floating_point T = double>
[[nodiscard]] CameraFrameSet<T, Rgb8> read_colmap(const std::filesystem::path& model_dir,
                                                  const std::filesystem::path& image_dir,
                                                  const LoadLimits& limits = {}) {
  ColmapCameras<T> model = read_colmap_cameras_of_images<T>(model_dir, limits);
  const std::filesystem::path images_txt = model_dir / "images.txt";
  std::vector<std::filesystem::path> paths;
  std::vector<ImageInfo> infos;
  for (std::size_t i = 0; i < model.names.size(); ++i) {
    paths.push_back(image_dir / model.names[i]);
    try {
      infos.push_back(read_image_info(paths.back(), limits));
    } catch (const io_error& err) {
      throw io_error(images_txt.string(), "image " + model.names[i] + ": " + err.what());
    }
    const PinholeCamera<T>& c = model.cameras[i];
    if (infos.back().width != c.width() || infos.back().height != c.height())
      throw io_error(paths.back().string(), "image is " + std::to_string(infos.back().width) + "x" +
                                                std::to_string(infos.back().height) +
                                                ", its camera in cameras.txt is " + std::to_string(c.width()) + "x" +
                                                std::to_string(c.height()));
  }
  check_set_budget(paths, infos, limits, CameraFrameSet<T, Rgb8>::holds_linear16());
  std::vector<Image<Rgb8>> frames;
  for (std::size_t i = 0; i < paths.size(); ++i) {
    frames.push_back(read_rgb8(paths[i], limits));
    if (frames.back().width() != infos[i].width || frames.back().height() != infos[i].height)
      throw io_error(paths[i].string(), "image changed size while loading");
    if (limits.progress) limits.progress(i + 1, paths.size());
  }
  return CameraFrameSet<T, Rgb8>(std::move(model.cameras), std::move(frames), std::move(model.names));
}

} // namespace mpr
