"""Frame sets from numpy arrays, round trips, and errors."""

import numpy as np
import pytest

import mpr


def ring(n=4, w=24, h=16):
    cams = [mpr.Camera.look_at([np.cos(a), 0.1, np.sin(a)], [0, 0, 0], [0, -1, 0], 0.8, w, h)
            for a in np.linspace(0.2, 1.0, n)]
    K = np.stack([c.K for c in cams])
    R = np.stack([c.R for c in cams])
    t = np.stack([c.t for c in cams])
    rng = np.random.default_rng(7)
    images = [rng.integers(0, 256, (h, w, 3), dtype=np.uint8) for _ in range(n)]
    return images, K, R, t


def test_uint8_round_trip_and_cameras():
    images, K, R, t = ring()
    frames = mpr.frame_set(images, K, R, t, names=["a", "b", "c", "d"])
    assert len(frames) == 4 and frames.names == ["a", "b", "c", "d"] and not frames.linear
    for i, image in enumerate(images):
        assert np.array_equal(frames.image(i), image)
        np.testing.assert_allclose(frames.camera(i).K, K[i], rtol=1e-6)
        np.testing.assert_allclose(frames.camera(i).R, R[i], atol=1e-6)
        np.testing.assert_allclose(frames.camera(i).t, t[i], atol=1e-6)


def test_float32_frames_are_linear():
    images, K, R, t = ring()
    linear = [(im / 255.0).astype(np.float32) for im in images]
    frames = mpr.frame_set(linear, K, R, t)
    assert frames.linear
    assert np.array_equal(frames.image(2), linear[2])
    view = mpr.View.pinhole(frames.camera(1), 1.0)
    out = mpr.render(frames, view, 24, 16, interpolation="nearest", linear=True)
    np.testing.assert_allclose(out, linear[1], atol=1e-5)  # the camera's own linear pixels


def test_depth_maps_are_carried():
    images, K, R, t = ring()
    depths = [np.full((16, 24), 1.0, dtype=np.float32) for _ in images]
    assert mpr.frame_set(images, K, R, t, depths=depths).has_depth


def test_camera_project_hand_worked():
    cam = mpr.Camera(np.diag([100.0, 100.0, 1.0]) + np.array([[0, 0, 20], [0, 0, 10], [0, 0, 0]]), np.eye(3),
                     [0, 0, 2], 40, 20)
    # X = (0.1, -0.05, 0) is at camera z = 2: x = 100 * 0.05 + 20, y = 100 * -0.025 + 10.
    x, y = cam.project([0.1, -0.05, 0.0])
    assert x == pytest.approx(25.0) and y == pytest.approx(7.5)
    assert cam.project([0, 0, -5]) is None
    np.testing.assert_allclose(cam.centre, [0, 0, -2])


@pytest.mark.parametrize(
    "change, needle",
    [
        (lambda a: a.update(images=[np.zeros((16, 24), np.uint8)] * 4), "images[0]"),
        (lambda a: a.update(images=[np.zeros((16, 24, 3), np.int32)] * 4), "dtype must be uint8"),
        (lambda a: a.update(images=[np.zeros((16, 48, 3), np.uint8)[:, ::2]] * 4), "not C-contiguous"),
        (lambda a: a["K"].__setitem__((1, 0, 0), np.nan), "K[1]: not finite"),
        (lambda a: a["t"].__setitem__((2, 1), np.inf), "t[2]: not finite"),
        (lambda a: a.update(R=a["R"][:3]), "invalid R"),
    ],
)
def test_bad_arrays_raise_value_error(change, needle):
    images, K, R, t = ring()
    args = {"images": images, "K": K.copy(), "R": R.copy(), "t": t.copy()}
    change(args)
    with pytest.raises(ValueError) as e:
        mpr.frame_set(**args)
    assert needle in str(e.value)


def test_errors_map_to_python_exceptions(tmp_path):
    with pytest.raises(OSError, match=r"^mpr: .*absent_par\.txt: cannot open"):
        mpr.read_par(tmp_path / "absent_par.txt")
    (tmp_path / "cameras.txt").write_text("1 FULL_OPENCV 4 4 1 1 1 1 0 0 0 0 0 0 0 0\n")
    (tmp_path / "images.txt").write_text("")
    with pytest.raises(OSError, match=r"cameras\.txt:1: camera model FULL_OPENCV is not supported"):
        mpr.read_colmap(tmp_path, tmp_path)
    images, K, R, t = ring()
    frames = mpr.frame_set(images, K, R, t)
    view = mpr.View.pinhole(frames.camera(0), 1.0)
    with pytest.raises(ValueError, match="interpolation: 'bogus'"):
        mpr.render(frames, view, 8, 8, interpolation="bogus")
    with pytest.raises(ValueError, match="invalid radius"):
        mpr.render(frames, view, 8, 8, interpolation="cylinder", radius=-1)
    with pytest.raises(ValueError, match="invalid point: not finite"):
        mpr.project(view, [np.nan, 0, 0])


def test_classify_and_project_gallery():
    plane = ([-1.0, -0.75, 0.0], [2.0, 0.0, 0.0], [0.0, 1.5, 0.0])
    types = {}
    for letter, _ in mpr.gallery_ids():
        types[letter] = mpr.classify(mpr.View.gallery(letter, *plane, [0, 0, 5], 2.0))["type"]
    assert types["A"] == "pinhole" and types["B"] == "orthographic" and types["G"] == "cross_slit"
    assert types["D"] == "pushbroom" and types["I"] == "bilinear"
    # An orthographic view along +z: the point (x, y, 3) projects to uv ((x + 1) / 2, (y + 0.75) / 1.5).
    ortho = mpr.View(*plane, [0, 0, 1], [0, 0, 1], [0, 0, 1])
    u, v = mpr.project(ortho, [0.5, 0.0, 3.0])
    assert u == pytest.approx(0.75) and v == pytest.approx(0.5)
    # Two-plane: every corner ray through the same point makes a pinhole there.
    pin = mpr.View.two_plane(*plane, [0, 0, -2], [0, 0, -2], [0, 0, -2])
    c = mpr.classify(pin)
    assert c["type"] == "pinhole"
    np.testing.assert_allclose(c["centre"], [0, 0, -2], atol=1e-5)


def quaternion(R):
    """(w, x, y, z) of a rotation matrix (trace > 0 branch; the test's cameras satisfy it)."""
    w = np.sqrt(1.0 + np.trace(R)) / 2
    return w, (R[2, 1] - R[1, 2]) / (4 * w), (R[0, 2] - R[2, 0]) / (4 * w), (R[1, 0] - R[0, 1]) / (4 * w)


def test_colmap_model_loads_to_the_par_cameras(golden, tmp_path):
    par = mpr.read_par(golden / "synth_par.txt")
    cameras, images = [], []
    for i in range(len(par)):
        c = par.camera(i)
        assert np.trace(c.R) > 0
        K = c.K
        cameras.append(f"{i + 1} PINHOLE {c.width} {c.height} {K[0, 0]!r} {K[1, 1]!r} {K[0, 2] + 0.5!r} {K[1, 2] + 0.5!r}")
        q = " ".join(repr(float(v)) for v in quaternion(c.R))
        t = " ".join(repr(float(v)) for v in c.t)
        images.append(f"{i + 1} {q} {t} {i + 1} {par.names[i]}\n")
    (tmp_path / "cameras.txt").write_text("\n".join(cameras) + "\n")
    (tmp_path / "images.txt").write_text("\n".join(images))
    colmap = mpr.read_colmap(tmp_path, golden)
    assert colmap.names == par.names
    for i in range(len(par)):
        np.testing.assert_allclose(colmap.camera(i).K, par.camera(i).K, rtol=1e-6)
        np.testing.assert_allclose(colmap.camera(i).R, par.camera(i).R, atol=1e-6)
        np.testing.assert_allclose(colmap.camera(i).t, par.camera(i).t, atol=1e-6)
        assert np.array_equal(colmap.image(i), par.image(i))
    (tmp_path / "images.txt").write_text("1 1 0 0 0 0 0 1 1 absent.png\n\n")
    with pytest.raises(OSError, match=r"images\.txt: image absent\.png: mpr: .*absent\.png"):
        mpr.read_colmap(tmp_path, golden)


def plane_depth(camera, z_plane=0.0):
    """Depth (camera z) of the world plane z = z_plane under every pixel: an analytic oracle."""
    w, h = camera.width, camera.height
    x, y = np.meshgrid(np.arange(w, dtype=float), np.arange(h, dtype=float))
    rays = np.stack([x, y, np.ones_like(x)], -1) @ np.linalg.inv(camera.K).T  # camera z = 1
    world_z = rays @ camera.R[2]  # z component of R^T r, for each pixel
    return ((z_plane - camera.centre[2]) / world_z).astype(np.float32)


def test_view_depth_of_a_plane_matches_the_analytic_depth():
    cams = [mpr.Camera.look_at([0.2 * (i - 1), 0.2 * (j - 1), -4], [0, 0, 0], [0, -1, 0], 0.6, 40, 30)
            for j in range(3) for i in range(3)]
    K, R, t = (np.stack([getattr(c, a) for c in cams]) for a in ("K", "R", "t"))
    images = [np.full((30, 40, 3), 128, np.uint8) for _ in cams]
    frames = mpr.frame_set(images, K, R, t, depths=[plane_depth(c) for c in cams])
    centre = frames.camera(4)
    view = mpr.View.pinhole(centre, 3.0)
    depth = mpr.view_depth(frames, view, 40, 30, along=centre)
    assert depth.shape == (30, 40) and depth.dtype == np.float32
    np.testing.assert_allclose(depth, plane_depth(centre), rtol=2e-3)
    with pytest.raises(ValueError):
        mpr.view_depth(mpr.frame_set(images, K, R, t), view, 40, 30)  # no depth maps


def checker_plane_image(camera):
    """What `camera` sees of a checkered plane z = 0 (0.25 squares), computed analytically."""
    w, h = camera.width, camera.height
    x, y = np.meshgrid(np.arange(w, dtype=float), np.arange(h, dtype=float))
    rays = np.stack([x, y, np.ones_like(x)], -1) @ np.linalg.inv(camera.K).T @ camera.R  # world directions
    points = camera.centre + plane_depth(camera)[..., None].astype(float) * rays
    cells = (np.floor(points[..., 0] / 0.25) + np.floor(points[..., 1] / 0.25)) % 2
    image = np.where(cells[..., None] > 0, 210, 30) * np.ones(3)
    return np.ascontiguousarray(image.astype(np.uint8))


def test_depth_interpolation_refocuses_onto_the_depth_maps():
    cams = [mpr.Camera.look_at([0.2 * (i - 1), 0.2 * (j - 1), -4], [0, 0, 0], [0, -1, 0], 0.6, 80, 60)
            for j in range(3) for i in range(3)]
    K, R, t = (np.stack([getattr(c, a) for c in cams]) for a in ("K", "R", "t"))
    images = [checker_plane_image(c) for c in cams]
    frames = mpr.frame_set(images, K, R, t, depths=[plane_depth(c) for c in cams])
    centre = frames.camera(4)
    view = mpr.View.pinhole(centre, 2.0)  # focused far in front of the plane
    wrong = np.abs(mpr.render(frames, view, 80, 60, interpolation="synthetic").astype(int) - images[4])
    right = np.abs(mpr.render(frames, view, 80, 60, interpolation="depth", radius=0.5).astype(int) - images[4])
    assert right.mean() < 0.5 * wrong.mean() and right.mean() < 6, (right.mean(), wrong.mean())
    with pytest.raises(ValueError):
        mpr.render(mpr.frame_set(images, K, R, t), view, 8, 8, interpolation="depth")
