# SPDX-License-Identifier: Apache-2.0
"""What the Python package's tests share: the paths ctest gives (RTCL,
RT_SOURCE_DIR, RT_SHARED_SCENES), meshes with exactly known insides, rays,
files for `rtcl trace` (the C oracle, through the command line) and bitwise
comparison of hit dictionaries."""

import os
import subprocess

import numpy as np
import pytest

SOURCE_DIR = os.environ.get("RT_SOURCE_DIR",
                            os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))
RTCL = os.environ.get("RTCL")
SHARED_SCENES = os.environ.get("RT_SHARED_SCENES", os.path.join(SOURCE_DIR, "..", "shared",
                                                                "scenes"))
HIT_KEYS = ("t_hit", "primitive_ids", "geometry_ids", "instance_ids", "primitive_uvs",
            "primitive_normals")


def shared_scene(rel):
    """The path of a shared scene, or a pytest skip saying it is missing."""
    path = os.path.join(SHARED_SCENES, rel)
    if not os.path.exists(path):
        pytest.skip("shared scene %s not found (RT_SHARED_SCENES=%s)" % (rel, SHARED_SCENES))
    return path


def rtcl_tool():
    if not RTCL or not os.access(RTCL, os.X_OK):
        pytest.skip("the rtcl tool is not known (ctest sets RTCL)")
    return RTCL


def backend_devices(api):
    """None when `rtcl devices --api api` lists a device, else why not."""
    r = subprocess.run([rtcl_tool(), "devices", "--api", api], capture_output=True, text=True)
    if r.returncode == 0:
        return None
    return (r.stdout + r.stderr).strip().splitlines()[0] if (r.stdout + r.stderr).strip() \
        else "rtcl devices --api %s failed" % api


def same_bits(a, b):
    """Whether two arrays are equal bit for bit (float32 compared as bits)."""
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape or a.dtype != b.dtype:
        return False
    if a.dtype.kind == "f":
        return np.array_equal(a.view(np.uint32), b.view(np.uint32))
    return np.array_equal(a, b)


def assert_same_hits(a, b, what):
    """Two cast_rays answers are the same bit for bit, key by key."""
    n = max(1, np.asarray(a["t_hit"]).size)
    for k in HIT_KEYS:
        x, y = np.asarray(a[k]), np.asarray(b[k])
        assert x.shape == y.shape and x.dtype == y.dtype, "%s: %s: %s %s vs %s %s" % (
            what, k, x.shape, x.dtype, y.shape, y.dtype)
        differ = (x.view(np.uint32) != y.view(np.uint32)).reshape(n, -1).any(axis=1)
        assert not differ.any(), "%s: %s differ on %d rays (first %s)" % (
            what, k, int(differ.sum()), np.nonzero(differ)[0][:5])


# ---- meshes -------------------------------------------------------------------

def sphere(n_lat=24, n_lon=48, radius=1.0, noise=0.0, seed=0):
    """A closed UV sphere (poles as single vertices), optionally with radial
    noise: (vertices float32 (V, 3), triangles int32 (F, 3))."""
    rng = np.random.default_rng(seed)
    verts = [(0.0, 0.0, radius)]
    for i in range(1, n_lat):
        th = np.pi * i / n_lat
        for j in range(n_lon):
            ph = 2 * np.pi * j / n_lon
            verts.append((radius * np.sin(th) * np.cos(ph), radius * np.sin(th) * np.sin(ph),
                          radius * np.cos(th)))
    verts.append((0.0, 0.0, -radius))
    v = np.array(verts)
    if noise:
        v *= 1.0 + noise * rng.standard_normal((len(v), 1))
    tris = []
    for j in range(n_lon):
        tris.append((0, 1 + j, 1 + (j + 1) % n_lon))
    for i in range(n_lat - 2):
        a0, b0 = 1 + i * n_lon, 1 + (i + 1) * n_lon
        for j in range(n_lon):
            j1 = (j + 1) % n_lon
            tris.append((a0 + j, b0 + j, b0 + j1))
            tris.append((a0 + j, b0 + j1, a0 + j1))
    last = len(verts) - 1
    base = 1 + (n_lat - 2) * n_lon
    for j in range(n_lon):
        tris.append((base + j, last, base + (j + 1) % n_lon))
    return v.astype(np.float32), np.array(tris, np.int32)


class Voxels:
    """The closed surface of the filled cells of a g^3 grid (two triangles a
    face): vertex (i, j, k) at offset + scale * (i, j, k). Its inside is
    known exactly: the filled cells."""

    def __init__(self, g=4, seed=7, scale=1.0, offset=0.0, fill=0.55):
        rng = np.random.default_rng(seed)
        self.g, self.scale, self.offset = g, np.float32(scale), np.float32(offset)
        self.full = rng.random((g, g, g)) < fill
        n = g + 1
        ijk = np.stack(np.meshgrid(np.arange(n), np.arange(n), np.arange(n), indexing="ij"),
                       -1).reshape(-1, 3)
        self.vertices = (self.offset + self.scale * ijk.astype(np.float32)).astype(np.float32)
        vid = lambda p: (p[0] * n + p[1]) * n + p[2]
        tris = []
        for x, y, z in zip(*np.nonzero(self.full)):
            for axis in range(3):
                for side in (0, 1):
                    nb = [x, y, z]
                    nb[axis] += 1 if side else -1
                    if self.filled(*nb):
                        continue
                    b, c = (axis + 1) % 3, (axis + 2) % 3
                    q = []
                    for k in range(4):
                        p = [x, y, z]
                        p[axis] += side
                        p[b] += k in (1, 2)
                        p[c] += k >= 2
                        q.append(vid(p))
                    tris += [(q[0], q[1], q[2]), (q[0], q[2], q[3])]
        self.triangles = np.array(tris, np.int64)

    def filled(self, x, y, z):
        g = self.g
        return 0 <= x < g and 0 <= y < g and 0 <= z < g and bool(self.full[x, y, z])

    def inside(self, points):
        """1 inside, 0 outside, -1 on a lattice plane, per point (exact for
        the dyadic points the tests make)."""
        u = (points.astype(np.float64) - float(self.offset)) / float(self.scale)
        f = np.floor(u)
        on_plane = (u == f).any(axis=-1)
        cell = f.astype(np.int64)
        ok = ((cell >= 0) & (cell < self.g)).all(axis=-1)
        c = np.clip(cell, 0, self.g - 1)
        res = np.where(ok, self.full[c[..., 0], c[..., 1], c[..., 2]], False).astype(np.int64)
        return np.where(on_plane, -1, res)

    def exact_rays(self, seed=1, per_target=2):
        """Rays aimed exactly at every vertex and edge midpoint of the
        surface: direction's largest component +-1, the others multiples of
        1/8, origin q - s d for a dyadic s, so the watertight test's shear
        puts the target exactly on the ray. Returns (rays (N, 6) float32,
        inside (N,)) with origins off the lattice planes."""
        rng = np.random.default_rng(seed)
        v, t = self.vertices.astype(np.float64), self.triangles
        targets = np.concatenate([v[t].reshape(-1, 3),
                                  0.5 * (v[t] + v[np.roll(t, -1, axis=1)]).reshape(-1, 3)])
        targets = np.unique(targets, axis=0)
        q = np.repeat(targets, per_target, axis=0)
        d = rng.integers(-7, 8, size=q.shape) / 8.0
        kz = rng.integers(0, 3, size=len(q))
        d[np.arange(len(q)), kz] = rng.choice([-1.0, 1.0], size=len(q))
        s = rng.choice([0.25, 0.375, 0.5, 0.75, 1.25, 2.25], size=(len(q), 1)) * float(self.scale)
        o = q - s * d
        rays = np.concatenate([o, d], axis=1).astype(np.float32)
        assert np.array_equal(rays.astype(np.float64), np.concatenate([o, d], axis=1))
        inside = self.inside(rays[:, :3])
        keep = inside >= 0
        return rays[keep], inside[keep]


def random_rays(n, lo, hi, seed=0, dtype=np.float32):
    """n rays with origins uniform in the box [lo, hi] and directions
    uniform on the sphere."""
    rng = np.random.default_rng(seed)
    o = rng.uniform(lo, hi, size=(n, 3))
    d = rng.standard_normal((n, 3))
    return np.concatenate([o, d], axis=1).astype(dtype)


def camera_rays(eye, look_at, width, height, hfov=60.0):
    """Pinhole camera rays (height, width, 6), up +y (rtcl.pinhole_rays)."""
    import rtcl
    return rtcl.pinhole_rays(eye, look_at, width, height, hfov)


# ---- the C oracle through rtcl trace ---------------------------------------------

def write_obj(path, vertices, triangles):
    with open(path, "w") as f:
        f.write("".join("v %.9g %.9g %.9g\n" % tuple(p) for p in vertices.astype(np.float32)))
        f.write("".join("f %d %d %d\n" % tuple(t + 1) for t in np.asarray(triangles)))


def write_rays(path, rays, tmin=0.0, tmax=np.inf):
    """A rays file of float32 rays (exactly: %.9g round-trips float32)."""
    r = np.asarray(rays, np.float32).reshape(-1, 6)
    ends = np.broadcast_to(np.array([tmin, tmax], np.float32), (len(r), 2))
    rows = np.concatenate([r, ends], axis=1)
    with open(path, "w") as f:
        f.write("".join(" ".join("%.9g" % x for x in row) + "\n" for row in rows))


def oracle_trace(scene_path, rays_path, out_path, *extra):
    """`rtcl trace --backend cpu`: (hit bool, t, u, v float32, prim, inst uint32)."""
    cmd = [rtcl_tool(), "trace", scene_path, "--rays", rays_path, "--out", out_path,
           "--backend", "cpu"] + list(extra)
    r = subprocess.run(cmd, capture_output=True, text=True)
    assert r.returncode == 0, "%s: %s" % (" ".join(cmd), r.stderr)
    rows = [line.split() for line in open(out_path)]
    hit = np.array([row[0] == "1" for row in rows])
    t, u, v = (np.array([np.float32(row[k]) for row in rows], np.float32) for k in (1, 2, 3))
    prim = np.array([int(row[4]) for row in rows]).astype(np.uint32)
    inst = np.array([int(row[5]) if len(row) > 5 else (0 if row[0] == "1" else -1)
                     for row in rows]).astype(np.uint32)
    return hit, t, u, v, prim, inst


def assert_matches_oracle(hits, oracle, what):
    hit, t, u, v, prim, inst = oracle
    got_hit = hits["t_hit"].reshape(-1) < np.inf
    assert np.array_equal(got_hit, hit), "%s: hit flags differ on %d rays" % (
        what, int((got_hit != hit).sum()))
    assert same_bits(hits["t_hit"].reshape(-1), t), "%s: t differs" % what
    uv = hits["primitive_uvs"].reshape(-1, 2)
    assert same_bits(uv[:, 0], u) and same_bits(uv[:, 1], v), "%s: u, v differ" % what
    assert np.array_equal(hits["primitive_ids"].reshape(-1), prim), "%s: prim differs" % what
    assert np.array_equal(hits["instance_ids"].reshape(-1), inst), "%s: inst differs" % what
