"""mpr: multi-perspective rendering from Python.

Light fields (camera arrays) from mpr's loaders or from numpy arrays, views through General
Linear Cameras, renders into numpy arrays, depth maps by plane sweep. Lengths are world units;
pixel coordinates put pixel centres at integers (OpenCV); uv in [0, 1]^2 spans a view's image.
Errors raise ValueError (bad arguments) or OSError (files) with mpr's one-line message.
"""

from ._mpr import (  # noqa: F401
    Camera,
    FrameSet,
    Scene,
    classroom,
    View,
    classify,
    estimate_depth,
    filters,
    frame_set,
    gallery_ids,
    interpolations,
    project,
    read_colmap,
    read_hci,
    read_lfca,
    read_par,
    read_stanford,
    render,
    render_scene,
    render_views,
    score_disparity,
    view_depth,
)

try:  # with tinyobjloader only
    from ._mpr import read_obj  # noqa: F401
except ImportError:
    pass

__all__ = [
    "Camera", "FrameSet", "View", "classify", "estimate_depth", "filters", "frame_set", "gallery_ids",
    "interpolations", "project", "read_colmap", "read_lfca", "read_par", "read_stanford", "render",
    "render_views", "Scene", "classroom", "render_scene", "view_depth", "read_hci", "score_disparity",
]
