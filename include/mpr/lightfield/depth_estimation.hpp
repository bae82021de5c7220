#pragma once
/// \file
/// Depth maps estimated from the images of a calibrated camera set by a plane sweep (Collins
/// 1996): for each camera, fronto-parallel planes at depths sampled uniformly in inverse depth
/// are swept through its view; at each plane every pixel's colour is compared with the
/// neighbouring cameras' colours where they see the same point (in a camera grid, the cameras
/// along the camera's image rows and columns, long baselines included), the per-neighbour costs
/// are combined robustly (the mean of the best half: a neighbour that is occluded there drops out),
/// aggregated over an edge-aware support (the recursive domain-transform filter of Gastal &
/// Oliveira 2011, guided by the camera's own image, so the support stops at colour edges), and
/// the cheapest plane is refined to sub-plane depth by a parabola through its neighbours. Gives
/// a depth map per camera for `CameraFrameSet::with_depth` and `DepthProxy`, with a confidence.

#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>
#include <mpr/core/parallel.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/lightfield/depth_median.hpp>
#include <mpr/lightfield/edge_snap.hpp>
#include <mpr/lightfield/frame_set.hpp>
#include <mpr/lightfield/kernels/sweep_kernels.hpp>
#include <mpr/lightfield/plane_sweep/depth_homography.hpp>
#include <mpr/lightfield/plane_sweep/sweep_row.hpp>
#include <mpr/lightfield/plane_sweep/sweep_workspace.hpp>
#include <mpr/lightfield/plane_sweep_config.hpp>
#include <mpr/lightfield/sweep_range.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <exception>
#include <functional>
#include <limits>
#include <mutex>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace mpr {

namespace detail {

/// The cameras `camera` is compared with, by `config.selection` (see `NeighbourSelection`;
/// nearest first, ties by index; with `axes` the row cameras, then the column cameras). Throws
/// `argument_error` ("frames") when one of them or the camera has lens distortion.
template <std::floating_point T, class Px>
[[nodiscard]] std::vector<std::size_t> sweep_neighbours(const CameraFrameSet<T, Px>& frames, std::size_t camera,
                                                        const PlaneSweepConfig& config) {
  const PinholeCamera<T>& ref = frames.camera(camera);
  const auto by_distance = [&](std::vector<std::size_t>& list) {
    std::sort(list.begin(), list.end(), [&](std::size_t a, std::size_t b) {
      const T da = (frames.camera(a).centre() - ref.centre()).squaredNorm();
      const T db = (frames.camera(b).centre() - ref.centre()).squaredNorm();
      return da < db || (da == db && a < b);
    });
  };
  std::vector<std::size_t> order, rows, columns;
  const double slope = std::tan(kSweepAxisDegrees * 3.14159265358979323846 / 180.0);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (i == camera) continue;
    order.push_back(i);
    const Vec3<T> b = ref.R() * (frames.camera(i).centre() - ref.centre());
    const double bx = std::abs(static_cast<double>(b.x())), by = std::abs(static_cast<double>(b.y()));
    if (bx > 0 && by <= slope * bx) rows.push_back(i);
    if (by > 0 && bx <= slope * by) columns.push_back(i);
  }
  const std::size_t want = static_cast<std::size_t>(config.neighbours);
  if (config.selection == NeighbourSelection::axes && rows.size() >= 2 && columns.size() >= 2) {
    by_distance(rows);
    by_distance(columns);
    // Half each; what one line lacks, the other gives.
    std::size_t r = std::min(rows.size(), (want + 1) / 2), c = std::min(columns.size(), want - r);
    r = std::min(rows.size(), want - c);
    order.assign(rows.begin(), rows.begin() + static_cast<std::ptrdiff_t>(r));
    order.insert(order.end(), columns.begin(), columns.begin() + static_cast<std::ptrdiff_t>(c));
  } else {
    by_distance(order);
    order.resize(std::min(order.size(), want));
  }
  for (const std::size_t i : order)
    if (frames.camera(i).has_distortion() || ref.has_distortion())
      throw argument_error("frames", frames.name(i) + ": lens distortion is not supported by the plane sweep");
  return order;
}

/// `ws.nt[j]` = the planes of camera order[j] (`sweep_planes`), for j < order.size(): a camera
/// the workspace already holds from the previous sweep is moved into place, not converted again
/// (neighbouring cameras of an array share most of their neighbours). Precondition: `ws` has only
/// swept cameras of `frames` (a workspace serves one frame set; the camera index is the key).
template <std::floating_point T, class Px>
void sweep_neighbour_planes(const CameraFrameSet<T, Px>& frames, const std::vector<std::size_t>& order,
                            SweepWorkspace& ws) {
  const std::size_t m = order.size(), none = std::numeric_limits<std::size_t>::max();
  ws.nt.resize(std::max(ws.nt.size(), m));
  ws.nt_camera.resize(ws.nt.size(), none);
  // First every camera already held into its slot, then the others converted: a slot's old
  // camera stays findable until every held camera is placed.
  std::vector<bool> placed(ws.nt.size(), false);
  for (std::size_t j = 0; j < m; ++j)
    for (std::size_t i = 0; i < ws.nt.size(); ++i)
      if (!placed[i] && ws.nt_camera[i] == order[j]) {
        std::swap(ws.nt[i], ws.nt[j]);
        std::swap(ws.nt_camera[i], ws.nt_camera[j]);
        placed[j] = true; // slot j was not placed before (nor is slot i, now holding j's old camera)
        break;
      }
  for (std::size_t j = 0; j < m; ++j)
    if (!placed[j]) {
      ws.nt_camera[j] = none; // until converted (an exception leaves no stale name)
      sweep_planes(frames.image(order[j]), false, ws.nt[j]);
      ws.nt_camera[j] = order[j];
    }
  ws.nt.resize(m);
  ws.nt_camera.resize(m);
}

/// The plane sweep of `estimate_depth` for a checked config and neighbour list, on `threads`
/// workers (rows of a plane, then column strips).
template <std::floating_point T, class Px>
[[nodiscard]] DepthEstimate plane_sweep(const CameraFrameSet<T, Px>& frames, std::size_t camera,
                                        const std::vector<std::size_t>& order, const PlaneSweepConfig& config,
                                        int threads, SweepWorkspace& ws) {
  const PinholeCamera<T>& ref = frames.camera(camera);
  const int width = ref.width(), height = ref.height();
  const int m = static_cast<int>(order.size());
  const int best = std::min(config.best, m);
  // Colours are compared as sRGB codes / 255 (perceptually even: dark texture counts as much as
  // bright), as planar float channels, for the camera and its neighbours.
  const SweepPlanes& rt = ws.rt;
  sweep_planes(frames.image(camera), true, ws.rt);
  sweep_neighbour_planes(frames, order, ws);
  const std::vector<SweepPlanes>& nt = ws.nt;

  // Neighbour j sees pixel p of the reference at depth d at h = A_j + d M_j p (homogeneous).
  std::vector<Mat3<float>> M(static_cast<std::size_t>(m));
  std::vector<Vec3<float>> A(static_cast<std::size_t>(m));
  for (int j = 0; j < m; ++j) {
    const DepthHomography h = depth_homography(ref, frames.camera(order[static_cast<std::size_t>(j)]));
    M[static_cast<std::size_t>(j)] = h.M.template cast<float>();
    A[static_cast<std::size_t>(j)] = h.A.template cast<float>();
  }

  // Domain-transform feedback per link, from the reference image's colour differences (the sum
  // over channels of |code difference|, 0..765, through a table).
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  std::vector<float>&ax = ws.ax, &ay = ws.ay;
  ax.resize(n);
  ay.resize(n);
  {
    const double sigma = std::max(config.spatial, 1e-6);
    const double base = std::exp(-std::sqrt(2.0) / sigma), ratio = sigma / config.range;
    float table[766];
    // Entry 0 is base itself: a range so small that the ratio overflows cuts at every colour
    // difference (pow(base, inf) = 0) but not between equal colours (inf * 0 would be NaN).
    table[0] = static_cast<float>(base);
    for (int k = 1; k < 766; ++k) table[k] = static_cast<float>(std::pow(base, 1 + ratio * (k / 255.0)));
    const auto diff = [&](std::size_t a, std::size_t b) {
      const Rgb8 p = rt.codes[a], q = rt.codes[b];
      return std::abs(p.r - q.r) + std::abs(p.g - q.g) + std::abs(p.b - q.b);
    };
    // No link into the first column (ax) or the first row (ay).
    for (std::size_t k = 0, y = 0; y < static_cast<std::size_t>(height); ++y)
      for (std::size_t x = 0; x < static_cast<std::size_t>(width); ++x, ++k) {
        ax[k] = x > 0 ? table[diff(k, k - 1)] : 0.0f;
        ay[k] = y > 0 ? table[diff(k, k - static_cast<std::size_t>(width))] : 0.0f;
      }
  }

  // The planes go in batches of kSweepTrackPlanes: one cost image each, so that the argmin
  // state (six arrays) is read and written once per batch.
  constexpr int batch = kSweepTrackPlanes;
  std::vector<float>&costs = ws.costs, &best_cost = ws.best_cost, &sum = ws.sum, &left = ws.left, &right = ws.right,
  &previous = ws.previous;
  costs.resize(static_cast<std::size_t>(batch) * n);
  // Not cleared: the first batch's `sweep_track` writes the argmin state without reading it.
  for (std::vector<float>* v : {&best_cost, &sum, &left, &right, &previous}) v->resize(n);
  std::vector<int>& best_plane = ws.best_plane;
  best_plane.resize(n);
  const double inv_near = 1 / config.near, inv_far = 1 / config.far;
  const auto depth_of = [&](double index) {
    return 1 / (inv_near + (inv_far - inv_near) * index / static_cast<double>(config.planes - 1));
  };
  // A neighbour's cost is at most 3 (three channels, each |difference| <= 1): a larger
  // truncation truncates nothing, and the sums of unseen neighbours' costs stay finite.
  const float tau = static_cast<float>(std::min(config.truncation, 3.0));
  const SimdLevel level = dispatch_level();
  constexpr int rows_per_block = kSweepLockstepRows;
  const int blocks = (height + rows_per_block - 1) / rows_per_block;
  // The workers' scratch, sized here (nothing is allocated inside the noexcept workers).
  ws.keep.resize(static_cast<std::size_t>(blocks) * static_cast<std::size_t>(best + 1) *
                 static_cast<std::size_t>(width));
  ws.carry.resize(static_cast<std::size_t>(kSweepTrackPlanes) * static_cast<std::size_t>(width));
  const std::size_t w = static_cast<std::size_t>(width);
  // What a row's cost at a depth reads (`sweep_cost_row`).
  const SweepRowInputs inputs{&rt, nt.data(), M.data(), A.data(), m, best, tau, level, config.integer_costs};
  // One worker: the blocks in order, each row pulled towards the one above (the forward
  // vertical pass) while in cache; more: blocks in parallel, the forward pass down strips.
  const bool in_order = resolve_thread_count(threads, blocks) == 1;
  for (int first = 0; first < config.planes; first += batch) {
    const int count = std::min(batch, config.planes - first);
    const auto row_of = [&](int i, int y) {
      return costs.data() + static_cast<std::size_t>(i) * n + static_cast<std::size_t>(y) * w;
    };
    const auto ay_row = [&](int y) { return ay.data() + static_cast<std::size_t>(y) * w; };
    const auto block_costs = [&](int block) noexcept {
      float* scratch = ws.keep.data() + static_cast<std::size_t>(block) * static_cast<std::size_t>(best + 1) * w;
      float* keep[32];
      for (int i = 0; i < best; ++i) keep[i] = scratch + static_cast<std::size_t>(i) * w;
      float* value = scratch + static_cast<std::size_t>(best) * w;
      const int y0 = block * rows_per_block, y1 = std::min(height, y0 + rows_per_block);
      // Row by row, the batch's planes together: the neighbours' rows a reference row reads at
      // neighbouring planes are the same or adjacent ones, still in cache for the next plane.
      float d[kSweepTrackPlanes];
      for (int i = 0; i < count; ++i) d[i] = static_cast<float>(depth_of(first + i));
      for (int y = y0; y < y1; ++y)
        for (int i = 0; i < count; ++i) sweep_cost_row(inputs, y, d[i], row_of(i, y), keep, value);
      for (int i = 0; i < count; ++i) {
        if (!(config.spatial > 0)) continue;
        // The horizontal aggregation pass, the block's rows side by side.
        const std::ptrdiff_t at = static_cast<std::ptrdiff_t>(y0) * width;
        if (y1 - y0 == rows_per_block)
          sweep_dt_rows(row_of(i, y0), ax.data() + at, width, width, level);
        else
          for (int y = y0; y < y1; ++y)
            sweep_dt_row(row_of(i, y), ax.data() + static_cast<std::ptrdiff_t>(y) * width, width, level);
        if (in_order)
          for (int y = std::max(y0, 1); y < y1; ++y) sweep_dt_link(row_of(i, y), row_of(i, y - 1), ay_row(y), w, level);
      }
    };
    if (in_order)
      for (int block = 0; block < blocks; ++block) block_costs(block);
    else
      parallel_rows(0, blocks, threads, block_costs);
    // Column strips (the whole width for one worker): the forward vertical pass where not done,
    // then the backward one from the bottom, each row final once reached (kept in `carry`, the
    // costs left in place), and the argmin bookkeeping of that row.
    const int strip = in_order ? width : 64, strips = (width + strip - 1) / strip;
    parallel_rows(0, strips, in_order ? 1 : threads, [&](int s) noexcept {
      const std::size_t x0 = static_cast<std::size_t>(s) * static_cast<std::size_t>(strip);
      const std::size_t len = std::min<std::size_t>(static_cast<std::size_t>(strip), w - x0);
      float* const carry = ws.carry.data() + static_cast<std::size_t>(count) * x0; // count * len floats
      const float* rows = nullptr; // plane 0's costs of the row tracked, the others `stride` apart
      std::ptrdiff_t stride = 0;
      const auto track = [&](int y) {
        const std::size_t k = static_cast<std::size_t>(y) * w + x0;
        sweep_track(rows, stride, count,
                    SweepTrackRow{best_cost.data() + k, best_plane.data() + k, left.data() + k, right.data() + k,
                                  previous.data() + k, sum.data() + k},
                    first, len, level);
      };
      if (!(config.spatial > 0)) {
        stride = static_cast<std::ptrdiff_t>(n);
        for (int y = 0; y < height; ++y) {
          rows = row_of(0, y) + x0;
          track(y);
        }
        return;
      }
      if (!in_order)
        for (int y = 1; y < height; ++y)
          for (int i = 0; i < count; ++i)
            sweep_dt_link(row_of(i, y) + x0, row_of(i, y - 1) + x0, ay_row(y) + x0, len, level);
      rows = carry;
      stride = static_cast<std::ptrdiff_t>(len);
      for (int i = 0; i < count; ++i) {
        std::copy_n(row_of(i, height - 1) + x0, len, carry + static_cast<std::size_t>(i) * len);
      }
      track(height - 1);
      for (int y = height - 2; y >= 0; --y) {
        // The rows come from memory, bottom up: fetch the next ones ahead.
        if (y > 0)
          for (int i = 0; i < count; ++i) sweep_prefetch(row_of(i, y - 1) + x0, len);
        for (int i = 0; i < count; ++i)
          sweep_dt_carry(carry + static_cast<std::size_t>(i) * len, row_of(i, y) + x0, ay_row(y + 1) + x0, len, level);
        track(y);
      }
    });
  }
  // The refined plane coordinate of each pixel (plane index + parabola offset), then the final
  // filter on it, then depth.
  DepthEstimate out{Image<float>(width, height), Image<float>(width, height)};
  Image<float> coordinate(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t k = static_cast<std::size_t>(y) * w + static_cast<std::size_t>(x);
      const int b = best_plane[k];
      double offset = 0;
      if (b > 0 && b < config.planes - 1) {
        const double curvature = left[k] - 2.0 * best_cost[k] + right[k];
        if (curvature > 0) offset = std::clamp(0.5 * (left[k] - right[k]) / curvature, -0.5, 0.5);
      }
      coordinate(x, y) = static_cast<float>(b + offset);
      const float mean = sum[k] / static_cast<float>(config.planes);
      out.confidence(x, y) = mean > 0 ? std::clamp(1.0f - best_cost[k] / mean, 0.0f, 1.0f) : 0.0f;
    }
  if (config.median.radius > 0)
    coordinate = weighted_median(coordinate.view(), ImageView<const Rgb8>(rt.codes.data(), width, height),
                                 out.confidence.view(), config.median, threads);
  if (std::isfinite(config.snap.jump))
    coordinate =
        snap_mixed_pixels(coordinate.view(), ImageView<const Rgb8>(rt.codes.data(), width, height), config.snap);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) out.depth(x, y) = static_cast<float>(depth_of(coordinate(x, y)));
  return out;
}

} // namespace detail

/// `config` with its depth range: as given, or for near = far = 0 `sweep_range(frames)`'s
/// (reported to `config.progress` as the stage "range"). Throws as `sweep_range`.
template <std::floating_point T, class Px>
[[nodiscard]] PlaneSweepConfig with_sweep_range(const CameraFrameSet<T, Px>& frames, PlaneSweepConfig config) {
  if (config.near != 0 || config.far != 0) return config;
  const auto start = std::chrono::steady_clock::now();
  const SweepRange range = sweep_range(frames);
  config.near = range.near;
  config.far = range.far;
  if (config.progress)
    config.progress({"range", 1, 1, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()});
  return config;
}

/// The working memory, in bytes, of sweeping camera `camera` of `frames` with `config`: its
/// buffers and its neighbours' images as planar floats and codes (`detail::SweepWorkspace`) plus the
/// returned depth and confidence maps. Bounded by `config.memory_limit`. Throws as
/// `estimate_depth`.
template <std::floating_point T, class Px>
[[nodiscard]] double plane_sweep_bytes(const CameraFrameSet<T, Px>& frames, std::size_t camera,
                                       const PlaneSweepConfig& config) {
  validate(config);
  if (camera >= frames.size()) throw argument_error("camera", "index out of range");
  if (frames.size() < 2) throw argument_error("frames", "a plane sweep needs at least two cameras");
  return detail::sweep_bytes(frames, camera, detail::sweep_neighbours(frames, camera, config), config.best);
}

/// The depth map of camera `camera` of `frames` by the plane sweep of the file comment, compared
/// with its `config.neighbours` nearest cameras, on `config.threads` workers (the rows of each
/// plane). Throws `argument_error` for a bad config, a camera index out of range ("camera"), a
/// set of fewer than two cameras or a camera with lens distortion ("frames", naming it), and a
/// camera whose sweep needs more than `config.memory_limit` bytes ("memory_limit", naming it and
/// the MiB needed; `plane_sweep_bytes`).
template <std::floating_point T, class Px>
[[nodiscard]] DepthEstimate estimate_depth(const CameraFrameSet<T, Px>& frames, std::size_t camera,
                                           const PlaneSweepConfig& given) {
  validate(given);
  if (camera >= frames.size()) throw argument_error("camera", "index out of range");
  if (frames.size() < 2) throw argument_error("frames", "a plane sweep needs at least two cameras");
  const std::vector<std::size_t> order = detail::sweep_neighbours(frames, camera, given);
  detail::check_sweep_memory(frames, camera, detail::sweep_bytes(frames, camera, order, given.best),
                             given.memory_limit);
  const PlaneSweepConfig config = with_sweep_range(frames, given);
  detail::SweepWorkspace workspace;
  return detail::plane_sweep(frames, camera, order, config, config.threads, workspace);
}

/// The estimated depth maps of every camera of `frames` (see `estimate_depth`), in camera order,
/// for `CameraFrameSet::with_depth`. The cameras are shared among the `config.threads` workers
/// (each worker's buffers take about 94 + 15 x neighbours bytes per pixel of a camera, 310 MB for Chess, and no
/// more workers run at once than `config.memory_limit` holds); with fewer cameras than workers,
/// each camera's rows are shared too. Throws as `estimate_depth`, before any work.
template <std::floating_point T, class Px>
[[nodiscard]] std::vector<Image<float>> estimate_depth_maps(const CameraFrameSet<T, Px>& frames,
                                                            const PlaneSweepConfig& given) {
  validate(given);
  if (frames.size() < 2) throw argument_error("frames", "a plane sweep needs at least two cameras");
  std::vector<std::vector<std::size_t>> neighbours;
  for (std::size_t i = 0; i < frames.size(); ++i) neighbours.push_back(detail::sweep_neighbours(frames, i, given));
  const int cameras = static_cast<int>(frames.size());
  // The most working memory any camera's sweep takes: as many workers as fit the limit.
  double most = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const double bytes = detail::sweep_bytes(frames, i, neighbours[i], given.best);
    detail::check_sweep_memory(frames, i, bytes, given.memory_limit);
    most = std::max(most, bytes);
  }
  const PlaneSweepConfig config = with_sweep_range(frames, given);
  const auto start = std::chrono::steady_clock::now();
  std::size_t finished = 0;
  const int fit = static_cast<int>(std::min(config.memory_limit / most, static_cast<double>(cameras)));
  const int total = detail::resolve_thread_count(config.threads, std::numeric_limits<int>::max());
  const int workers = std::max(1, std::min({total, cameras, fit})), inner = std::max(1, total / workers);
  std::vector<Image<float>> maps(frames.size());
  std::exception_ptr failure;
  std::mutex guard;
  std::atomic<int> next{0};
  detail::parallel_rows(0, workers, workers, [&](int) noexcept {
    try {
      detail::SweepWorkspace workspace;
      for (int i = next.fetch_add(1); i < cameras; i = next.fetch_add(1)) {
        const auto k = static_cast<std::size_t>(i);
        maps[k] = detail::plane_sweep(frames, k, neighbours[k], config, inner, workspace).depth;
        if (config.progress) {
          const std::lock_guard<std::mutex> lock(guard);
          config.progress({"sweep", ++finished, frames.size(),
                           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()});
        }
      }
    } catch (...) {
      const std::lock_guard<std::mutex> lock(guard);
      if (!failure) failure = std::current_exception();
    }
  });
  if (failure) std::rethrow_exception(failure);
  return maps;
}

} // namespace mpr
