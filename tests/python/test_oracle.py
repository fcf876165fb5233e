# SPDX-License-Identifier: Apache-2.0
"""The package's hits are the C oracle's, bit for bit: `rtcl trace --backend
cpu` (rt_trace_rays on the scalar oracle, through the command line, which
shares no code with the package but the library) on the same float32 rays,
written exactly (%.9g), on random and camera rays through generated meshes
and the shared bunny, and on the robustness suite (tests/robust/gen_cases.py:
closed meshes hit exactly at shared vertices and edges, far from the origin,
tiny and huge, +-0 directions, grazing rays, degenerate and coincident
triangles, t at the range's ends, invalid rays)."""

import json
import os
import subprocess
import sys

import numpy as np
import pytest

import rtcl
import util


def oracle_compare(tmp_path, scene_path, rays, scene=None, tmin=0.0, tmax=np.inf, tag="rays"):
    rays_path, out_path = str(tmp_path / (tag + ".rays")), str(tmp_path / (tag + ".hits"))
    util.write_rays(rays_path, rays, tmin, tmax)
    oracle = util.oracle_trace(scene_path, rays_path, out_path)
    scene = scene or rtcl.Scene.load(scene_path)
    for backend in ("packet", "cpu"):
        hits = scene.cast_rays(rays, tmin=tmin, tmax=tmax, backend=backend)
        util.assert_matches_oracle(hits, oracle, "%s on %s" % (backend, tag))
        assert np.array_equal(scene.test_occlusion(rays, tmin=tmin, tmax=tmax, backend=backend)
                              .reshape(-1), oracle[0]), "%s occlusion on %s" % (backend, tag)
    return oracle


def test_generated_mesh(tmp_path):
    v, f = util.sphere(32, 64, noise=0.02, seed=1)
    path = str(tmp_path / "ball.obj")
    util.write_obj(path, v, f)
    made = rtcl.Scene()
    made.add_mesh(v, f)
    rays = util.random_rays(20000, -1.5, 1.5, seed=2)
    o = oracle_compare(tmp_path, path, rays, made, tag="random")
    assert 5000 < o[0].sum() < 20000
    oracle_compare(tmp_path, path, util.camera_rays((0.3, 0.2, 3), (0, 0, 0), 64, 48),
                   tag="camera")
    oracle_compare(tmp_path, path, rays, tmin=0.5, tmax=2.0, tag="segments")


def test_bunny(tmp_path):
    path = util.shared_scene("stanford_bunny/stanford-bunny.obj")
    scene = rtcl.Scene.load(path)
    rng = np.random.default_rng(3)
    lo, hi = np.array([-0.1, 0.03, -0.06]), np.array([0.06, 0.19, 0.06])
    o = rng.uniform(lo, hi, size=(20000, 3))
    d = rng.standard_normal((20000, 3))
    rays = np.concatenate([o, d], axis=1).astype(np.float32)
    oracle_compare(tmp_path, path, rays, scene, tag="bunny-random")
    oracle_compare(tmp_path, path, util.camera_rays((-0.02, 0.11, 0.3), (-0.02, 0.11, 0), 96, 96,
                                                    40.0), scene, tag="bunny-camera")


def test_robustness_suite(tmp_path):
    cases = tmp_path / "cases"
    gen = os.path.join(util.SOURCE_DIR, "tests", "robust", "gen_cases.py")
    subprocess.run([sys.executable, gen, str(cases)], check=True, capture_output=True)
    manifest = json.load(open(cases / "manifest.json"))
    compared = 0
    for case in manifest["cases"]:
        if "--offset-origins" in case["flags"]:
            continue  # origins moved off a surface by rtcl trace: not a plain ray query
        name = case["name"]
        table = np.loadtxt(cases / (name + ".rays"), dtype=np.float32, ndmin=2)
        rays, tmin, tmax = table[:, :6], table[:, 6], table[:, 7]
        obj, rays_path = str(cases / (name + ".obj")), str(cases / (name + ".rays"))
        out = str(tmp_path / (name + ".hits"))
        scene = rtcl.Scene.load(obj)
        any_hit = "--any-hit" in case["flags"]
        oracle = util.oracle_trace(obj, rays_path, out, *(["--any-hit"] if any_hit else []))
        for backend in ("packet", "cpu"):
            if any_hit:
                got = scene.test_occlusion(rays, tmin=tmin, tmax=tmax, backend=backend)
                assert np.array_equal(got, oracle[0]), "%s: %s occlusion" % (name, backend)
            else:
                hits = scene.cast_rays(rays, tmin=tmin, tmax=tmax, backend=backend)
                util.assert_matches_oracle(hits, oracle, "%s on %s" % (backend, name))
        compared += len(rays)
    assert compared > 1000
