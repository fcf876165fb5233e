# SPDX-License-Identifier: Apache-2.0
"""bench/python_open3d.py on a small run (counts, not timing): it runs beside
Open3D and the Embree peer, reports every field, its classes add up, and
rtcl never misses a clear exact crossing (a leak), on the bunny."""

import json
import os
import subprocess
import sys

import pytest

import util


def test_small_run(tmp_path):
    pytest.importorskip("open3d", reason="Open3D is not installed (python3-open3d)")
    util.shared_scene("stanford_bunny/stanford-bunny.obj")
    out = str(tmp_path / "bench.json")
    env = dict(os.environ)
    r = subprocess.run([sys.executable, os.path.join(util.SOURCE_DIR, "bench", "python_open3d.py"),
                        "--scenes", util.SHARED_SCENES, "--only", "bunny", "--rays", "4000",
                        "--reps", "1", "--json", out], capture_output=True, text=True, env=env)
    assert r.returncode == 0, r.stderr
    report = json.load(open(out))
    (scene,) = report["scenes"]
    assert scene["triangles"] == 69451
    assert [s["rays"] for s in scene["sets"]] == ["random", "camera", "vertex"]
    for s in scene["sets"]:
        assert s["n"] > 3000 and s["hits_rtcl"] > 0
        for peer in ("open3d", "embree"):
            d = s["vs_" + peer]
            assert d["peer_miss_at_edge"] <= d["peer_miss"]
            assert d["occlusion_peer_miss"] <= d["occlusion"]
            assert s["hits_rtcl"] - d["peer_miss"] + d["rtcl_miss"] == s["hits_" + peer]
            assert d["rtcl_miss_clear_crossing"] == 0, "rtcl leaked through %s" % peer
            assert d["rtcl_miss_exact_crossing"] <= d["rtcl_miss_checked"]
        for key in ("cast_mrays_rtcl", "occlusion_mrays_embree", "cast_mrays_open3d"):
            assert s[key] > 0
