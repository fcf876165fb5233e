# SPDX-License-Identifier: Apache-2.0
"""rtcl: exact, watertight ray queries on numpy arrays.

    import numpy as np, rtcl
    scene = rtcl.Scene()
    scene.add_mesh(vertices, triangles)          # (V, 3) floats, (F, 3) ints
    hits = scene.cast_rays(rays)                 # rays (..., 6): origin, direction
    hits["t_hit"], hits["primitive_ids"], hits["primitive_normals"]
    inside = scene.count_intersections(rays) % 2 == 1

Every backend ("packet", "cpu", "opencl", "vulkan") gives the bits of the
rtcl library's scalar oracle; rays through shared edges and vertices never
slip through a closed mesh. docs/PYTHON.md has the whole API."""

from ._arrays import BACKENDS
from ._rtcl import version as __version__
from .rays import pinhole_rays
from .scene import ACCELS, INVALID_ID, UPDATE_POLICIES, Scene

__all__ = ["Scene", "pinhole_rays", "INVALID_ID", "BACKENDS", "ACCELS", "UPDATE_POLICIES",
           "__version__"]
