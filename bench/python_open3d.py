#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""python_open3d.py - rtcl's Python package beside Open3D's RaycastingScene
(Embree inside) in the same run, on the same numpy arrays: scene build time,
Mrays/s of cast_rays and test_occlusion (Open3D: test_occlusions), and the
rays on which they disagree, classified. A third column, "embree", makes
Open3D's Embree calls through ctypes with a working ray mask
(bench/embree_ctypes.py): Debian 12's python3-open3d 0.16.1 sets every
ray's mask to 0 against Debian's Embree, built with EMBREE_RAY_MASK=ON, and
so misses every ray (its column then times queries that find nothing).

usage: PYTHONPATH=build/python /usr/bin/python3 bench/python_open3d.py
           [--scenes DIR] [--only bunny,sponza,dragon] [--rays N] [--reps K]
           [--exact M] [--threads T] [--backend B] [--json OUT.json] [--quick]

Scenes (from DIR, default ../shared/scenes): the Stanford bunny (69k
triangles), Sponza (66k), the Stanford dragon (871k). Per scene two ray sets
of N rays (default 1M): random (origins uniform in the scene's box, directions
uniform on the sphere) and camera (a pinhole camera, sqrt(N) x sqrt(N)
pixels; Sponza from its interior view in ../shared/scenes/VIEWS.md), and a
third set, vertex: rays from outside the box aimed at random vertices of the
mesh, where several triangles meet (not timed for the report's tables, but
timed the same way; it is where a test that is not watertight leaks). Both
libraries get the same float32 vertices, triangles and rays; the mesh is read
here (fan-triangulated OBJ faces), not by either library's loader.

Build: from an empty scene to the answer of one ray (both libraries build
their structures lazily: Open3D commits its Embree scene at the first query,
rtcl builds its BVH and the packet tracer's wide copies). Each query is run
once untimed, then K times; the median is reported. Timings mean something
only on a quiet machine; the counts below mean something anywhere.

Disagreements with each peer (closest hits, t compared relative to 1e-5):
  peer_miss    rtcl hits, the peer misses (peer_miss_at_edge: rtcl's hit
               within 1e-4 in barycentrics of an edge or vertex)
  rtcl_miss    the peer hits, rtcl misses
  t_differs    both hit, t differs: on the same triangle, or another one
  tie          both hit at the same t on different triangles (coincident or
               shared-edge hits: both are right)
  occlusion    the answers of the occlusion queries differ (occlusion_peer_miss:
               rtcl occluded, the peer not)
For up to M (default 200) rays of each hit/miss class, the exact answer in
rational arithmetic (tests/robust/exact.py, the float32 ray against the
float32 triangle): does the exact ray cross the triangle that one library
reported (_exact_crossing: margin >= 0), and clearly (_clear_crossing: by
more than 2^-16 of the triangle's size, beyond any float test's rounding)?
A clear crossing that a library missed is a leak; a crossing within the
rounding band (a ray grazing a silhouette edge or vertex) may go either way.
For up
to M rays whose t differs on the same triangle: whose t is nearer the exact
one (t_differs_rtcl_nearer_exact of t_differs_checked).
"""
import argparse
import json
import math
import os
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "robust"))

SCENES = {
    "bunny": ("stanford_bunny/stanford-bunny.obj", None),
    "sponza": ("sponza_dabrovic/sponza.obj", ((-14, 3, 0), (10, 5, 0), 75.0)),
    "dragon": ("stanford_dragon/dragon_vrip.obj", None),
}


def read_obj(path):
    """(vertices float32 (V, 3), triangles uint32 (F, 3)); polygons as fans."""
    verts, tris = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                verts.append(line.split()[1:4])
            elif line.startswith("f "):
                idx = [int(t.split("/")[0]) for t in line.split()[1:]]
                idx = [i - 1 if i > 0 else len(verts) + i for i in idx]
                for k in range(1, len(idx) - 1):
                    tris.append((idx[0], idx[k], idx[k + 1]))
    return np.array(verts, np.float32), np.array(tris, np.uint32)


def random_rays(n, lo, hi, seed):
    rng = np.random.default_rng(seed)
    o = rng.uniform(lo, hi, size=(n, 3))
    d = rng.standard_normal((n, 3))
    return np.concatenate([o, d], axis=1).astype(np.float32)


def camera_rays(n, lo, hi, view, rtcl):
    side = max(1, int(math.isqrt(n)))
    if view is None:  # the box's front, from +z, the whole box in a 40 degree view
        c, ext = (lo + hi) / 2, hi - lo
        view = (c + np.array([0, 0, 1.6 * max(ext)]), c, 40.0)
    return rtcl.pinhole_rays(view[0], view[1], side, side, view[2]).reshape(-1, 6)


def vertex_rays(n, verts, tris, seed):
    """Rays from outside the scene's box aimed at random vertices of its
    triangles (where several triangles meet: the leaks of a test that is not
    watertight), from random directions."""
    rng = np.random.default_rng(seed)
    used = np.unique(tris)
    q = verts[rng.choice(used, size=n)].astype(np.float64)
    d = rng.standard_normal((n, 3))
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    reach = 2.0 * float((verts.max(axis=0) - verts.min(axis=0)).max())
    return np.concatenate([q - reach * d, d], axis=1).astype(np.float32)


def timed(fn, reps):
    fn()  # untimed: caches, lazy builds
    times = []
    for _ in range(reps):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return float(np.median(times)), out


def as_numpy(x):
    return x.numpy() if hasattr(x, "numpy") else np.asarray(x)


def classify(rays, tris, verts, ours, theirs, our_occ, their_occ, exact_limit):
    """Counts of the classes in the module docstring, with exact checks."""
    t_r, t_o = ours["t_hit"], as_numpy(theirs["t_hit"])
    hit_r, hit_o = t_r < np.inf, t_o < np.inf
    prim_r, prim_o = ours["primitive_ids"], as_numpy(theirs["primitive_ids"])
    their_occ = as_numpy(their_occ)
    uv_r = ours["primitive_uvs"]
    out = {}
    o_miss = hit_r & ~hit_o
    w = np.minimum(np.minimum(uv_r[:, 0], uv_r[:, 1]), 1 - uv_r[:, 0] - uv_r[:, 1])
    out["peer_miss"] = int(o_miss.sum())
    out["peer_miss_at_edge"] = int((o_miss & (w < 1e-4)).sum())
    out["rtcl_miss"] = int((hit_o & ~hit_r).sum())
    both = hit_r & hit_o
    scale = np.maximum(np.abs(t_r), np.abs(t_o))
    with np.errstate(invalid="ignore"):
        t_diff = both & (np.abs(t_r - t_o) > 1e-5 * scale)
    out["t_differs_same_triangle"] = int((t_diff & (prim_r == prim_o)).sum())
    out["t_differs_other_triangle"] = int((t_diff & (prim_r != prim_o)).sum())
    out["tie_other_triangle"] = int((both & ~t_diff & (prim_r != prim_o)).sum())
    out["occlusion"] = int((our_occ != their_occ).sum())
    out["occlusion_peer_miss"] = int((our_occ & ~their_occ).sum())
    try:
        from exact import BAND, intersect
    except ImportError:
        return out
    for name, mask, prims in (("peer_miss", o_miss, prim_r), ("rtcl_miss", hit_o & ~hit_r,
                                                                prim_o)):
        idx = np.nonzero(mask)[0][:exact_limit]
        crossing = clear = 0
        for i in idx:
            o, d = tuple(float(x) for x in rays[i, :3]), tuple(float(x) for x in rays[i, 3:])
            tri = tuple(tuple(float(x) for x in verts[k]) for k in tris[prims[i]])
            r = intersect(o, d, tri)
            if r is not None and r[0] >= 0 and r[3] >= 0:
                crossing += 1
                clear += r[3] >= BAND * r[4]
        out[name + "_checked"] = len(idx)
        out[name + "_exact_crossing"] = int(crossing)
        out[name + "_clear_crossing"] = int(clear)
    # t differs on one triangle: whose t is nearer the exact one?
    idx = np.nonzero(t_diff & (prim_r == prim_o))[0][:exact_limit]
    nearer, err_r, err_o = 0, 0.0, 0.0
    for i in idx:
        o, d = tuple(float(x) for x in rays[i, :3]), tuple(float(x) for x in rays[i, 3:])
        tri = tuple(tuple(float(x) for x in verts[k]) for k in tris[prim_r[i]])
        r = intersect(o, d, tri)
        if r is not None and r[0] != 0:
            e_r, e_o = abs(float(t_r[i]) - r[0]), abs(float(t_o[i]) - r[0])
            nearer += e_r <= e_o
            err_r, err_o = max(err_r, float(e_r / abs(r[0]))), max(err_o, float(e_o / abs(r[0])))
    out["t_differs_checked"] = len(idx)
    out["t_differs_rtcl_nearer_exact"] = int(nearer)
    out["t_differs_max_rel_error_rtcl"] = "%.2g" % err_r
    out["t_differs_max_rel_error_peer"] = "%.2g" % err_o
    return out


def bench_scene(name, path, view, args, o3d, rtcl, embree_ctypes):
    verts, tris = read_obj(path)
    row = {"scene": name, "triangles": int(len(tris))}
    one = np.array([[0, 0, 0, 1, 0, 0]], np.float32)
    nt = args.threads or 0

    def build_rtcl():
        s = rtcl.Scene()
        s.add_mesh(verts, tris)
        s.cast_rays(one, backend=args.backend, threads=args.threads)
        return s

    def build_o3d():
        s = o3d.t.geometry.RaycastingScene()
        s.add_triangles(o3d.core.Tensor(verts), o3d.core.Tensor(tris))
        s.cast_rays(o3d.core.Tensor(one), nthreads=nt)
        return s

    def build_embree():
        s = embree_ctypes.EmbreeScene(args.threads)
        s.add_triangles(verts, tris)
        s.cast_rays(one)
        return s

    peers = {}
    for peer, build in (("rtcl", build_rtcl), ("open3d", build_o3d), ("embree", build_embree)):
        t0 = time.perf_counter()
        peers[peer] = build()
        row["build_ms_" + peer] = 1e3 * (time.perf_counter() - t0)
    lo, hi = verts.min(axis=0).astype(float), verts.max(axis=0).astype(float)
    row["sets"] = []
    for set_name, rays in (("random", random_rays(args.rays, lo, hi, 1)),
                           ("camera", camera_rays(args.rays, lo, hi, view, rtcl)),
                           ("vertex", vertex_rays(args.rays, verts, tris, 2))):
        tr = o3d.core.Tensor(rays)
        n = len(rays)
        kw = dict(backend=args.backend, threads=args.threads)
        ours, o3, em = peers["rtcl"], peers["open3d"], peers["embree"]
        queries = {
            "rtcl": (lambda: ours.cast_rays(rays, **kw), lambda: ours.test_occlusion(rays, **kw)),
            "open3d": (lambda: o3.cast_rays(tr, nthreads=nt),
                       lambda: o3.test_occlusions(tr, nthreads=nt)),
            "embree": (lambda: em.cast_rays(rays), lambda: em.test_occlusion(rays)),
        }
        r = {"rays": set_name, "n": n}
        answers = {}
        for peer, (cast, occ) in queries.items():
            s_cast, hits = timed(cast, args.reps)
            s_occ, occluded = timed(occ, args.reps)
            r["cast_mrays_" + peer] = n / s_cast / 1e6
            r["occlusion_mrays_" + peer] = n / s_occ / 1e6
            r["hits_" + peer] = int((as_numpy(hits["t_hit"]) < np.inf).sum())
            answers[peer] = (hits, occluded)
        for peer in ("open3d", "embree"):
            r["vs_" + peer] = classify(rays, tris, verts, answers["rtcl"][0], answers[peer][0],
                                       answers["rtcl"][1], answers[peer][1], args.exact)
        row["sets"].append(r)
        print_set(name, row, r)
    peers["embree"].close()
    return row


def print_set(scene, row, r):
    print("%-7s %-7s %8d rays, hits: rtcl %d, open3d %d, embree %d"
          % (scene, r["rays"], r["n"], r["hits_rtcl"], r["hits_open3d"], r["hits_embree"]))
    for what in ("build_ms", "cast_mrays", "occlusion_mrays"):
        src = row if what == "build_ms" else r
        print("        %-16s rtcl %9.2f  open3d %9.2f  embree %9.2f"
              % (what.replace("_", " "), src[what + "_rtcl"], src[what + "_open3d"],
                 src[what + "_embree"]))
    for peer in ("open3d", "embree"):
        d = r["vs_" + peer]
        print("        vs %-7s %s" % (peer, ", ".join("%s %s" % (k, v) for k, v in d.items())))
    sys.stdout.flush()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scenes", default=os.path.join(HERE, "..", "..", "shared", "scenes"))
    ap.add_argument("--only", default="bunny,sponza,dragon")
    ap.add_argument("--rays", type=int, default=1000000)
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--exact", type=int, default=200)
    ap.add_argument("--threads", type=int, default=None)
    ap.add_argument("--backend", default="packet")
    ap.add_argument("--json")
    ap.add_argument("--quick", action="store_true", help="20000 rays, 1 rep (checks, not timing)")
    args = ap.parse_args()
    if args.quick:
        args.rays, args.reps = 20000, 1
    try:
        import open3d as o3d
    except ImportError:
        sys.exit("python_open3d.py: open3d is not installed (Debian: python3-open3d)")
    import rtcl
    sys.path.insert(0, HERE)
    import embree_ctypes
    print("rtcl %s (backend %s) beside Open3D %s and Embree through ctypes; threads %s"
          % (rtcl.__version__, args.backend, o3d.__version__, args.threads or "all"))
    rows = []
    for name in args.only.split(","):
        rel, view = SCENES[name]
        path = os.path.join(args.scenes, rel)
        if not os.path.exists(path):
            print("%s: %s not found: skipped" % (name, path))
            continue
        rows.append(bench_scene(name, path, view, args, o3d, rtcl, embree_ctypes))
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"rtcl": rtcl.__version__, "open3d": o3d.__version__, "rays": args.rays,
                       "reps": args.reps, "backend": args.backend, "threads": args.threads,
                       "scenes": rows}, f, indent=1)


if __name__ == "__main__":
    main()
