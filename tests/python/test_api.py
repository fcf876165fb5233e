# SPDX-License-Identifier: Apache-2.0
"""The rtcl package's API: shapes and dtypes of what goes in and comes out,
every refusal (TypeError or ValueError naming the argument, never a crash,
and a refused call changes nothing), zero-copy inputs, the GIL released
while tracing, and concurrent queries."""

import math
import os
import subprocess
import threading
import time
import tracemalloc

import numpy as np
import pytest

import rtcl
import util

TRI = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], np.float32)
ONE = np.array([[0, 1, 2]], np.int32)
DOWN = np.array([[0.25, 0.25, 1, 0, 0, -1]], np.float32)


@pytest.fixture
def tri_scene():
    s = rtcl.Scene()
    s.add_mesh(TRI, ONE)
    return s


@pytest.fixture(scope="module")
def sphere_scene():
    s = rtcl.Scene()
    s.add_mesh(*util.sphere(48, 96))
    return s


# ---- what comes out --------------------------------------------------------

def test_cast_rays_result(tri_scene):
    rays = np.array([[0.25, 0.25, 1, 0, 0, -1], [2, 2, 1, 0, 0, -1]], np.float32)
    h = tri_scene.cast_rays(rays)
    assert set(h) == set(util.HIT_KEYS)
    assert h["t_hit"].dtype == np.float32 and h["t_hit"].shape == (2,)
    for k in ("primitive_ids", "geometry_ids", "instance_ids"):
        assert h[k].dtype == np.uint32 and h[k].shape == (2,)
    assert h["primitive_uvs"].shape == (2, 2) and h["primitive_normals"].shape == (2, 3)
    assert h["t_hit"][0] == 1.0 and h["t_hit"][1] == np.inf
    assert list(h["primitive_ids"]) == [0, rtcl.INVALID_ID]
    assert list(h["geometry_ids"]) == [0, rtcl.INVALID_ID]
    assert list(h["instance_ids"]) == [0, rtcl.INVALID_ID]
    assert np.array_equal(h["primitive_uvs"], [[0.25, 0.25], [0, 0]])
    assert np.array_equal(h["primitive_normals"], [[0, 0, 1], [0, 0, 0]])
    assert tri_scene.last_backend == "packet"
    assert tri_scene.test_occlusion(rays).tolist() == [True, False]
    assert tri_scene.test_occlusions is not None  # Open3D's name
    c = tri_scene.count_intersections(rays)
    assert c.dtype == np.int32 and c.tolist() == [1, 0]


def test_leading_shapes(sphere_scene):
    rays = util.camera_rays((0, 0, 3), (0, 0, 0), 16, 9)
    h = sphere_scene.cast_rays(rays)
    assert h["t_hit"].shape == (9, 16) and h["primitive_normals"].shape == (9, 16, 3)
    flat = sphere_scene.cast_rays(rays.reshape(-1, 6))
    util.assert_same_hits({k: v.reshape(flat[k].shape) for k, v in h.items()}, flat, "reshaped")
    assert sphere_scene.test_occlusion(rays).shape == (9, 16)
    assert sphere_scene.count_intersections(rays).shape == (9, 16)
    one = sphere_scene.cast_rays(rays[4, 8])  # a single ray: 0-d results
    assert one["t_hit"].shape == () and one["primitive_uvs"].shape == (2,)
    assert one["t_hit"] == h["t_hit"][4, 8]


def test_pinhole_rays_are_the_cameras(tmp_path):
    """rtcl.pinhole_rays gives the library's camera rays (within float
    rounding): their t on the Cornell box is the depth AOV of rtcl render."""
    rays = rtcl.pinhole_rays((0, 0.9, 3), (0, 0.9, 0), 48, 27, 60.0)
    assert rays.shape == (27, 48, 6) and rays.dtype == np.float32
    assert np.allclose(rays[..., :3], [0, 0.9, 3])
    mid = rays[13, 23, 3:] + rays[13, 24, 3:]  # the two centre pixels: straight ahead
    assert abs(mid[0]) < 1e-6 and abs(mid[1]) < 1e-6 and mid[2] < 0
    out = str(tmp_path / "depth.pfm")
    r = subprocess.run([util.rtcl_tool(), "render", os.path.join(util.SOURCE_DIR, "scenes",
                                                                   "cornell.json"),
                        "--width", "48", "--height", "27", "--aov", "depth", "-o", out],
                       capture_output=True, text=True)
    if r.returncode != 0 and "JSON" in r.stderr:
        pytest.skip("this build has no JSON scenes: %s" % r.stderr.strip())
    assert r.returncode == 0, r.stderr
    data = open(out, "rb").read()
    parts = data.split(b"\n", 3)  # "Pf", "W H", scale, pixels (bottom row first)
    w, h = (int(x) for x in parts[1].split())
    scale = float(parts[2])
    depth = np.frombuffer(parts[3], "<f4" if scale < 0 else ">f4").reshape(h, w)[::-1]
    scene = rtcl.Scene.load(os.path.join(util.SOURCE_DIR, "scenes", "cornell.json"))
    t = scene.cast_rays(rays)["t_hit"]
    close = np.isclose(t, depth, rtol=1e-4) | ((t == np.inf) & (depth == np.inf))
    assert close.mean() > 0.98, close.mean()  # silhouette pixels may go either way
    with pytest.raises(ValueError, match="parallel"):
        rtcl.pinhole_rays((0, 0, 0), (0, 1, 0), 4, 4)


def test_origins_and_directions(sphere_scene):
    rays = util.random_rays(500, -2, 2, seed=3)
    want = sphere_scene.cast_rays(rays)
    util.assert_same_hits(sphere_scene.cast_rays(rays[:, :3], rays[:, 3:]), want, "o + d")
    # One origin for every ray.
    d = rays[:, 3:]
    one = sphere_scene.cast_rays(np.array([0.5, 0.25, 3.0]), d)
    full = sphere_scene.cast_rays(np.broadcast_to(np.float32([0.5, 0.25, 3.0]), d.shape).copy(), d)
    util.assert_same_hits(one, full, "one origin")


def test_dtypes_and_layouts_give_the_same_hits(sphere_scene):
    rays = util.random_rays(300, -2, 2, seed=4)
    want = sphere_scene.cast_rays(rays)
    for variant in (rays.astype(np.float64), np.asfortranarray(rays), rays.tolist(),
                    np.repeat(rays, 2, axis=0)[::2]):
        util.assert_same_hits(sphere_scene.cast_rays(variant), want, "variant")
    wide = np.zeros((300, 12), np.float32)
    wide[:, ::2] = rays  # a strided view: columns 0, 2, 4, ...
    util.assert_same_hits(sphere_scene.cast_rays(wide[:, ::2]), want, "strided")
    v, f = util.sphere(12, 24)
    a, b = rtcl.Scene(), rtcl.Scene()
    a.add_mesh(v, f)
    b.add_mesh(v.astype(np.float64).tolist(), f.astype(np.uint64))
    rays = util.random_rays(300, -2, 2, seed=5)
    util.assert_same_hits(a.cast_rays(rays), b.cast_rays(rays), "mesh dtypes")


def test_tmin_tmax(tri_scene):
    rays = np.repeat(DOWN, 4, axis=0)
    assert tri_scene.cast_rays(rays, tmax=0.5)["t_hit"].tolist() == [np.inf] * 4
    assert tri_scene.cast_rays(rays, tmin=1.0, tmax=1.0)["t_hit"].tolist() == [1.0] * 4
    per_ray = tri_scene.cast_rays(rays, tmin=np.array([0, 1.5, 0, 0]),
                                  tmax=np.array([2, 2, 0.5, np.inf]))["t_hit"]
    assert per_ray.tolist() == [1.0, np.inf, np.inf, 1.0]
    assert tri_scene.test_occlusion(rays, tmax=np.array([2, 0.5, 2, 0.5])).tolist() == \
        [True, False, True, False]
    assert tri_scene.count_intersections(rays, tmin=0.5, tmax=[2, 0.75, 2, 1]).tolist() == \
        [1, 0, 1, 1]


def test_invalid_rays_miss(tri_scene):
    rays = np.array([[np.nan, 0.25, 1, 0, 0, -1], [0.25, 0.25, 1, 0, 0, 0],
                     [0.25, 0.25, np.inf, 0, 0, -1], [0.25, 0.25, 1, 0, 0, -np.inf],
                     [0.25, 0.25, 1e300, 0, 0, -1]])
    h = tri_scene.cast_rays(rays)
    assert np.all(h["t_hit"] == np.inf) and np.all(h["primitive_ids"] == rtcl.INVALID_ID)
    assert not tri_scene.test_occlusion(rays).any()
    assert not tri_scene.count_intersections(rays).any()
    # A NaN end of one ray's range: that ray misses.
    two = DOWN.repeat(2, 0)
    assert tri_scene.cast_rays(two, tmax=[2, np.nan])["t_hit"].tolist() == [1.0, np.inf]
    assert tri_scene.test_occlusion(two, tmin=[np.nan, 0]).tolist() == [False, True]
    assert tri_scene.count_intersections(two, tmin=[np.nan, 0]).tolist() == [0, 1]


def test_empty_queries(tri_scene):
    for rays in (np.zeros((0, 6), np.float32), np.zeros((3, 0, 6))):
        h = tri_scene.cast_rays(rays)
        assert h["t_hit"].shape == rays.shape[:-1] and h["primitive_uvs"].shape == \
            rays.shape[:-1] + (2,)
        assert tri_scene.test_occlusion(rays).shape == rays.shape[:-1]
        assert tri_scene.count_intersections(rays).shape == rays.shape[:-1]
    empty = rtcl.Scene()  # no meshes at all: every ray misses
    assert empty.cast_rays(DOWN)["t_hit"][0] == np.inf
    assert empty.count_intersections(DOWN)[0] == 0
    empty.build()


def test_threads_and_backends_give_the_same_bits(sphere_scene):
    rays = util.random_rays(20000, -2, 2, seed=6)
    want = sphere_scene.cast_rays(rays, backend="cpu", threads=1)
    counts = sphere_scene.count_intersections(rays, threads=1)
    occluded = sphere_scene.test_occlusion(rays, backend="cpu", threads=1)
    for backend in ("cpu", "packet"):
        for threads in (1, 2, 3, None):
            got = sphere_scene.cast_rays(rays, backend=backend, threads=threads)
            util.assert_same_hits(got, want, "%s, %s threads" % (backend, threads))
            assert np.array_equal(sphere_scene.test_occlusion(rays, backend=backend,
                                                              threads=threads), occluded)
            assert np.array_equal(sphere_scene.count_intersections(rays, threads=threads), counts)
    assert np.array_equal(occluded, want["t_hit"] < np.inf)


def test_load_and_ids(tmp_path):
    v, f = util.sphere(8, 16)
    path = tmp_path / "ball.obj"
    util.write_obj(str(path), v, f)
    loaded = rtcl.Scene.load(path)  # a path-like object
    assert loaded.mesh_count == 1 and loaded.instance_count == 1
    made = rtcl.Scene()
    assert made.add_mesh(v, f) == 0
    rays = util.random_rays(1000, -2, 2, seed=8)
    util.assert_same_hits(loaded.cast_rays(rays), made.cast_rays(rays), "loaded vs made")
    # Instances: ids in order, meshes reported as geometry_ids.
    assert made.add_mesh(v, f, instance=False) == 1
    assert made.mesh_count == 2 and made.instance_count == 1
    m = np.eye(4)
    m[0, 3] = 5.0
    assert made.add_instance(1, m) == 1
    h = made.cast_rays(np.array([[5, 0, 3, 0, 0, -1], [0, 0, 3, 0, 0, -1]], np.float32))
    assert h["geometry_ids"].tolist() == [1, 0] and h["instance_ids"].tolist() == [1, 0]
    assert repr(made) == "<rtcl.Scene: 2 meshes, 2 instances>"


def test_accel_structures_give_the_same_bits():
    v, f = util.sphere(24, 48, noise=0.05, seed=2)
    rays = util.random_rays(5000, -2, 2, seed=9)
    want = None
    for accel in rtcl.ACCELS:
        s = rtcl.Scene()
        s.add_mesh(v, f, accel=accel)
        got = (s.cast_rays(rays), s.count_intersections(rays))
        if want is None:
            want = got
        util.assert_same_hits(got[0], want[0], accel)
        assert np.array_equal(got[1], want[1]), accel


# ---- refusals ----------------------------------------------------------------

def refuses(exc, match, fn, *args, **kwargs):
    with pytest.raises(exc, match=match):
        fn(*args, **kwargs)


def test_add_mesh_refusals():
    s = rtcl.Scene()
    refuses(ValueError, r"vertices: shape \(N, 3\)", s.add_mesh, TRI[:, :2], ONE)
    refuses(ValueError, r"vertices: shape", s.add_mesh, TRI.reshape(-1), ONE)
    refuses(TypeError, "vertices: an array of real numbers", s.add_mesh, TRI.astype(complex), ONE)
    refuses(TypeError, "vertices: an array of real numbers", s.add_mesh, TRI > 0, ONE)
    refuses(TypeError, "vertices", s.add_mesh, [["a", "b", "c"]] * 3, ONE)
    refuses(TypeError, "vertices: not an array", s.add_mesh, [[0, 0, 0], [1, 0], [0, 1, 0]], ONE)
    refuses(ValueError, "at least one vertex", s.add_mesh, np.zeros((0, 3)), ONE)
    bad = TRI.copy()
    bad[1, 2] = np.nan
    refuses(ValueError, "vertex 1 has a NaN or infinite", s.add_mesh, bad, ONE)
    bad[1, 2] = np.inf
    refuses(ValueError, "vertex 1 has a NaN or infinite", s.add_mesh, bad, ONE)
    refuses(ValueError, "vertex 2 has a float32-overflowing", s.add_mesh,
            np.array([[0, 0, 0], [1, 0, 0], [0, 1e39, 0]]), ONE)
    refuses(TypeError, "triangles: integer vertex indices", s.add_mesh, TRI, ONE.astype(float))
    refuses(ValueError, r"triangles: shape \(N, 3\)", s.add_mesh, TRI, [[0, 1, 2, 0]])
    refuses(ValueError, "at least one triangle", s.add_mesh, TRI, np.zeros((0, 3), int))
    refuses(ValueError, "negative index -1", s.add_mesh, TRI, [[0, 1, -1]])
    refuses(ValueError, "refers to vertex 3, but there are 3", s.add_mesh, TRI, [[0, 1, 3]])
    refuses(ValueError, "refers to vertex %d" % 2 ** 40, s.add_mesh, TRI, [[0, 1, 2 ** 40]])
    refuses(ValueError, "refers to vertex", s.add_mesh, TRI, np.array([[0, 1, 2 ** 63 - 1]]))
    refuses(ValueError, "accel: unknown structure 'octree'", s.add_mesh, TRI, ONE, accel="octree")
    assert s.mesh_count == 0 and s.instance_count == 0  # nothing was added


def test_add_instance_refusals():
    s = rtcl.Scene()
    s.add_mesh(TRI, ONE, instance=False)
    refuses(ValueError, "mesh 1 does not exist", s.add_instance, 1)
    refuses(ValueError, "mesh -1 does not exist", s.add_instance, -1)
    refuses(ValueError, "mesh %d does not exist" % 2 ** 40, s.add_instance, 2 ** 40)
    refuses(TypeError, "mesh: an integer id", s.add_instance, "0")
    refuses(TypeError, "mesh: an integer id", s.add_instance, 0.0)
    refuses(TypeError, "mesh: an integer id", s.add_instance, True)
    refuses(ValueError, "a 4x4 matrix", s.add_instance, 0, np.eye(3))
    refuses(ValueError, "finite", s.add_instance, 0, np.full((4, 4), np.nan))
    singular = np.eye(4)
    singular[2, 2] = 0
    refuses(ValueError, "transform: the transform is singular", s.add_instance, 0, singular)
    last = np.eye(4)
    last[3, 0] = 1
    refuses(ValueError, "last row", s.add_instance, 0, last)
    assert s.instance_count == 0
    assert s.add_instance(np.uint8(0), np.eye(4, dtype=np.float32)) == 0
    assert s.instance_count == 1


def test_update_vertices_refusals():
    s = rtcl.Scene()
    s.add_mesh(TRI, ONE)
    refuses(ValueError, "mesh 0 has 3 vertices; 2 positions given", s.update_vertices, 0,
            TRI[:2])
    refuses(ValueError, "mesh 5 does not exist", s.update_vertices, 5, TRI)
    refuses(ValueError, "policy: unknown update policy 'never'", s.update_vertices, 0, TRI,
            policy="never")
    refuses(ValueError, "NaN or infinite", s.update_vertices, 0, np.full((3, 3), np.nan))
    refuses(TypeError, "mesh: an integer id", s.update_vertices, None, TRI)
    assert s.cast_rays(DOWN)["t_hit"][0] == 1.0  # the mesh is as it was


def test_query_refusals(tri_scene):
    s = tri_scene
    for q in (s.cast_rays, s.test_occlusion, s.count_intersections):
        refuses(ValueError, r"rays: shape \(\.\.\., 6\)", q, DOWN[:, :5])
        refuses(ValueError, r"rays: shape \(\.\.\., 6\)", q, np.float32(1.0))
        refuses(TypeError, "rays: an array of real numbers", q, DOWN.astype(bool))
        refuses(TypeError, "rays: an array of real numbers", q, DOWN.astype(complex))
        refuses(TypeError, "rays: not an array", q, [[0, 0, 0, 0, 0, 1], [1, 2]])
        refuses(ValueError, r"directions: shape \(\.\.\., 3\)", q, DOWN[:, :3], DOWN)
        refuses(ValueError, "origins: shape", q, DOWN[:, :3].repeat(2, 0), DOWN[:, 3:])
        refuses(ValueError, "tmin must not be NaN", q, DOWN, tmin=np.nan)
        refuses(ValueError, "tmin: shape", q, DOWN.repeat(3, 0), tmin=[0, 1])
        refuses(TypeError, "tmax: an array of real numbers", q, DOWN, tmax="far")
        refuses(ValueError, "threads: 1 to 1024", q, DOWN, threads=0)
        refuses(ValueError, "threads: 1 to 1024", q, DOWN, threads=-2)
        refuses(ValueError, "threads: 1 to 1024", q, DOWN, threads=10 ** 9)
        refuses(TypeError, "threads: an integer or None", q, DOWN, threads=2.0)
        refuses(TypeError, "threads: an integer or None", q, DOWN, threads=True)
    for q in (s.cast_rays, s.test_occlusion):
        refuses(ValueError, "backend: unknown backend 'gpu'", q, DOWN, backend="gpu")
        refuses(ValueError, "only opencl, vulkan and auto take a device", q, DOWN,
                backend="cpu:0")
        refuses(ValueError, "only opencl, vulkan and auto take a device", q, DOWN,
                backend="opencl:")
        refuses(TypeError, "backend: a name", q, DOWN, backend=1)
    with pytest.raises(TypeError):
        s.count_intersections(DOWN, backend="cpu")  # counting is on the CPU


def test_load_refusals(tmp_path):
    refuses(OSError, "no_such_file.obj", rtcl.Scene.load, str(tmp_path / "no_such_file.obj"))
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")
    refuses(ValueError, r"bad\.obj:4", rtcl.Scene.load, bad)
    bad.write_text("v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    refuses(ValueError, r"bad\.obj:1", rtcl.Scene.load, bad)
    refuses(TypeError, "", rtcl.Scene.load, 42)


def test_device_backend_refusal(tri_scene):
    """A device that is not there: ValueError (no such device) or, in a build
    without OpenCL, RuntimeError, with the reason; the scene still works."""
    with pytest.raises((ValueError, RuntimeError), match="OpenCL"):
        tri_scene.cast_rays(DOWN, backend="opencl:no-such-device-anywhere")
    assert tri_scene.cast_rays(DOWN)["t_hit"][0] == 1.0


def test_extension_checks_what_it_reads(tri_scene):
    """The extension module checks sizes and formats itself: called directly
    with wrong arrays it raises, never reads or writes out of bounds."""
    core = tri_scene._core
    from rtcl import _rtcl
    f = np.zeros(6, np.float32)
    outs = lambda n: (np.empty(n, np.float32), np.empty(n, np.uint32), np.empty(n, np.uint32),
                      np.empty(n, np.uint32), np.empty(2 * n, np.float32),
                      np.empty(3 * n, np.float32))
    one = np.zeros(1, np.float32)
    with pytest.raises(ValueError, match="too few numbers"):
        core.query(_rtcl.CAST, 2, f, 0, 6, f, 3, 6, one, one, "cpu", 0, outs(2))
    with pytest.raises(ValueError, match="too few numbers"):
        core.query(_rtcl.CAST, 1, f, 4, 6, f, 3, 6, one, one, "cpu", 0, outs(1))
    with pytest.raises(ValueError, match="too few numbers"):
        core.query(_rtcl.CAST, 1, f, -1, 6, f, 3, 6, one, one, "cpu", 0, outs(1))
    with pytest.raises(TypeError, match="origins: items of format"):
        core.query(_rtcl.CAST, 1, f.astype(np.float64), 0, 6, f, 3, 6, one, one, "cpu", 0,
                   outs(1))
    with pytest.raises(ValueError, match="t_hit: 2 items where 1"):
        core.query(_rtcl.CAST, 1, f, 0, 6, f, 3, 6, one, one, "cpu", 0, outs(2))
    with pytest.raises(ValueError, match="tmin: 1 or 2 numbers"):
        core.query(_rtcl.CAST, 2, np.zeros(12, np.float32), 0, 6, np.zeros(12, np.float32), 3, 6,
                   np.zeros(3, np.float32), one, "cpu", 0, outs(2))
    ro = np.empty(1, np.float32)
    ro.flags.writeable = False
    o = list(outs(1))
    o[0] = ro
    with pytest.raises(TypeError, match="writable"):
        core.query(_rtcl.CAST, 1, f, 0, 6, f, 3, 6, one, one, "cpu", 0, tuple(o))
    with pytest.raises(ValueError, match="2 output arrays where 6"):
        core.query(_rtcl.CAST, 1, f, 0, 6, f, 3, 6, one, one, "cpu", 0, outs(1)[:2])
    with pytest.raises(ValueError, match="unknown query kind"):
        core.query(7, 1, f, 0, 6, f, 3, 6, one, one, "cpu", 0, outs(1))
    with pytest.raises(TypeError, match="occluded: items of format"):
        core.query(_rtcl.OCCLUSION, 1, f, 0, 6, f, 3, 6, one, one, "cpu", 0,
                   (np.empty(1, np.float32),))
    with pytest.raises(TypeError, match="C-contiguous"):
        core.add_mesh(np.zeros((3, 6), np.float32)[:, ::2], np.zeros(3, np.uint32), "bvh")
    with pytest.raises(ValueError, match="3 numbers per row"):
        core.add_mesh(np.zeros(4, np.float32), np.zeros(3, np.uint32), "bvh")
    with pytest.raises(ValueError, match="mesh 9 does not exist"):
        core.add_instance(9, None)
    with pytest.raises(ValueError, match="16 numbers"):
        core.add_instance(0, np.zeros(9, np.float32))


# ---- zero copy, the GIL, threads ------------------------------------------------

def peak_alloc(fn):
    """The most memory numpy and Python allocated during fn, in bytes."""
    tracemalloc.start()
    tracemalloc.reset_peak()
    base = tracemalloc.get_traced_memory()[0]
    fn()
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return peak - base


def test_contiguous_float32_is_read_in_place(sphere_scene):
    n = 200000
    rays = util.random_rays(n, -2, 2, seed=10)
    sphere_scene.cast_rays(rays[:10])  # builds the BVH outside the measurement
    outputs = n * (4 * 4 + 8 + 12)  # t, three ids, uv, normal
    in_place = peak_alloc(lambda: sphere_scene.cast_rays(rays))
    converted = peak_alloc(lambda: sphere_scene.cast_rays(rays.astype(np.float64)))
    assert in_place < outputs + n * 24 * 0.1, (in_place, outputs)
    assert converted >= outputs + n * 24 * 0.9, (converted, outputs)  # the measure sees copies
    o, d = rays[:, :3].copy(), rays[:, 3:].copy()
    assert peak_alloc(lambda: sphere_scene.cast_rays(o, d)) < outputs + n * 24 * 0.1
    assert peak_alloc(lambda: sphere_scene.test_occlusion(rays)) < n + n * 24 * 0.1
    assert peak_alloc(lambda: sphere_scene.count_intersections(rays)) < 4 * n + n * 24 * 0.1


def test_gil_is_released_while_tracing(sphere_scene):
    rays = util.random_rays(1500000, -2, 2, seed=11)
    sphere_scene.cast_rays(rays[:10], threads=1)
    span = {}

    def query():
        span["start"] = time.perf_counter()
        sphere_scene.cast_rays(rays, threads=1)
        span["end"] = time.perf_counter()

    worker = threading.Thread(target=query)
    stamps = []
    worker.start()
    while worker.is_alive():
        stamps.append(time.perf_counter())
    worker.join()
    inner = (span["end"] - span["start"]) * 0.2
    during = [t for t in stamps if span["start"] + inner < t < span["end"] - inner]
    # Held GIL: this thread could not run at all while the query was in C.
    assert len(during) > 1000, (len(during), span["end"] - span["start"])


def test_concurrent_queries_on_one_scene(sphere_scene):
    rays = [util.random_rays(20000, -2, 2, seed=20 + i) for i in range(4)]
    want = [sphere_scene.cast_rays(r, threads=1) for r in rays]
    want_counts = [sphere_scene.count_intersections(r) for r in rays]
    got = [None] * 4
    errors = []

    def run(i):
        try:
            for _ in range(3):
                got[i] = sphere_scene.cast_rays(rays[i], threads=1 + i % 2)
                assert np.array_equal(sphere_scene.count_intersections(rays[i]), want_counts[i])
        except Exception as e:  # reported below
            errors.append(e)

    threads = [threading.Thread(target=run, args=(i,)) for i in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors
    for i in range(4):
        util.assert_same_hits(got[i], want[i], "thread %d" % i)
