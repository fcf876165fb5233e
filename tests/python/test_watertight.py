# SPDX-License-Identifier: Apache-2.0
"""Watertightness and exact inside/outside: closed meshes whose inside is
known exactly (the surface of random voxels, on the integer lattice and on a
shifted, scaled one; a closed sphere against exact rational half-space tests
of its faces' planes, where it is convex), rays aimed exactly at their shared
vertices and edges (the largest direction component +-1 and the others
multiples of 1/8, so the watertight test's shear puts the target exactly on
the ray) and random points. A ray from inside never misses on any backend;
crossing parity is the exact inside on every ray; counts and hits are the
same after refit, LBVH and SAH rebuilds."""

from fractions import Fraction

import numpy as np
import pytest

import rtcl
import util

VOXELS = [util.Voxels(4, seed=7), util.Voxels(5, seed=11, scale=0.125, offset=96.0),
          util.Voxels(4, seed=3, scale=1024.0, offset=-3072.0)]


def voxel_scene(v, accel="bvh"):
    s = rtcl.Scene()
    s.add_mesh(v.vertices, v.triangles, accel=accel)
    return s


@pytest.mark.parametrize("v", VOXELS, ids=["lattice", "shifted", "large"])
def test_rays_through_vertices_and_edges(v):
    rays, inside = v.exact_rays(seed=5, per_target=8)
    assert len(rays) > 3000 and inside.sum() > 500
    for accel in rtcl.ACCELS:
        s = voxel_scene(v, accel)
        counts = s.count_intersections(rays)
        wrong = np.nonzero((counts % 2) != inside)[0]
        assert len(wrong) == 0, "%s: %d of %d rays with the wrong parity, e.g. %s: %s" % (
            accel, len(wrong), len(rays), rays[wrong[:3]], counts[wrong[:3]])
        for backend in ("packet", "cpu"):
            hit = s.cast_rays(rays, backend=backend)["t_hit"] < np.inf
            assert hit[inside == 1].all(), "%s/%s: %d rays from inside leaked" % (
                accel, backend, int((~hit[inside == 1]).sum()))
            assert np.array_equal(s.test_occlusion(rays, backend=backend), hit)
            assert hit[counts > 0].all()


@pytest.mark.parametrize("v", VOXELS, ids=["lattice", "shifted", "large"])
def test_random_points(v):
    rng = np.random.default_rng(8)
    n = 30000
    lo = float(v.offset) - 0.5 * float(v.scale)
    span = (v.g + 1) * float(v.scale)
    p = (lo + span * rng.random((n, 3))).astype(np.float32)
    u = (p.astype(np.float64) - float(v.offset)) / float(v.scale)
    clear = (np.abs(u - np.round(u)) > 1e-3).all(axis=1)  # t far from 0 for every crossing
    p = p[clear]
    d = rng.standard_normal(p.shape).astype(np.float32)
    s = voxel_scene(v)
    counts = s.count_intersections(p, d)
    inside = v.inside(p)
    assert (inside >= 0).all()
    assert np.array_equal(counts % 2, inside), "%d wrong" % int(((counts % 2) != inside).sum())
    # Several directions per point agree (a closed mesh: parity is the point's).
    for k in range(3):
        d2 = rng.standard_normal(p.shape).astype(np.float32)
        assert np.array_equal(s.count_intersections(p, d2) % 2, inside)


def exact_inside_convex(vertices, triangles, points):
    """1 where the point is strictly inside every face plane of a closed
    convex mesh (exact rational arithmetic on the float32 values), 0 where
    strictly outside one, -1 where on a plane."""
    v = [[Fraction(float(c)) for c in p] for p in vertices]
    out = []
    centre = [sum(p[k] for p in v) / len(v) for k in range(3)]
    planes = []
    for a, b, c in triangles:
        e1 = [v[b][k] - v[a][k] for k in range(3)]
        e2 = [v[c][k] - v[a][k] for k in range(3)]
        n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
             e1[0] * e2[1] - e1[1] * e2[0]]
        side = sum(n[k] * (centre[k] - v[a][k]) for k in range(3))
        planes.append((n, v[a], 1 if side < 0 else -1))  # sign that means "outside"
    for p in points:
        q = [Fraction(float(c)) for c in p]
        state = 1
        for n, a, out_sign in planes:
            s = sum(n[k] * (q[k] - a[k]) for k in range(3)) * out_sign
            if s > 0:
                state = 0
                break
            if s == 0:
                state = -1
        out.append(state)
    return np.array(out)


def test_convex_sphere_exact_reference():
    # A coarse sphere: its faces' planes bound a convex polyhedron only if it
    # is convex, which a UV sphere with planar-enough quads is; the exact
    # test below checks every point against every plane.
    v, f = util.sphere(6, 12)
    s = rtcl.Scene()
    s.add_mesh(v, f)
    rng = np.random.default_rng(12)
    p = rng.uniform(-1.1, 1.1, size=(1500, 3)).astype(np.float32)
    ref = exact_inside_convex(v, f, p)
    keep = ref >= 0
    d = rng.standard_normal(p.shape).astype(np.float32)
    counts = s.count_intersections(p[keep], d[keep])
    # Points within rounding of a face are rare; the margin test below leaves
    # out any whose crossing t is within 1e-5 of 0.
    h = s.cast_rays(p[keep], d[keep])
    far = ~(np.abs(h["t_hit"]) < 1e-5)
    got, want = (counts % 2)[far], ref[keep][far]
    assert far.sum() > 1400
    assert np.array_equal(got, want), "%d of %d points wrong" % (int((got != want).sum()),
                                                                 int(far.sum()))
    # From inside, a convex mesh is crossed exactly once.
    assert (counts[far][want == 1] == 1).all()


def test_every_update_policy_gives_the_same_bits():
    v0, f = util.sphere(40, 80, noise=0.03, seed=4)
    rays = util.random_rays(20000, -1.6, 1.6, seed=13)
    scenes = {p: rtcl.Scene() for p in rtcl.UPDATE_POLICIES + ("fast", "rebuild")}
    for p, s in scenes.items():
        s.add_mesh(v0, f)
        s.cast_rays(rays[:10])  # the first BVH
    rng = np.random.default_rng(14)
    v = v0.copy()
    for frame in range(3):
        v = (v * (1.0 + 0.05 * rng.standard_normal((len(v), 1)))).astype(np.float32)
        fresh = rtcl.Scene()
        fresh.add_mesh(v, f)
        want = fresh.cast_rays(rays, backend="cpu")
        want_counts = fresh.count_intersections(rays)
        for p, s in scenes.items():
            s.update_vertices(0, v, policy=p)
            for backend in ("packet", "cpu"):
                util.assert_same_hits(s.cast_rays(rays, backend=backend), want,
                                      "frame %d, %s, %s" % (frame, p, backend))
            assert np.array_equal(s.count_intersections(rays), want_counts), (frame, p)


def test_instances_count_and_hit():
    v = VOXELS[0]
    s = rtcl.Scene()
    mesh = s.add_mesh(v.vertices, v.triangles, instance=False)
    turn = np.array([[0, -1, 0, 12], [1, 0, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]], np.float64)
    s.add_instance(mesh)
    s.add_instance(mesh, turn)
    rays, inside = v.exact_rays(seed=6, per_target=8)
    rays = rays.copy()
    rays[:, 3] = np.abs(rays[:, 3])  # towards the second instance, at x 8..12
    one = voxel_scene(v)
    counts, counts_one = s.count_intersections(rays), one.count_intersections(rays)
    assert np.array_equal(counts % 2, counts_one % 2)  # the other instance is closed too
    assert (counts >= counts_one).all() and (counts > counts_one).sum() > 50
    h = s.cast_rays(rays)
    assert set(np.unique(h["instance_ids"][h["t_hit"] < np.inf])) == {0, 1}
    assert (h["geometry_ids"][h["t_hit"] < np.inf] == 0).all()
