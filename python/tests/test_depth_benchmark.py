"""The HCI 4D benchmark from Python: the loader and the scorer (mpr/io/hci_light_field.hpp,
mpr/lightfield/disparity_score.hpp)."""

import numpy as np
import pytest

import mpr


def test_score_disparity_hand_worked():
    truth = np.zeros((4, 5), np.float32)
    estimate = truth.copy()
    estimate[0, 0] = 0.02   # off by more than 0.01 only
    estimate[1, 1] = -0.05  # more than 0.01 and 0.03
    estimate[2, 2] = 0.5    # more than every threshold
    s = mpr.score_disparity(estimate, truth, border=0)
    assert s["pixels"] == 20
    assert s["badpix_001"] == pytest.approx(15.0)
    assert s["badpix_003"] == pytest.approx(10.0)
    assert s["badpix_007"] == pytest.approx(5.0)
    assert s["mse_x100"] == pytest.approx(100 * (0.02**2 + 0.05**2 + 0.5**2) / 20, rel=1e-5)
    # A border of 1 leaves the 3 x 2 inner pixels: (1, 1) and (2, 2) of them are off.
    inner = mpr.score_disparity(estimate, truth, border=1)
    assert inner["pixels"] == 6
    assert inner["badpix_007"] == pytest.approx(100 / 6)
    with pytest.raises(ValueError, match="estimate"):
        mpr.score_disparity(estimate[:3], truth)


def test_read_hci_backgammon(data_dir):
    scene = data_dir / "hci" / "backgammon" if data_dir else None
    if scene is None or not scene.is_dir():
        pytest.skip("real data not found (MPR_DATA_DIR/hci/backgammon)")
    lf = mpr.read_hci(scene)
    frames = lf["frames"]
    assert len(frames) == 81
    assert lf["views"][lf["centre"]] == 40
    truth = lf["ground_truth"]
    assert truth is not None and truth.shape == (512, 512)
    # Disparity units without parameters.cfg: f B = 512, s = 10, so d = 512 / z - 10.
    assert lf["focal_baseline"] == pytest.approx(512)
    assert lf["offset"] == pytest.approx(10)
    assert lf["near"] == pytest.approx(512 / (lf["disparity_max"] + 10))
    assert mpr.score_disparity(truth, truth)["badpix_007"] == 0
