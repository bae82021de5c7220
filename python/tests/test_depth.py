"""Plane-sweep depth from Python (mpr/lightfield/depth_estimation.hpp, sweep_range.hpp)."""

import numpy as np
import pytest

import mpr


def test_estimate_depth_range_from_the_calibration(temple_par):
    """near = far = 0 (the defaults): the range comes from mpr::sweep_range; the temple, 0.44-0.71
    from the cameras by its bounding box, is found inside those depths."""
    if temple_par is None:
        pytest.skip("real data not found (set MPR_DATA_DIR)")
    frames = mpr.read_par(str(temple_par))
    depth, confidence = mpr.estimate_depth(frames, 0, planes=16, threads=2)
    seen = depth[np.isfinite(depth)]
    assert seen.size > 0
    assert seen.min() >= 0.44 and seen.max() <= 0.72
    assert confidence.shape == depth.shape
    # One of near and far set alone is no range: near must lie in [1e-30, 1e30].
    with pytest.raises(Exception, match="near"):
        mpr.estimate_depth(frames, 0, near=0.0, far=1.0, planes=16)


def step_scene(size=(48, 64), foreground=3, background=1):
    """A 3x3 array (unit spacing, focal 64 px, looking along +z) of a textured background plane
    at disparity `background` with a textured square at disparity `foreground` in front of it
    (pixels per camera step, whole numbers, so every view is an exact shift of the textures).
    Returns the frame set and the true depth of the centre camera (index 4)."""
    h, w = size
    f = 64.0
    rng = np.random.default_rng(7)
    margin = 2 * foreground
    texture = lambda: np.kron(rng.integers(0, 256, ((h + 2 * margin) // 2 + 1, (w + 2 * margin) // 2 + 1, 3)),
                              np.ones((2, 2, 1))).astype(np.uint8)  # 2x2-pixel blocks of random colour
    back, front = texture(), texture()
    square = (slice(h // 4, 3 * h // 4), slice(w // 4, 3 * w // 4))  # in the centre view's pixels
    K = np.array([[f, 0, (w - 1) / 2], [0, f, (h - 1) / 2], [0, 0, 1]])
    images, Ks, Rs, ts = [], [], [], []
    for j in (-1, 0, 1):
        for i in (-1, 0, 1):
            # A camera at (i, j, 0) sees the point of a plane at disparity d that the centre view
            # shows at pixel (u + d i, v + d j).
            ys, xs = np.mgrid[0:h, 0:w]
            image = back[ys + margin + background * j, xs + margin + background * i]
            fy, fx = ys + foreground * j, xs + foreground * i
            inside = (fy >= square[0].start) & (fy < square[0].stop) & (fx >= square[1].start) & (fx < square[1].stop)
            image[inside] = front[fy[inside] + margin, fx[inside] + margin]
            images.append(np.ascontiguousarray(image))
            Ks.append(K)
            Rs.append(np.eye(3))
            ts.append([-float(i), -float(j), 0.0])
    frames = mpr.frame_set(images, np.stack(Ks), np.stack(Rs), np.array(ts))
    truth = np.full((h, w), f / background)
    truth[square] = f / foreground
    return frames, truth


def test_estimate_depth_passes_the_final_filters_through():
    """median_radius and snap_jump reach mpr::PlaneSweepConfig: turning either filter off changes
    the map of a scene with a depth step (the filters act at its edges), and the defaults equal
    the same values given by name."""
    frames, truth = step_scene()
    sweep = dict(near=16.0, far=80.0, planes=64, threads=2)
    default, _ = mpr.estimate_depth(frames, 4, **sweep)
    named, _ = mpr.estimate_depth(frames, 4, median_radius=3, median_range=0.16, median_flat=1.0,
                                  median_min_confidence=0.02, snap_jump=8.0, **sweep)
    no_median, _ = mpr.estimate_depth(frames, 4, median_radius=0, **sweep)
    no_snap, _ = mpr.estimate_depth(frames, 4, snap_jump=np.inf, **sweep)
    neither, _ = mpr.estimate_depth(frames, 4, median_radius=0, snap_jump=np.inf, **sweep)
    np.testing.assert_array_equal(default, named)
    for other in (no_median, no_snap, neither):
        assert (other != default).sum() > 0
    assert (neither != no_median).sum() > 0 and (neither != no_snap).sum() > 0
    # The scene is the estimate's oracle: away from the step's edges the depth is right either way.
    inner = np.zeros(truth.shape, bool)
    inner[6:-6, 6:-6] = True
    edges = np.abs(np.gradient(truth)[0]) + np.abs(np.gradient(truth)[1]) > 0
    for image in (default, neither):
        good = np.abs(image - truth) < 0.05 * truth
        assert good[inner & ~edges].mean() > 0.9


@pytest.mark.parametrize("keyword, value", [("median_radius", 8), ("median_radius", -1), ("median_range", 0.0),
                                            ("median_flat", -1.0), ("median_min_confidence", 0.0),
                                            ("median_min_confidence", 1.5), ("snap_jump", 0.0),
                                            ("snap_jump", float("nan"))])
def test_estimate_depth_rejects_bad_filter_settings(keyword, value):
    """A bad filter setting raises ValueError naming the Python keyword (median's `range` is not
    the sweep's `range`)."""
    frames, _ = step_scene(size=(16, 16), foreground=2)
    with pytest.raises(ValueError, match=f"invalid {keyword}:"):
        mpr.estimate_depth(frames, 4, near=16.0, far=80.0, planes=8, **{keyword: value})
