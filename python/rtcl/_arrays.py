# SPDX-License-Identifier: Apache-2.0
"""Checks and conversions of the caller's arguments into what the extension
module reads: C-contiguous float32 and uint32 arrays. An array that already
is one is passed on as it is (no copy); any other real array is converted
once. Every refusal is a TypeError (wrong kind of thing) or a ValueError
(wrong shape or value) that names the argument."""

import math
import numbers

import numpy as np

BACKENDS = ("packet", "cpu", "opencl", "vulkan", "auto")
DEVICE_BACKENDS = ("opencl", "vulkan", "auto")
MAX_THREADS = 1024


def real_array(name, value):
    """value as a numpy array of real numbers (integers or floats, not bool,
    complex, strings or objects)."""
    try:
        a = np.asarray(value)
    except (ValueError, TypeError) as e:  # ragged nested lists
        raise TypeError("%s: not an array of numbers (%s)" % (name, e)) from None
    if a.dtype.kind not in "iuf":
        raise TypeError("%s: an array of real numbers was expected, got dtype %s" % (name, a.dtype))
    return a


def as_float32(a):
    """a as a C-contiguous float32 array: a itself when it is one. Values
    beyond float32's range become +-inf (no warning: the caller checks)."""
    if a.dtype == np.float32 and a.flags.c_contiguous:
        return a
    with np.errstate(over="ignore", invalid="ignore"):
        return np.ascontiguousarray(a, dtype=np.float32)


def check_shape(name, a, tail, what):
    if a.ndim != len(tail) + 1 or tuple(a.shape[1:]) != tail:
        raise ValueError("%s: shape (%s) expected (%s), got %s"
                         % (name, ", ".join(["N"] + [str(t) for t in tail]), what, a.shape))


def vertices(name, value):
    """(V, 3) real -> (V, 3) float32, every coordinate finite."""
    a = real_array(name, value)
    check_shape(name, a, (3,), "x, y, z per vertex")
    if a.shape[0] == 0:
        raise ValueError("%s: a mesh needs at least one vertex" % name)
    v = as_float32(a)
    finite = np.isfinite(v).all(axis=1)
    if not finite.all():
        i = int(np.argmin(finite))
        beyond = bool(np.isfinite(a[i]).all())
        raise ValueError("%s: vertex %d has a %s coordinate (%s)"
                         % (name, i, "float32-overflowing" if beyond else "NaN or infinite",
                            ", ".join(repr(float(x)) for x in a[i])))
    return v


def triangles(name, value, vertex_count):
    """(F, 3) integers in [0, vertex_count) -> (F, 3) uint32."""
    try:
        a = np.asarray(value)
    except (ValueError, TypeError) as e:
        raise TypeError("%s: not an array of integers (%s)" % (name, e)) from None
    if a.dtype.kind not in "iu":
        raise TypeError("%s: integer vertex indices were expected, got dtype %s" % (name, a.dtype))
    check_shape(name, a, (3,), "three vertex indices per triangle")
    if a.shape[0] == 0:
        raise ValueError("%s: a mesh needs at least one triangle" % name)
    low, high = a.min(), a.max()
    if low < 0:
        i = int(np.argmin(a.min(axis=1)))
        raise ValueError("%s: triangle %d has the negative index %d" % (name, i, int(low)))
    if high >= vertex_count:
        i = int(np.argmax(a.max(axis=1)))
        raise ValueError("%s: triangle %d refers to vertex %d, but there are %d vertices"
                         % (name, i, int(high), vertex_count))
    if a.dtype == np.uint32 and a.flags.c_contiguous:
        return a
    return np.ascontiguousarray(a, dtype=np.uint32)


def transform(name, value):
    """(4, 4) real -> 16 float32, finite (the library checks the last row
    and that the matrix is invertible)."""
    a = real_array(name, value)
    if a.shape != (4, 4):
        raise ValueError("%s: a 4x4 matrix was expected, got shape %s" % (name, a.shape))
    m = as_float32(a)
    if not np.isfinite(m).all():
        raise ValueError("%s: every element must be a finite float32 number" % name)
    return m


def identifier(name, value):
    """An id: a Python or numpy integer, 0 .. 2^32 - 1."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError("%s: an integer id was expected, got %s" % (name, type(value).__name__))
    if not 0 <= int(value) <= 0xFFFFFFFF:
        raise ValueError("%s %d does not exist" % (name, int(value)))
    return int(value)


def threads(value):
    """None (every core) or 1 .. MAX_THREADS -> the renderer's count (0: every core)."""
    if value is None:
        return 0
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError("threads: an integer or None was expected, got %s" % type(value).__name__)
    if not 1 <= int(value) <= MAX_THREADS:
        raise ValueError("threads: 1 to %d, or None for every core; got %d"
                         % (MAX_THREADS, int(value)))
    return int(value)


def backend(value):
    if not isinstance(value, str):
        raise TypeError("backend: a name was expected, got %s" % type(value).__name__)
    name, colon, device = value.partition(":")
    if name not in BACKENDS:
        raise ValueError("backend: unknown backend %r (%s; opencl:DEVICE or vulkan:DEVICE for a "
                         "device by index or name)" % (value, ", ".join(BACKENDS)))
    if colon and (name not in DEVICE_BACKENDS or not device):
        raise ValueError("backend: %r: only opencl, vulkan and auto take a device (NAME:DEVICE)"
                         % value)
    return value


class Rays:
    """The rays of a query as the extension reads them: n rays of the
    leading shape, origins and directions as (array, offset, step) in
    float32 numbers, the ends as float32 arrays of 1 or n numbers."""

    def __init__(self, rays, directions, tmin, tmax):
        if directions is None:
            r = real_array("rays", rays)
            if r.ndim < 1 or r.shape[-1] != 6:
                raise ValueError("rays: shape (..., 6) expected (ox, oy, oz, dx, dy, dz per ray; "
                                 "or origins (..., 3) and directions (..., 3)), got %s"
                                 % (r.shape,))
            r = as_float32(r)
            self.shape = r.shape[:-1]
            self.org = (r, 0, 6)
            self.dir = (r, 3, 6)
        else:
            o = real_array("origins", rays)
            d = real_array("directions", directions)
            if d.ndim < 1 or d.shape[-1] != 3:
                raise ValueError("directions: shape (..., 3) expected, got %s" % (d.shape,))
            if o.shape != d.shape and o.shape != (3,):
                raise ValueError("origins: shape %s does not match the directions' %s (or (3,) "
                                 "for one origin of every ray)" % (o.shape, d.shape))
            d = as_float32(d)
            o = as_float32(o)
            self.shape = d.shape[:-1]
            self.org = (o, 0, 0 if o.shape == (3,) and d.shape != (3,) else 3)
            self.dir = (d, 0, 3)
        self.n = math.prod(self.shape)
        self.tmin = _range_end("tmin", tmin, self.shape)
        self.tmax = _range_end("tmax", tmax, self.shape)

    def args(self):
        """The ray arguments of the extension's query, after kind."""
        org, oo, os_ = self.org
        dir_, do, ds = self.dir
        return (self.n, org, oo, os_, dir_, do, ds, self.tmin, self.tmax)


def _range_end(name, value, shape):
    """A scalar (not NaN) or an array of one end per ray (a NaN there makes
    that ray miss, as a NaN in the ray does)."""
    a = real_array(name, value)
    if a.ndim == 0:
        if np.isnan(a):
            raise ValueError("%s must not be NaN" % name)
        return as_float32(a.reshape(1))
    try:
        b = np.broadcast_to(a, shape)
    except ValueError:
        raise ValueError("%s: shape %s does not broadcast to the rays' %s"
                         % (name, a.shape, shape)) from None
    return as_float32(b).reshape(-1)
