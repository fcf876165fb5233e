# SPDX-License-Identifier: Apache-2.0
"""Rays to query with: the rays of a pinhole camera."""

import numpy as np


def pinhole_rays(eye, look_at, width, height, hfov_degrees=60.0, up=(0.0, 1.0, 0.0)):
    """The rays (height, width, 6) float32 of a pinhole camera at eye looking
    at look_at, through the centres of its pixels (row 0 at the top), with a
    horizontal field of view of hfov_degrees: the geometry of rtcl's camera
    (rt.h's rt_camera, kernels/rt_layout.h): direction forward + sx right +
    sy up, with right and up scaled by tan(hfov / 2) (up also by height /
    width), sx and sy in (-1, 1). Directions are not unit length: t is in
    their units (t = 1 on the image plane one unit ahead). Computed in
    double and rounded once, so they are within float rounding of the
    library's own camera rays, not their bits."""
    eye = np.asarray(eye, np.float64)
    f = np.asarray(look_at, np.float64) - eye
    if not (width >= 1 and height >= 1 and 0.0 < hfov_degrees < 180.0):
        raise ValueError("pinhole_rays: width and height >= 1, 0 < hfov_degrees < 180")
    f = f / np.linalg.norm(f)
    right = np.cross(f, np.asarray(up, np.float64))
    if not np.linalg.norm(right) > 1e-6:
        raise ValueError("pinhole_rays: up is parallel to the view direction")
    right /= np.linalg.norm(right)
    u = np.cross(right, f)
    tx = np.tan(np.radians(hfov_degrees) / 2)
    ty = tx * height / width
    sx = (2.0 * (np.arange(width) + 0.5) / width - 1.0) * tx
    sy = (1.0 - 2.0 * (np.arange(height) + 0.5) / height) * ty
    d = f + sx[None, :, None] * right + sy[:, None, None] * u
    o = np.broadcast_to(eye, d.shape)
    return np.concatenate([o, d], axis=-1).astype(np.float32)
