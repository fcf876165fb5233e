# SPDX-License-Identifier: Apache-2.0
"""exact.py - exact rational arithmetic on float32 inputs for the robustness
suite (tests/robust). Every float32 is a dyadic rational, so Fraction gives
the exact answer of a ray/triangle query; no rounding anywhere below except
where a function says it rounds to float32.
"""
import struct
from fractions import Fraction as Fr

# A miss that passes closer than BAND * S to a triangle (S: the largest
# coordinate of the triangle relative to the ray origin), and a hit that
# lands closer than that to an open edge, are "either": float tests have
# rounding errors of a few ulps of S (2^-24 S each); 2^-16 S is 256 ulps.
BAND = Fr(1, 2**16)
# Hits whose exact t are within this relative distance of the nearest one
# may come out in either order after rounding (the allowed primitives).
T_WINDOW = Fr(1, 2**16)


def f32(x):
    """x (a float or Fraction) rounded to float32, as a Python float."""
    return struct.unpack('<f', struct.pack('<f', float(x)))[0]


def is_f32(q):
    """Is the rational q exactly a float32?"""
    try:
        return Fr(f32(q)) == q
    except OverflowError:
        return False


def f32_next(x, up=True):
    """The float32 next to x (towards +inf when up)."""
    i = struct.unpack('<i', struct.pack('<f', x))[0]
    if x == 0.0:
        return struct.unpack('<f', struct.pack('<i', 1 if up else -2147483647))[0]
    i += 1 if (x > 0) == up else -1
    return struct.unpack('<f', struct.pack('<i', i))[0]


def fmt(x):
    """A float32 as text that strtof reads back to the same bits."""
    return '%.9g' % x


def frs(q):
    """A Fraction as 'p/q' text."""
    return '%d/%d' % (q.numerator, q.denominator)


def vec(p):
    return tuple(Fr(c) for c in p)


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def area_zero(tri):
    v0, v1, v2 = (vec(p) for p in tri)
    return cross(sub(v1, v0), sub(v2, v0)) == (0, 0, 0)


def _ray_space(o, d, tri, num):
    """Edge functions U, V, W and per-vertex depths in the ray's frame (the
    watertight test's shear, here exact when num is Fraction)."""
    kz = max(range(3), key=lambda k: abs(d[k]))
    kx, ky = (kz + 1) % 3, (kz + 2) % 3
    sx, sy, sz = num(d[kx]) / num(d[kz]), num(d[ky]) / num(d[kz]), 1 / num(d[kz])
    pts, scale = [], 0
    for p in tri:
        a = [num(p[k]) - num(o[k]) for k in range(3)]
        scale = max(scale, abs(a[0]), abs(a[1]), abs(a[2]))
        pts.append((a[kx] - sx * a[kz], a[ky] - sy * a[kz], sz * a[kz]))
    (ax, ay, az), (bx, by, bz), (cx, cy, cz) = pts
    U = cx * by - cy * bx
    V = ax * cy - ay * cx
    W = bx * ay - by * ax
    edges = ((cx - bx, cy - by), (ax - cx, ay - cy), (bx - ax, by - ay))
    return U, V, W, (az, bz, cz), edges, scale


def intersect(o, d, tri):
    """The exact crossing of the line o + t d with the triangle's plane:
    (t, u, v, margin, scale) or None when the ray is parallel to the plane or
    the triangle has no area. margin is the signed distance (in the plane
    perpendicular to the ray, edges measured in the 1-norm, so it is never
    overstated) from the ray to the nearest edge: >= 0 inside, < 0 outside.
    A double-precision pass first skips triangles the ray clearly misses."""
    U, V, W, _, edges, scale = _ray_space(o, d, tri, float)
    det = U + V + W
    if det != 0.0 and scale > 0.0:
        s = 1.0 if det > 0 else -1.0
        for E, (ex, ey) in zip((U, V, W), edges):
            n1 = abs(ex) + abs(ey)
            if n1 > 0 and s * E / n1 < -1e-6 * scale:
                return None
    U, V, W, (az, bz, cz), edges, scale = _ray_space(o, d, tri, Fr)
    det = U + V + W
    if det == 0:
        return None
    s = 1 if det > 0 else -1
    margin = None
    for E, (ex, ey) in zip((U, V, W), edges):
        n1 = abs(ex) + abs(ey)
        m = s * E / n1 if n1 else Fr(0)
        margin = m if margin is None or m < margin else margin
    t = (U * az + V * bz + W * cz) / det
    return t, V / det, W / det, margin, scale


def expect_ray(o, d, tmin, tmax, tris, covered=False, exact_ends=False, any_hit=False,
               skip_self=None):
    """The expectation of one ray against a triangle list (float32 coordinates):
    {'hit': 'must'|'miss'|'either', 'prims': {index: [t, u, v]}} with exact
    t, u, v of each primitive that may be reported. covered: the ray crosses
    a closed surface, so a hit exactly on a shared edge or vertex is required
    (a leak otherwise). exact_ends: the geometry makes every test compute t
    exactly, so t equal to tmin or tmax decides. skip_self: t at or below this
    is the surface the origin lies on (offset rays), never a valid hit."""
    tmin_q = Fr(tmin) if tmin != -float('inf') else None
    tmax_q = Fr(tmax) if tmax != float('inf') else None
    cands = []
    seen = {}
    for i, tri in enumerate(tris):
        key = tuple(tuple(p) for p in tri)
        if key in seen:  # an identical copy computes the same t: the tie rule
            continue     # (lower index) picks the first one
        seen[key] = i
        r = intersect(o, d, tri)
        if r is None:
            continue
        t, u, v, margin, scale = r
        if skip_self is not None and t <= skip_self:
            continue
        band = BAND * scale
        in_range = (tmin_q is None or t >= tmin_q) and (tmax_q is None or t <= tmax_q)
        near_end = not exact_ends and any(e is not None and abs(t - e) <= T_WINDOW * abs(t)
                                          for e in (tmin_q, tmax_q))
        exact_hit = margin >= 0 and in_range
        strong = in_range and not near_end and (margin >= band or (covered and margin >= 0))
        possible = margin > -band and (in_range or near_end)
        if possible:
            cands.append((t, i, u, v, strong, exact_hit))
    if not cands:
        return {'hit': 'miss', 'prims': {}}
    hit = 'must' if any(c[4] for c in cands) else 'either'
    if any_hit:
        allowed = cands
    else:
        exact = [c[0] for c in cands if c[5]]
        limit = min(exact) if exact else max(c[0] for c in cands)
        limit += T_WINDOW * abs(limit)
        allowed = [c for c in cands if c[0] <= limit]
    return {'hit': hit, 'prims': {str(c[1]): [frs(c[0]), frs(c[2]), frs(c[3])] for c in allowed}}
