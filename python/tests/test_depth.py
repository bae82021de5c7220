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
