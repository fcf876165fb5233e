# SPDX-License-Identifier: Apache-2.0
"""embree_ctypes.py - Embree 3 from Python through ctypes, queried the way
Open3D's RaycastingScene queries it (one triangle geometry per mesh,
RTC_SCENE_FLAG_ROBUST, rtcIntersect1M / rtcOccluded1M over batches of rays on
several threads), but with the ray mask set to all ones.

Why it exists: Debian 12's python3-open3d 0.16.1 sets every ray's mask to 0
and links Debian's libembree3 3.13.5, which is built with EMBREE_RAY_MASK=ON
(/usr/lib/x86_64-linux-gnu/cmake/embree-3.13.5/embree-config.cmake), so
(mask & geometry mask) is 0 and Open3D's cast_rays, test_occlusions and
count_intersections miss every ray there. This peer shows what the same
Embree calls do with a working mask, beside rtcl, in the same run.

ctypes releases the GIL during each foreign call, so the batches run in
parallel on a thread pool."""

import ctypes
import ctypes.util
from concurrent.futures import ThreadPoolExecutor

import numpy as np

RTC_GEOMETRY_TYPE_TRIANGLE = 0
RTC_BUFFER_TYPE_INDEX, RTC_BUFFER_TYPE_VERTEX = 0, 1
RTC_FORMAT_UINT3, RTC_FORMAT_FLOAT3 = 0x5003, 0x9003
RTC_SCENE_FLAG_ROBUST = 1 << 2
INVALID = 0xFFFFFFFF
BATCH = 1 << 14

# struct RTCRay (48 bytes) and RTCHit (32 bytes, one instance level): an
# RTCRayHit of 80 bytes (sizes as a C compiler gives them for Debian's
# headers).
RAY_FIELDS = [("org", "<f4", 3), ("tnear", "<f4"), ("dir", "<f4", 3), ("time", "<f4"),
              ("tfar", "<f4"), ("mask", "<u4"), ("id", "<u4"), ("flags", "<u4")]
RAY = np.dtype(RAY_FIELDS, align=True)
RAYHIT = np.dtype(RAY_FIELDS + [("Ng", "<f4", 3), ("u", "<f4"), ("v", "<f4"), ("primID", "<u4"),
                                ("geomID", "<u4"), ("instID", "<u4")], align=True)
assert RAY.itemsize == 48 and RAYHIT.itemsize == 80


class _Context(ctypes.Structure):
    """struct RTCIntersectContext as rtcInitIntersectContext fills it
    (RTC_MAX_INSTANCE_LEVEL_COUNT 1, no minimum width: Debian's build)."""
    _fields_ = [("flags", ctypes.c_int), ("filter", ctypes.c_void_p),
                ("instID", ctypes.c_uint * 1)]


def _library():
    name = ctypes.util.find_library("embree3") or "libembree3.so.3"
    lib = ctypes.CDLL(name)
    vp, u, sz = ctypes.c_void_p, ctypes.c_uint, ctypes.c_size_t
    for fn, res, args in (("rtcNewDevice", vp, [ctypes.c_char_p]),
                          ("rtcNewScene", vp, [vp]), ("rtcSetSceneFlags", None, [vp, ctypes.c_int]),
                          ("rtcNewGeometry", vp, [vp, ctypes.c_int]),
                          ("rtcSetSharedGeometryBuffer", None, [vp, ctypes.c_int, u, ctypes.c_int,
                                                                vp, sz, sz, sz]),
                          ("rtcCommitGeometry", None, [vp]), ("rtcAttachGeometry", u, [vp, vp]),
                          ("rtcReleaseGeometry", None, [vp]), ("rtcCommitScene", None, [vp]),
                          ("rtcIntersect1M", None, [vp, vp, vp, u, sz]),
                          ("rtcOccluded1M", None, [vp, vp, vp, u, sz]),
                          ("rtcReleaseScene", None, [vp]), ("rtcReleaseDevice", None, [vp]),
                          ("rtcGetDeviceError", ctypes.c_int, [vp])):
        f = getattr(lib, fn)
        f.restype, f.argtypes = res, args
    return lib


class EmbreeScene:
    """Triangle meshes in one Embree scene; cast_rays and test_occlusion on
    (N, 6) float32 rays, answering as Open3D's RaycastingScene does."""

    def __init__(self, threads=None):
        self.lib = _library()
        self.device = self.lib.rtcNewDevice(None)
        if not self.device:
            raise RuntimeError("rtcNewDevice failed")
        self.scene = self.lib.rtcNewScene(self.device)
        self.lib.rtcSetSceneFlags(self.scene, RTC_SCENE_FLAG_ROBUST)
        self.keep = []  # the shared buffers live as long as the scene
        self.committed = False
        self.pool = ThreadPoolExecutor(threads or None)

    def add_triangles(self, vertices, triangles):
        v = np.ascontiguousarray(vertices, np.float32)
        v = np.concatenate([v, np.zeros((1, 3), np.float32)])  # Embree reads 16 bytes a vertex
        t = np.ascontiguousarray(triangles, np.uint32)
        g = self.lib.rtcNewGeometry(self.device, RTC_GEOMETRY_TYPE_TRIANGLE)
        self.lib.rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                            v.ctypes.data, 0, 12, len(v) - 1)
        self.lib.rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                            t.ctypes.data, 0, 12, len(t))
        self.lib.rtcCommitGeometry(g)
        gid = self.lib.rtcAttachGeometry(self.scene, g)
        self.lib.rtcReleaseGeometry(g)
        self.keep += [v, t]
        self.committed = False
        return gid

    def _rays(self, rays, dtype):
        r = np.ascontiguousarray(rays, np.float32).reshape(-1, 6)
        out = np.zeros(len(r), dtype)
        out["org"], out["dir"] = r[:, :3], r[:, 3:]
        out["tfar"] = np.inf
        out["mask"] = 0xFFFFFFFF
        if dtype is RAYHIT:
            out["geomID"] = INVALID
            out["instID"] = INVALID
        return out

    def _run(self, fn, buf):
        if not self.committed:
            self.lib.rtcCommitScene(self.scene)
            self.committed = True
        ctx = _Context(0, None, (ctypes.c_uint * 1)(INVALID))
        base, stride = buf.ctypes.data, buf.dtype.itemsize
        jobs = [self.pool.submit(fn, self.scene, ctypes.byref(ctx), base + i * stride,
                                 min(BATCH, len(buf) - i), stride)
                for i in range(0, len(buf), BATCH)]
        for j in jobs:
            j.result()
        if self.lib.rtcGetDeviceError(self.device):
            raise RuntimeError("Embree reported an error")

    def cast_rays(self, rays):
        buf = self._rays(rays, RAYHIT)
        self._run(self.lib.rtcIntersect1M, buf)
        hit = buf["geomID"] != INVALID
        ng = buf["Ng"]
        with np.errstate(invalid="ignore", divide="ignore"):
            n = ng / np.linalg.norm(ng, axis=1, keepdims=True)
        return {"t_hit": np.where(hit, buf["tfar"], np.float32(np.inf)),
                "geometry_ids": buf["geomID"].copy(),
                "primitive_ids": np.where(hit, buf["primID"], INVALID).astype(np.uint32),
                "primitive_uvs": np.where(hit[:, None], np.stack([buf["u"], buf["v"]], 1), 0)
                .astype(np.float32),
                "primitive_normals": np.where(hit[:, None], n, 0).astype(np.float32)}

    def test_occlusion(self, rays):
        buf = self._rays(rays, RAY)
        self._run(self.lib.rtcOccluded1M, buf)
        return buf["tfar"] == -np.inf

    def close(self):
        self.pool.shutdown()
        self.lib.rtcReleaseScene(self.scene)
        self.lib.rtcReleaseDevice(self.device)
