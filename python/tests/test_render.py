"""Each render through the module equals the C++ render of the same job, byte for byte."""

import re

import numpy as np
import pytest

import mpr


def jobs(frames, depth, w, h):
    camera = frames.camera(len(frames) // 2)
    view = mpr.View.pinhole(camera, depth)
    target = camera.centre + 2 * depth * camera.R[2]
    gallery = mpr.View.gallery("G", view.origin, view.width_vector, view.height_vector, target, depth)
    return {
        "synthetic8": mpr.render(frames, view, w, h, interpolation="synthetic"),
        "nearest_linear": mpr.render(frames, view, w, h, interpolation="nearest", linear=True),
        "cylinder_tent4": mpr.render(frames, view, w, h, interpolation="cylinder", radius=0.25, spp=4,
                                     filter="tent"),
        "gallery_g": mpr.render(frames, gallery, w, h),
        # float32 arithmetic, as the C++ job computes its sizes in float
        "disc_aperture8": mpr.render(frames, view, w, h, spp=8, filter="box", aperture="disc",
                                     aperture_size=float(np.float32(depth) / np.float32(40)),
                                     focus=float(np.float32(depth) / np.float32(4))),
    }


def compare(golden, prefix, rendered):
    for name, image in rendered.items():
        expected = np.fromfile(golden / f"{prefix}{name}.bin", dtype=image.dtype).reshape(image.shape)
        assert np.array_equal(image, expected), f"{prefix}{name}: {np.count_nonzero(image != expected)} values differ"


def test_synthetic_renders_equal_cpp(golden):
    frames = mpr.read_par(golden / "synth_par.txt")
    assert len(frames) == 9
    rendered = jobs(frames, 4.0, 40, 30)
    assert rendered["synthetic8"].dtype == np.uint8 and rendered["synthetic8"].shape == (30, 40, 3)
    assert rendered["nearest_linear"].dtype == np.float32
    assert rendered["synthetic8"].std() > 10  # not a flat background
    compare(golden, "synth_", rendered)


def test_real_temple_renders_equal_cpp(golden, temple_par):
    if temple_par is None:
        pytest.skip("real data not found (set MPR_DATA_DIR)")
    frames = mpr.read_par(temple_par)
    compare(golden, "real_", jobs(frames, 0.6, 160, 120))


def test_threads_and_grid(golden):
    frames = mpr.read_par(golden / "synth_par.txt")
    view = mpr.View.pinhole(frames.camera(4), 4.0)
    one = mpr.render(frames, view, 40, 30, threads=1)
    assert np.array_equal(one, mpr.render(frames, view, 40, 30, threads=3))
    grid = mpr.render_views(frames, [view, view, view], 40, 30, columns=2)
    assert grid.shape == (60, 80, 3)
    assert np.array_equal(grid[:30, 40:], one) and np.array_equal(grid[30:, :40], one)
    assert not grid[30:, 40:].any()  # the empty fourth tile stays black


def test_nearest_at_camera_reproduces_frame(golden):
    # The refocus view of camera k with the nearest interpolation reads camera k's own pixels:
    # an independent oracle (the frame itself) for the whole path.
    frames = mpr.read_par(golden / "synth_par.txt")
    image = mpr.render(frames, mpr.View.pinhole(frames.camera(4), 4.0), 40, 30, interpolation="nearest")
    assert np.array_equal(image, frames.image(4))


def test_classroom_renders_equal_cpp(golden):
    scene = mpr.classroom()
    camera = mpr.Camera.look_at([0.5, 1.6, 8.0], [0.0, 1.2, -14.0], [0.0, 1.0, 0.0], 1.0, 64, 48)
    view = mpr.View.pinhole(camera, 10.0)
    rendered = {
        "classroom8": mpr.render_scene(scene, view, 64, 48),
        "classroom_gauss4_linear": mpr.render_scene(scene, view, 64, 48, spp=4, filter="gaussian", linear=True),
    }
    assert rendered["classroom8"].std() > 10
    compare(golden, "", rendered)


def test_render_into_out(golden):
    frames = mpr.read_par(golden / "synth_par.txt")
    view = mpr.View.pinhole(frames.camera(4), 4.0)
    out = np.zeros((30, 40, 3), np.uint8)
    returned = mpr.render(frames, view, 40, 30, out=out)
    assert returned is out or np.shares_memory(returned, out)
    assert np.array_equal(out, mpr.render(frames, view, 40, 30))
    linear = np.zeros((30, 40, 3), np.float32)
    mpr.render(frames, view, 40, 30, linear=True, out=linear)
    assert np.array_equal(linear, mpr.render(frames, view, 40, 30, linear=True))
    for bad, needle in [(np.zeros((30, 40, 3), np.float32), "dtype must be uint8"),
                        (np.zeros((31, 40, 3), np.uint8), "shape must be (30, 40, 3)"),
                        (np.zeros((30, 80, 3), np.uint8)[:, ::2], "C-contiguous")]:
        with pytest.raises(ValueError, match=re.escape(needle)):
            mpr.render(frames, view, 40, 30, out=bad)


def test_aperture_errors(golden):
    frames = mpr.read_par(golden / "synth_par.txt")
    view = mpr.View.pinhole(frames.camera(4), 4.0)
    with pytest.raises(ValueError, match="needs spp > 1"):
        mpr.render(frames, view, 8, 8, aperture="disc", aperture_size=0.1)
    with pytest.raises(ValueError, match=r"invalid aperture: 'hexagon' is not disc, square, gaussian or polygonN"):
        mpr.render(frames, view, 8, 8, spp=4, aperture="hexagon")
    with pytest.raises(ValueError, match=r"invalid aperture: 2 is outside \[3, 64\]"):
        mpr.render(frames, view, 8, 8, spp=4, aperture="polygon2")
    with pytest.raises(ValueError, match="invalid interpolation: 'linear' is not nearest, synthetic, cylinder or depth"):
        mpr.render(frames, view, 8, 8, interpolation="linear")
    with pytest.raises(ValueError, match="invalid filter: 'sinc' is not box, tent, gaussian, mitchell or lanczos"):
        mpr.render(frames, view, 8, 8, filter="sinc")
    with pytest.raises(ValueError, match="invalid aperture_size"):
        mpr.render(frames, view, 8, 8, spp=4, aperture="disc", aperture_size=-1)
    # A zero-size aperture is the pinhole: the image without one (within a code: the renderer may
    # take its per-ray path instead of the affine one).
    a = mpr.render(frames, view, 40, 30, spp=4, aperture="square", aperture_size=0.0).astype(int)
    assert np.abs(a - mpr.render(frames, view, 40, 30, spp=4)).max() <= 1
    # An open aperture focused off the plane blurs: the image changes.
    b = mpr.render(frames, view, 40, 30, spp=8, aperture="disc", aperture_size=0.2, focus=1.0).astype(int)
    assert np.abs(b - a).mean() > 1
    # The names are mpr-render's: a polygon aperture (mpr-render --aperture polygon6:SIZE) and the
    # alias "synthetic_aperture" of "synthetic".
    hexagon = mpr.render(frames, view, 40, 30, spp=8, aperture="polygon6", aperture_size=0.2, focus=1.0).astype(int)
    assert np.abs(hexagon - a).mean() > 1
    assert mpr.interpolations == ["nearest", "synthetic", "cylinder", "depth"]
    assert mpr.filters == ["box", "tent", "gaussian", "mitchell", "lanczos"]
    assert np.array_equal(mpr.render(frames, view, 40, 30, interpolation="synthetic_aperture"),
                          mpr.render(frames, view, 40, 30, interpolation="synthetic"))
