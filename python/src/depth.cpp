// Depth from Python: the plane sweep of mpr/lightfield/depth_estimation.hpp into numpy arrays.

#include "bindings.hpp"

#include <mpr/io/hci_light_field.hpp>
#include <mpr/lightfield/array_disparity.hpp>
#include <mpr/lightfield/depth_estimation.hpp>
#include <mpr/lightfield/depth_median.hpp>
#include <mpr/lightfield/disparity_score.hpp>
#include <mpr/lightfield/edge_snap.hpp>
#include <mpr/lightfield/view_depth.hpp>
#include <mpr/render/policy_names.hpp>
#include <mpr/render/renderer.hpp>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstring>
#include <optional>
#include <string>
#include <type_traits>

namespace mpr_py {
namespace {

const mpr::PlaneSweepConfig kSweep{}; // the library's defaults

/// `validate(part)` with the parameter renamed to its Python keyword (`prefix` + the field), so
/// that median's `range` is not mistaken for the sweep's.
template <class Config>
void validate_as(const Config& part, const std::string& prefix) {
  try {
    mpr::validate(part);
  } catch (const mpr::argument_error& e) {
    throw mpr::argument_error(prefix + e.parameter(), e.reason());
  }
}

py::array_t<float> to_array(const mpr::Image<float>& image) {
  py::array_t<float> out({static_cast<py::ssize_t>(image.height()), static_cast<py::ssize_t>(image.width())});
  std::memcpy(out.mutable_data(), image.data(), sizeof(float) * static_cast<std::size_t>(out.size()));
  return out;
}

mpr::PlaneSweepConfig config_of(double near, double far, int planes, const std::string& selection, int neighbours,
                                int best, double truncation, double spatial, double range,
                                const mpr::WeightedMedianConfig& median, const mpr::EdgeSnapConfig& snap, int threads) {
  mpr::PlaneSweepConfig c;
  c.selection = mpr::choose(mpr::neighbour_selection_names, selection, "selection");
  c.near = near;
  c.far = far;
  c.planes = planes;
  c.neighbours = neighbours;
  c.best = best;
  c.truncation = truncation;
  c.spatial = spatial;
  c.range = range;
  c.median = median;
  c.snap = snap;
  c.threads = threads;
  validate_as(median, "median_");
  validate_as(snap, "snap_");
  mpr::validate(c);
  return c;
}

py::array_t<float> view_depth(const FrameSet& frames, const View& view, int width, int height,
                              const std::optional<mpr::PinholeCamera<T>>& along, int threads) {
  if (width < 1 || height < 1 || width > (1 << 15) || height > (1 << 15))
    throw mpr::argument_error("width/height", "each must lie in [1, 32768] pixels");
  py::array_t<float> out({static_cast<py::ssize_t>(height), static_cast<py::ssize_t>(width)});
  const mpr::ImageView<float> image(out.mutable_data(), width, height);
  std::visit(
      [&](const auto& set) {
        using Px = typename std::remove_cvref_t<decltype(*set)>::pixel_type;
        mpr::FrameDepthSampler<T, Px> sampler(set);
        if (along) sampler = std::move(sampler).along_axis(*along);
        py::gil_scoped_release release;
        mpr::Renderer(view.plane, view.selector, sampler)
            .render(image, mpr::Region(0, 0, width, height), mpr::RenderOptions{threads});
      },
      frames.frames);
  return out;
}

} // namespace

void bind_depth(py::module_& m) {
  m.def(
      "estimate_depth",
      [](const FrameSet& frames, std::size_t camera, double near, double far, int planes, const std::string& selection,
         int neighbours, int best, double truncation, double spatial, double range, int median_radius,
         double median_range, double median_flat, double median_min_confidence, double snap_jump, int threads) {
        const mpr::WeightedMedianConfig median{median_radius, median_range, median_flat, median_min_confidence};
        const mpr::PlaneSweepConfig c = config_of(near, far, planes, selection, neighbours, best, truncation, spatial,
                                                  range, median, mpr::EdgeSnapConfig{snap_jump}, threads);
        mpr::DepthEstimate e;
        {
          py::gil_scoped_release release;
          e = std::visit([&](const auto& f) { return mpr::estimate_depth(*f, camera, c); }, frames.frames);
        }
        return py::make_tuple(to_array(e.depth), to_array(e.confidence));
      },
      py::arg("frames"), py::arg("camera"), py::arg("near") = kSweep.near, py::arg("far") = kSweep.far,
      py::arg("planes") = kSweep.planes, py::arg("selection") = "axes", py::arg("neighbours") = kSweep.neighbours,
      py::arg("best") = kSweep.best, py::arg("truncation") = kSweep.truncation, py::arg("spatial") = kSweep.spatial,
      py::arg("range") = kSweep.range, py::arg("median_radius") = kSweep.median.radius,
      py::arg("median_range") = kSweep.median.range, py::arg("median_flat") = kSweep.median.flat,
      py::arg("median_min_confidence") = kSweep.median.min_confidence, py::arg("snap_jump") = kSweep.snap.jump,
      py::arg("threads") = 0,
      "Plane-sweep depth of camera `camera` (mpr::estimate_depth, defaults as mpr::PlaneSweepConfig): against up to "
      "`neighbours` cameras, those along the camera's image row and column (`selection='axes'`, falling back to the "
      "nearest where the array has no such axes) or the nearest (`'nearest'`), the `best` costs of each plane "
      "kept; returns (depth, confidence), two H x W float32 arrays; depth along the camera's optical axis in world "
      "units within [near, far], confidence in [0, 1]. near = far = 0 (the default): the range from the calibration "
      "and the images (mpr::sweep_range). The final filters (mpr::PlaneSweepConfig::median and ::snap): a joint "
      "weighted median over a (2 median_radius + 1)^2 window (median_radius 0..7, 0: none), guided by the camera's "
      "colours (median_range > 0: the colour distance, sum of |sRGB code difference| / 255 over channels, over "
      "which a neighbour's weight falls by e) and weighted by confidence (at least median_min_confidence, in (0, "
      "1]), windows whose values lie within median_flat planes (>= 0) left alone; then the mixed pixels of depth "
      "edges decided by colour where a pixel's neighbours differ by more than snap_jump planes (> 0; math.inf: "
      "none). A bad value raises ValueError naming the keyword. The GIL is released while sweeping.");
  m.def(
      "read_hci",
      [](const std::filesystem::path& folder) {
        mpr::HciLightField<T> lf;
        {
          py::gil_scoped_release release;
          lf = mpr::read_hci_light_field<T>(folder);
        }
        py::dict out;
        out["centre"] = lf.centre;
        out["views"] = lf.views;
        out["focal_baseline"] = lf.disparity.focal_baseline;
        out["offset"] = lf.disparity.offset;
        out["disparity_min"] = lf.disparity_min;
        out["disparity_max"] = lf.disparity_max;
        out["near"] = lf.near_depth();
        out["far"] = lf.far_depth();
        out["ground_truth"] = lf.ground_truth ? py::object(to_array(*lf.ground_truth)) : py::object(py::none());
        out["frames"] = FrameSet{std::make_shared<const FrameSet8>(std::move(lf.frames))};
        return out;
      },
      py::arg("folder"),
      "Reads a scene of the HCI 4D light-field benchmark (input_CamNNN.png views, parameters.cfg when present, "
      "gt_disp_lowres.pfm when present): a dict with `frames` (FrameSet), `centre` (index of the centre view), "
      "`views` (benchmark view numbers), `focal_baseline` and `offset` (disparity d = focal_baseline / depth - "
      "offset, pixels per view step), `disparity_min`/`disparity_max`, `near`/`far` (their depths) and "
      "`ground_truth` (H x W float32 disparity, top row first, or None). Raises OSError naming the file.");
  m.def(
      "score_disparity",
      [](const py::array_t<float, py::array::c_style | py::array::forcecast>& estimate,
         const py::array_t<float, py::array::c_style | py::array::forcecast>& truth, int border) {
        if (estimate.ndim() != 2 || truth.ndim() != 2)
          throw mpr::argument_error("estimate", "estimate and truth must be H x W arrays");
        const auto view = [](const py::array_t<float, py::array::c_style | py::array::forcecast>& a) {
          return mpr::ImageView<const float>(a.data(), static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)));
        };
        mpr::DisparityScoreRegion region;
        region.border = border;
        const mpr::DisparityScore s = mpr::score_disparity(view(estimate), view(truth), region);
        py::dict out;
        out["pixels"] = s.pixels;
        out["badpix_001"] = s.badpix_001;
        out["badpix_003"] = s.badpix_003;
        out["badpix_007"] = s.badpix_007;
        out["mse_x100"] = s.mse_x100;
        out["q25_x100"] = s.q25_x100;
        return out;
      },
      py::arg("estimate"), py::arg("truth"), py::arg("border") = 15,
      "The HCI benchmark's scores of a disparity map against the truth (same H x W; pixels `border` or more from "
      "every edge, truth finite): a dict with `badpix_001`, `badpix_003`, `badpix_007` (% of pixels off by more than "
      "0.01/0.03/0.07 pixel), `mse_x100`, `q25_x100` and `pixels`.");
  m.def("view_depth", &view_depth, py::arg("frames"), py::arg("view"), py::arg("width"), py::arg("height"),
        py::arg("along") = py::none(), py::arg("threads") = 0,
        "The depth of any view of a light field that carries depth maps (mpr-render --write-depth): a new height x "
        "width float32 array, per pixel where the surface the cameras' depth maps describe meets the pixel's ray: "
        "the ray parameter (signed distance in front of the view's image plane, world units), or with "
        "`along=camera` the depth along that camera's optical axis; inf where no surface is found.");
}

} // namespace mpr_py
