"""Frame sets read uint8 arrays in place: checked by memory and by data sharing."""

import gc
import os
import weakref

import numpy as np
import pytest

import mpr

# A build with AddressSanitizer copies every frame (CameraFrameSet::can_share): nothing to share.
pytestmark = pytest.mark.skipif(os.environ.get("MPR_ADDRESS_SANITIZER") == "1",
                                reason="frames are copied under AddressSanitizer")


def resident_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def row_of_cameras(n, w, h):
    cams = [mpr.Camera.look_at([0.05 * (i - n // 2), 0, -3], [0, 0, 0], [0, -1, 0], 0.6, w, h) for i in range(n)]
    return np.stack([c.K for c in cams]), np.stack([c.R for c in cams]), np.stack([c.t for c in cams])


def test_twenty_megapixel_frames_add_no_copy():
    n, w, h = 20, 1000, 1000
    rng = np.random.default_rng(5)
    images = [rng.integers(0, 256, (h, w, 3), dtype=np.uint8) for _ in range(n)]  # every page written
    K, R, t = row_of_cameras(n, w, h)
    array_bytes = sum(im.nbytes for im in images)  # 60 MB
    gc.collect()
    before = resident_bytes()
    frames = mpr.frame_set(images, K, R, t)
    added = resident_bytes() - before
    shared = sum(frames.shares(i) for i in range(n))
    # An array the kernels cannot read in place (about 1 in 64) is copied twice (image and texels).
    assert shared >= n - 5
    assert added < 2 * (n - shared) * images[0].nbytes + array_bytes // 20, (
        f"resident memory grew by {added / 2**20:.1f} MiB for {array_bytes / 2**20:.1f} MiB of arrays "
        f"({shared} of {n} frames shared)")


def shareable(image):
    """A copy of `image` placed so that the 64 bytes after it lie in its last 4 KiB block."""
    buf = np.empty(image.nbytes + 4096, np.uint8)
    start = next(o for o in range(4096) if 1 <= (buf.ctypes.data + o + image.nbytes) % 4096 <= 4096 - 64)
    out = buf[start:start + image.nbytes].reshape(image.shape)
    out[...] = image
    return out


def test_writing_to_a_shared_array_changes_the_render():
    n, w, h = 3, 24, 16
    K, R, t = row_of_cameras(n, w, h)
    images = [shareable(np.full((h, w, 3), 40 * (i + 1), np.uint8)) for i in range(n)]
    frames = mpr.frame_set(images, K, R, t)
    assert all(frames.shares(i) for i in range(n))
    view = mpr.View.pinhole(frames.camera(1), 3.0)
    # The nearest interpolation at camera 1's own view reads camera 1's pixels (an independent
    # oracle: the array itself).
    assert np.array_equal(mpr.render(frames, view, w, h, interpolation="nearest"), images[1])
    images[1][5, 7] = (1, 2, 3)
    after = mpr.render(frames, view, w, h, interpolation="nearest")
    assert tuple(after[5, 7]) == (1, 2, 3)
    assert np.array_equal(after, images[1])
    assert np.array_equal(frames.image(1), images[1])


def test_the_set_keeps_its_arrays_alive():
    n, w, h = 3, 24, 16
    K, R, t = row_of_cameras(n, w, h)
    images = [shareable(np.full((h, w, 3), 60 * i, np.uint8)) for i in range(n)]
    base = images[2].base
    watch = weakref.ref(base)
    frames = mpr.frame_set(images, K, R, t)
    view = mpr.View.pinhole(frames.camera(2), 3.0)
    del images, base
    gc.collect()
    assert watch() is not None  # held by the set
    out = mpr.render(frames, view, w, h, interpolation="nearest")
    assert (out == 120).all()
    del frames
    gc.collect()
    assert watch() is None  # released with the set


def test_float32_and_loaded_frames_are_copies():
    n, w, h = 2, 24, 16
    K, R, t = row_of_cameras(n, w, h)
    linear = [np.full((h, w, 3), 0.5, np.float32) for _ in range(n)]
    frames = mpr.frame_set(linear, K, R, t)
    assert not frames.shares(0)
    linear[0][...] = 1.0
    assert (frames.image(0) == 0.5).all()  # converted at construction
