# SPDX-License-Identifier: Apache-2.0
"""rtcl.Scene: triangle meshes, instances of them, and ray queries on numpy
arrays (docs/PYTHON.md)."""

import math
import os

import numpy as np

from . import _arrays, _rtcl

INVALID_ID = 0xFFFFFFFF
"""The id of a miss in primitive_ids, geometry_ids and instance_ids (as
Open3D's RaycastingScene.INVALID_ID)."""

ACCELS = ("bvh", "kd", "kd-binned")
UPDATE_POLICIES = ("auto", "refit", "lbvh", "sah")
# The library's names before 0.2 (and the issue's): "fast" is lbvh, "rebuild" sah.
POLICY_ALIASES = {"fast": "lbvh", "rebuild": "sah"}


class Scene:
    """Meshes, instances of them, and exact ray queries.

    Every backend ("packet", the default; "cpu", the scalar oracle;
    "opencl", "vulkan"; "auto") gives the same bits: the hits of rtcl's C
    function rt_trace_rays on the oracle. Queries release the GIL; a scene
    may be queried from several threads (one query runs at a time per
    scene). Ids are dense and 0-based, in the order things were added.
    """

    def __init__(self):
        self._core = _rtcl.Scene()

    @classmethod
    def load(cls, path):
        """A scene from any file rtcl reads (a .json scene, an .obj, ...),
        with its meshes and objects (instances). OSError when the file cannot
        be read, ValueError (with file:line:column) when it is malformed."""
        scene = cls.__new__(cls)
        scene._core = _rtcl.load(os.fspath(path))
        return scene

    @property
    def mesh_count(self):
        """Meshes in the scene (ids 0 .. mesh_count - 1)."""
        return self._core.mesh_count

    @property
    def instance_count(self):
        """Instances (the library's objects) in the scene."""
        return self._core.instance_count

    @property
    def last_backend(self):
        """The backend that ran the last cast_rays or test_occlusion (what
        "auto" chose), or None before the first."""
        return self._core.last_backend

    def __repr__(self):
        return "<rtcl.Scene: %d meshes, %d instances>" % (self.mesh_count, self.instance_count)

    def add_mesh(self, vertices, triangles, accel="bvh", instance=True):
        """Adds a triangle mesh and returns its id.

        vertices: (V, 3) real numbers (float32 is taken as it is; other
        types are rounded to float32, and must then be finite).
        triangles: (F, 3) integers, vertex indices in [0, V).
        accel: "bvh", "kd" or "kd-binned" (every structure gives the same
        hits). instance: also add an instance of the mesh with the identity
        transform (as Open3D's add_triangles does); False adds only the mesh,
        for add_instance."""
        if accel not in ACCELS:
            raise ValueError("accel: unknown structure %r (%s)" % (accel, ", ".join(ACCELS)))
        v = _arrays.vertices("vertices", vertices)
        t = _arrays.triangles("triangles", triangles, v.shape[0])
        mesh = self._core.add_mesh(v, t, accel)
        if instance:
            self._core.add_instance(mesh, None)
        return mesh

    def add_instance(self, mesh, transform=None):
        """Adds an instance of a mesh and returns its id. transform: a 4x4
        matrix acting on column vectors (p' = M p, the translation in the last
        column), last row 0 0 0 1, invertible; None is the identity."""
        m = _arrays.identifier("mesh", mesh)
        matrix = None if transform is None else _arrays.transform("transform", transform)
        return self._core.add_instance(m, matrix)

    def update_vertices(self, mesh, vertices, policy="auto"):
        """Moves every vertex of a mesh (the triangles stay) and says how the
        next query brings its BVH up to date: "refit" (keep the tree, recompute
        its boxes), "lbvh" (a quick Morton-code LBVH build; also "fast"),
        "sah" (a full binned SAH build; also "rebuild") or "auto" (refit while
        the tree stays within rtcl's bound of an SAH build's cost, else an SAH
        build). Every policy gives the same hits. A kd-tree mesh becomes a BVH
        mesh."""
        name = POLICY_ALIASES.get(policy, policy) if isinstance(policy, str) else policy
        if name not in UPDATE_POLICIES:
            raise ValueError("policy: unknown update policy %r (%s; or fast, rebuild)"
                             % (policy, ", ".join(UPDATE_POLICIES)))
        m = _arrays.identifier("mesh", mesh)
        v = _arrays.vertices("vertices", vertices)
        self._core.update_vertices(m, v, name)

    def build(self, backend="packet", threads=None):
        """Brings the acceleration structures (and a device backend's copy of
        them) up to date now; the first query does it otherwise."""
        empty = np.zeros(1, np.float32)
        outputs = (np.empty(0, np.float32), np.empty(0, np.uint32), np.empty(0, np.uint32),
                   np.empty(0, np.uint32), np.empty(0, np.float32), np.empty(0, np.float32))
        self._core.query(_rtcl.CAST, 0, empty, 0, 0, empty, 0, 0, empty, empty,
                         _arrays.backend(backend), _arrays.threads(threads), outputs)

    def cast_rays(self, rays, directions=None, *, tmin=0.0, tmax=math.inf, backend="packet",
                  threads=None):
        """The closest hit of each ray.

        rays: (..., 6) real numbers, ox oy oz dx dy dz per ray; or origins
        (..., 3) (or (3,), one origin for all) and directions (..., 3). The
        ray is o + t d for t in [tmin, tmax] (inclusive; scalars, not NaN, or
        arrays that broadcast to the rays' leading shape); d need not be unit
        length and t is in units of its length. A contiguous float32 array is read in place;
        anything else is converted to float32 once. A ray with a NaN or
        infinite component, a NaN end or a zero direction misses.
        backend: "packet", "cpu", "opencl", "vulkan", "auto" (a device when
        there is one), or "opencl:DEVICE"; threads: the CPU backends' threads
        (None: every core). Every backend gives the same bits.

        Returns a dict of arrays of the rays' leading shape (...):
        t_hit float32 (inf on a miss); primitive_ids uint32 (the triangle's
        index in its mesh), geometry_ids uint32 (the mesh), instance_ids
        uint32 (INVALID_ID on a miss); primitive_uvs float32 (..., 2), the
        barycentrics (u, v) of the hit, p = (1-u-v) v0 + u v1 + v v2;
        primitive_normals float32 (..., 3), the triangle's unit geometric
        normal in world space, (v1 - v0) x (v2 - v0) normalised (0 on a miss).
        Ties in t go to the lower instance, then the lower triangle."""
        r = _arrays.Rays(rays, directions, tmin, tmax)
        n = r.n
        t = np.empty(n, np.float32)
        prim = np.empty(n, np.uint32)
        geom = np.empty(n, np.uint32)
        inst = np.empty(n, np.uint32)
        uv = np.empty((n, 2), np.float32)
        normal = np.empty((n, 3), np.float32)
        self._core.query(_rtcl.CAST, *r.args(), _arrays.backend(backend),
                         _arrays.threads(threads), (t, prim, geom, inst, uv, normal))
        s = r.shape
        return {"t_hit": t.reshape(s), "primitive_ids": prim.reshape(s),
                "geometry_ids": geom.reshape(s), "instance_ids": inst.reshape(s),
                "primitive_uvs": uv.reshape(s + (2,)), "primitive_normals": normal.reshape(s + (3,))}

    def test_occlusion(self, rays, directions=None, *, tmin=0.0, tmax=math.inf, backend="packet",
                       threads=None):
        """Whether each ray hits anything in [tmin, tmax]: a bool array of
        the rays' leading shape. Arguments as for cast_rays; stops at the
        first hit found, so it is faster than cast_rays. The answer is exact
        (the same as cast_rays' t_hit < inf on the same range)."""
        r = _arrays.Rays(rays, directions, tmin, tmax)
        occluded = np.empty(r.n, np.bool_)
        self._core.query(_rtcl.OCCLUSION, *r.args(), _arrays.backend(backend),
                         _arrays.threads(threads), (occluded,))
        return occluded.reshape(r.shape)

    test_occlusions = test_occlusion  # Open3D's RaycastingScene name

    def count_intersections(self, rays, directions=None, *, tmin=0.0, tmax=math.inf,
                            threads=None):
        """How many triangles each ray crosses in [tmin, tmax]: an int32
        array of the rays' leading shape; an odd count from a point to
        infinity means inside a closed mesh. Each triangle counts once.

        The crossing rule: a crossing is a hit of rtcl's watertight test that
        cast_rays could report. Where a ray passes exactly through an edge or
        a vertex (an edge function exactly zero) it counts as if moved by an
        infinitesimal (e, e^2) in the test's sheared 2D frame, so exactly one
        of the triangles around an edge or vertex it passes through counts,
        and a silhouette it only touches counts 0 or 2: a closed mesh's
        inside/outside parity is right whenever no crossing lies within a
        few ulps of tmin or tmax. A ray in a triangle's plane crosses nothing.

        Runs on the CPU (the scalar oracle's code, threads as for cast_rays)
        whatever backend the other queries use."""
        r = _arrays.Rays(rays, directions, tmin, tmax)
        counts = np.empty(r.n, np.int32)
        self._core.query(_rtcl.COUNT, *r.args(), "", _arrays.threads(threads), (counts,))
        return counts.reshape(r.shape)
