# SPDX-License-Identifier: Apache-2.0
"""Every backend this machine has gives the same bits through the package:
packet, cpu, opencl (PoCL here) and vulkan (lavapipe here), on closest hits
(t, ids, u, v and the host's normals) and occlusion, for random rays, camera
rays and rays through a closed mesh's vertices and edges (none leaks). A
device backend without a device (`rtcl devices --api NAME` fails) is
skipped with the reason; with a device it must work."""

import numpy as np
import pytest

import rtcl
import util


@pytest.fixture(scope="module")
def scene_and_rays():
    v, f = util.sphere(32, 64, noise=0.02, seed=21)
    vox = util.Voxels(4, seed=7, scale=0.25, offset=2.0)
    s = rtcl.Scene()
    s.add_mesh(v, f)
    s.add_mesh(vox.vertices, vox.triangles, accel="kd")
    m = np.eye(4)
    m[:3, :3] = [[0, 0, 1.5], [0, 1.5, 0], [-1.5, 0, 0]]
    m[:3, 3] = [-3, 0.5, 0]
    s.add_instance(0, m)
    exact, inside = vox.exact_rays(seed=3)
    rays = np.concatenate([util.random_rays(6000, -4, 4, seed=22),
                           util.camera_rays((0, 1, 8), (0, 0, 0), 64, 32).reshape(-1, 6), exact])
    return s, rays, len(rays) - len(exact), inside


@pytest.mark.parametrize("backend", ["packet", "opencl", "vulkan", "auto"])
def test_backend_gives_the_oracles_bits(scene_and_rays, backend):
    if backend in ("opencl", "vulkan"):
        why = util.backend_devices(backend)
        if why:
            pytest.skip("no %s device: %s" % (backend, why))
    s, rays, first_exact, inside = scene_and_rays
    want = s.cast_rays(rays, backend="cpu")
    got = s.cast_rays(rays, backend=backend)
    used = s.last_backend
    assert used in ("cpu", "packet", "opencl", "vulkan")
    util.assert_same_hits(got, want, backend)
    assert np.array_equal(s.test_occlusion(rays, backend=backend), want["t_hit"] < np.inf)
    hit = got["t_hit"][first_exact:] < np.inf
    assert hit[inside == 1].all(), "%s: rays from inside the closed mesh leaked" % backend
    assert (got["geometry_ids"][got["t_hit"] < np.inf] <= 1).all()
    # A second query reuses the device's state: the same bits again.
    util.assert_same_hits(s.cast_rays(rays, backend=backend), want, backend + " again")
