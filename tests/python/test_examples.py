# SPDX-License-Identifier: Apache-2.0
"""The examples in examples/python run as the README shows them (from the
repository root, on the shared scenes) and produce what they say: a PLY
point cloud of surface points with unit normals within the sensor's range,
and an inside share of the bunny's box near the bunny's volume."""

import os
import re
import subprocess
import sys

import numpy as np

import util

EXAMPLES = os.path.join(util.SOURCE_DIR, "examples", "python")


def run(script, *args):
    r = subprocess.run([sys.executable, os.path.join(EXAMPLES, script)] + list(args),
                       capture_output=True, text=True, cwd=util.SOURCE_DIR)
    assert r.returncode == 0, r.stderr
    assert r.stderr == "", r.stderr
    return r.stdout


def test_examples_are_short():
    for name in os.listdir(EXAMPLES):
        if name.endswith(".py"):
            with open(os.path.join(EXAMPLES, name)) as f:
                assert len(f.readlines()) < 30, name


def test_lidar_sponza(tmp_path):
    sponza = util.shared_scene("sponza_dabrovic/sponza.obj")
    out = str(tmp_path / "scan.ply")
    m = re.match(r"(\S+): (\d+) points from (\d+) beams", run("lidar_sponza.py", sponza, out))
    assert m, "unexpected output"
    points, beams = int(m.group(2)), int(m.group(3))
    data = open(out, "rb").read()
    header, body = data.split(b"end_header\n", 1)
    assert b"element vertex %d" % points in header
    cloud = np.frombuffer(body, "<f4").reshape(-1, 6)
    assert len(cloud) == points and 0.9 * beams < points <= beams  # Sponza is closed around the nave
    assert np.isfinite(cloud).all()
    assert np.allclose(np.linalg.norm(cloud[:, 3:], axis=1), 1.0, atol=1e-6)
    sensor_x = np.linspace(-12.0, 12.0, 25)
    near = np.min(np.abs(cloud[:, None, 0] - sensor_x[None, :]), axis=1)
    assert (near <= 40.0).all()


def test_inside_bunny():
    bunny = util.shared_scene("stanford_bunny/stanford-bunny.obj")
    m = re.match(r"(\d+) of (\d+) points inside \(([\d.]+)% of the box", run("inside_bunny.py",
                                                                          bunny))
    assert m, "unexpected output"
    share = float(m.group(3))
    assert 20.0 < share < 32.0, share  # the bunny fills about a quarter of its box
