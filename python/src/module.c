/* SPDX-License-Identifier: Apache-2.0 */
/* module.c - rtcl._rtcl, the extension module under the Python package rtcl
 * (python/rtcl/): one type, Scene, that owns an rt_scene and the renderers
 * that query it. rtcl/__init__.py checks and converts the caller's arrays;
 * this module checks again what it reads (format, item size, length), so
 * that no array reaches the library wrongly sized, whoever calls it.
 *
 * Threads: every library call runs with the GIL released and the scene's
 * lock held (taken with the GIL released, so that a thread waiting for the
 * lock never holds the GIL the tracing thread needs to return). */
#include "rtcl_py.h" /* Python.h first, as Python asks */

#include <string.h>

typedef struct renderer_slot {
    int threads; /* as asked: 0 is every core */
    rt_renderer *renderer;
    char backend[64]; /* the backend last asked for ("auto" stays "auto") */
} renderer_slot;

/* Renderers kept per scene, one per thread count asked for (each keeps its
 * own BVHs); a fifth thread count replaces the oldest. */
enum { RENDERERS = 4 };

typedef struct SceneObject {
    PyObject_HEAD rt_scene *scene;
    PyThread_type_lock lock;
    uint32_t material; /* the material of instances made here, UINT32_MAX before the first */
    renderer_slot renderers[RENDERERS];
    int renderer_count, renderer_next;
    char last_backend[32];
} SceneObject;

/* The outcome of library calls made without the GIL, raised once it is back. */
typedef struct call_result {
    rt_status status;
    char message[1200];
} call_result;

static void result_set(call_result *res, rt_status st, const char *message) {
    res->status = st;
    snprintf(res->message, sizeof res->message, "%s",
             message && message[0] ? message : rt_status_string(st));
}

/* Raises the exception that fits a library status; returns NULL. */
static PyObject *raise_result(const call_result *res) {
    PyObject *type = PyExc_RuntimeError;
    switch (res->status) {
    case RT_ERROR_INVALID_ARGUMENT:
    case RT_ERROR_PARSE:
        type = PyExc_ValueError;
        break;
    case RT_ERROR_IO:
        type = PyExc_OSError;
        break;
    case RT_ERROR_OUT_OF_MEMORY:
        type = PyExc_MemoryError;
        break;
    default:
        break;
    }
    PyErr_SetString(type, res->message);
    return NULL;
}

#define LOCKED_BEGIN(self) Py_BEGIN_ALLOW_THREADS PyThread_acquire_lock((self)->lock, WAIT_LOCK);
#define LOCKED_END(self)                                                                           \
    PyThread_release_lock((self)->lock);                                                           \
    Py_END_ALLOW_THREADS

/* ---- arguments ------------------------------------------------------------ */

/* A C-contiguous buffer of native items of the given size whose format is
 * one of the letters in codes ("f": float32; "IL": uint32; ...). */
static int get_array(PyObject *obj, Py_buffer *view, const char *name, const char *codes,
                     Py_ssize_t itemsize, int writable) {
    int flags = PyBUF_C_CONTIGUOUS | PyBUF_FORMAT | (writable ? PyBUF_WRITABLE : 0);
    if (PyObject_GetBuffer(obj, view, flags) < 0) {
        PyErr_Clear();
        PyErr_Format(PyExc_TypeError, "%s: expected a C-contiguous%s array, got %.80s", name,
                     writable ? " writable" : "", Py_TYPE(obj)->tp_name);
        return 0;
    }
    const char *f = view->format ? view->format : "B";
    if (*f == '@' || *f == '=' || *f == '<') f++; /* native, little-endian (x86-64, aarch64) */
    if (view->itemsize != itemsize || strlen(f) != 1 || !strchr(codes, *f)) {
        PyErr_Format(PyExc_TypeError,
                     "%s: items of format '%.8s' and size %zd where '%c' of %zd "
                     "bytes was expected",
                     name, view->format ? view->format : "B", view->itemsize, codes[0], itemsize);
        PyBuffer_Release(view);
        return 0;
    }
    return 1;
}

/* An id: a Python int (or anything with __index__) in 0 .. UINT32_MAX. */
static int get_id(PyObject *obj, const char *name, uint32_t *out) {
    PyObject *index = PyNumber_Index(obj);
    if (!index) {
        PyErr_Clear();
        PyErr_Format(PyExc_TypeError, "%s must be an integer, got %.80s", name,
                     Py_TYPE(obj)->tp_name);
        return 0;
    }
    int overflow = 0;
    long long v = PyLong_AsLongLongAndOverflow(index, &overflow);
    Py_DECREF(index);
    if (overflow || v < 0 || v > (long long)UINT32_MAX) {
        PyErr_Format(PyExc_ValueError, "%s %R does not exist", name, obj);
        return 0;
    }
    *out = (uint32_t)v;
    return 1;
}

/* ---- the Scene type --------------------------------------------------------- */

static PyObject *scene_wrap(PyTypeObject *type, rt_scene *scene) {
    SceneObject *self = (SceneObject *)type->tp_alloc(type, 0);
    if (!self) {
        rt_scene_destroy(scene);
        return NULL;
    }
    self->scene = scene;
    self->material = UINT32_MAX;
    self->lock = PyThread_allocate_lock();
    if (!self->lock) {
        Py_DECREF(self);
        return PyErr_NoMemory();
    }
    return (PyObject *)self;
}

static PyObject *scene_new(PyTypeObject *type, PyObject *args, PyObject *kwargs) {
    static char *names[] = {NULL};
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, ":Scene", names)) return NULL;
    rt_scene *scene = NULL;
    if (rt_scene_create(&scene) != RT_OK) return PyErr_NoMemory();
    return scene_wrap(type, scene);
}

static void scene_dealloc(SceneObject *self) {
    for (int i = 0; i < self->renderer_count; i++) rt_renderer_destroy(self->renderers[i].renderer);
    rt_scene_destroy(self->scene);
    if (self->lock) PyThread_free_lock(self->lock);
    Py_TYPE(self)->tp_free((PyObject *)self);
}

static PyTypeObject SceneType;

static PyObject *scene_load(PyObject *module, PyObject *args) {
    (void)module;
    PyObject *path_obj = NULL;
    if (!PyArg_ParseTuple(args, "O&:load", PyUnicode_FSConverter, &path_obj)) return NULL;
    const char *path = PyBytes_AS_STRING(path_obj);
    rt_scene *scene = NULL;
    rt_error err;
    memset(&err, 0, sizeof err);
    rt_status st;
    Py_BEGIN_ALLOW_THREADS st = rt_scene_load(path, &scene, &err);
    Py_END_ALLOW_THREADS Py_DECREF(path_obj);
    if (st != RT_OK) {
        call_result res;
        result_set(&res, st, err.message);
        return raise_result(&res);
    }
    return scene_wrap(&SceneType, scene);
}

/* add_mesh(vertices float32 (3V), triangles uint32 (3F), accel) -> mesh id */
static PyObject *scene_add_mesh(SceneObject *self, PyObject *args) {
    PyObject *vobj, *tobj;
    const char *accel_name;
    if (!PyArg_ParseTuple(args, "OOs:add_mesh", &vobj, &tobj, &accel_name)) return NULL;
    rt_accel accel;
    if (!rt_accel_parse(accel_name, &accel))
        return PyErr_Format(PyExc_ValueError,
                            "accel: unknown structure '%s' (bvh, kd or kd-binned)", accel_name);
    Py_buffer v, t;
    if (!get_array(vobj, &v, "vertices", "f", 4, 0)) return NULL;
    if (!get_array(tobj, &t, "triangles", "IL", 4, 0)) {
        PyBuffer_Release(&v);
        return NULL;
    }
    const Py_ssize_t nv = v.len / 12, nt = t.len / 12;
    PyObject *ret = NULL;
    if (v.len % 12 || t.len % 12) {
        PyErr_SetString(PyExc_ValueError, "vertices and triangles: 3 numbers per row");
    } else if ((unsigned long long)nv > UINT32_MAX || (unsigned long long)nt > UINT32_MAX) {
        PyErr_SetString(PyExc_ValueError, "a mesh holds fewer than 2^32 vertices and triangles");
    } else {
        call_result res = {RT_OK, ""};
        uint32_t mesh = 0;
        LOCKED_BEGIN(self)
        rt_status st = rt_mesh_create(self->scene, &mesh);
        if (st == RT_OK)
            st = rt_mesh_add_triangles(self->scene, mesh, v.buf, NULL, (uint32_t)nv, t.buf,
                                       (uint32_t)nt);
        if (st == RT_OK) st = rt_mesh_set_accel(self->scene, mesh, accel);
        if (st != RT_OK) result_set(&res, st, rt_scene_error(self->scene));
        LOCKED_END(self)
        ret = res.status == RT_OK ? PyLong_FromUnsignedLong(mesh) : raise_result(&res);
    }
    PyBuffer_Release(&v);
    PyBuffer_Release(&t);
    return ret;
}

/* Whether the library takes matrix as an object's transform, tried on a
 * scene of its own so that a refused matrix leaves the caller's scene as it
 * was; on failure res says why. No GIL needed. */
static void check_transform(const float *matrix, call_result *res) {
    rt_scene *s = NULL;
    uint32_t material = 0, object = 0;
    rt_material mat = rt_material_default();
    rt_status st = rt_scene_create(&s);
    if (st == RT_OK) st = rt_material_add(s, &mat, &material);
    if (st == RT_OK) st = rt_object_create(s, material, &object);
    if (st == RT_OK) st = rt_object_transform(s, object, matrix);
    if (st != RT_OK) {
        /* "object 0: the transform is singular" names the scratch object. */
        const char *why = s ? rt_scene_error(s) : "";
        const char *colon = strstr(why, ": ");
        char text[600];
        snprintf(text, sizeof text, "transform: %s", colon ? colon + 2 : why);
        result_set(res, st, text);
    }
    rt_scene_destroy(s);
}

/* add_instance(mesh, matrix float32 (16) or None) -> instance id */
static PyObject *scene_add_instance(SceneObject *self, PyObject *args) {
    PyObject *mesh_obj, *mobj;
    if (!PyArg_ParseTuple(args, "OO:add_instance", &mesh_obj, &mobj)) return NULL;
    uint32_t mesh;
    if (!get_id(mesh_obj, "mesh", &mesh)) return NULL;
    Py_buffer m;
    const int have_matrix = mobj != Py_None;
    if (have_matrix) {
        if (!get_array(mobj, &m, "transform", "f", 4, 0)) return NULL;
        if (m.len != 16 * 4) {
            PyBuffer_Release(&m);
            return PyErr_Format(PyExc_ValueError, "transform: 16 numbers (4x4), got %zd",
                                m.len / 4);
        }
    }
    call_result res = {RT_OK, ""};
    uint32_t object = 0;
    LOCKED_BEGIN(self)
    /* Everything is checked before the object is made: a failed call adds
     * nothing. */
    if (mesh >= rt_scene_mesh_count(self->scene)) {
        char text[160];
        snprintf(text, sizeof text, "mesh %u does not exist (the scene has %u)", mesh,
                 rt_scene_mesh_count(self->scene));
        result_set(&res, RT_ERROR_INVALID_ARGUMENT, text);
    } else if (have_matrix) {
        check_transform(m.buf, &res);
    }
    rt_status st = res.status;
    if (st == RT_OK && self->material == UINT32_MAX) {
        rt_material mat = rt_material_default();
        st = rt_material_add(self->scene, &mat, &self->material);
    }
    if (st == RT_OK) st = rt_object_create(self->scene, self->material, &object);
    if (st == RT_OK) st = rt_object_add_mesh(self->scene, object, mesh);
    if (st == RT_OK && have_matrix) st = rt_object_transform(self->scene, object, m.buf);
    if (st != RT_OK && res.status == RT_OK) result_set(&res, st, rt_scene_error(self->scene));
    LOCKED_END(self)
    if (have_matrix) PyBuffer_Release(&m);
    return res.status == RT_OK ? PyLong_FromUnsignedLong(object) : raise_result(&res);
}

/* update_vertices(mesh, vertices float32 (3V), policy) */
static PyObject *scene_update_vertices(SceneObject *self, PyObject *args) {
    PyObject *mesh_obj, *vobj;
    const char *policy_name;
    if (!PyArg_ParseTuple(args, "OOs:update_vertices", &mesh_obj, &vobj, &policy_name)) return NULL;
    uint32_t mesh;
    if (!get_id(mesh_obj, "mesh", &mesh)) return NULL;
    rt_update_policy policy;
    if (!rt_update_policy_parse(policy_name, &policy))
        return PyErr_Format(PyExc_ValueError,
                            "policy: unknown update policy '%s' (sah, refit, lbvh or auto)",
                            policy_name);
    Py_buffer v;
    if (!get_array(vobj, &v, "vertices", "f", 4, 0)) return NULL;
    if (v.len % 12 || (unsigned long long)(v.len / 12) > UINT32_MAX) {
        PyBuffer_Release(&v);
        PyErr_SetString(PyExc_ValueError, "vertices: 3 numbers per row");
        return NULL;
    }
    call_result res = {RT_OK, ""};
    LOCKED_BEGIN(self)
    /* The positions first: a refused array leaves the policy as it was. */
    rt_status st = rt_mesh_set_positions(self->scene, mesh, v.buf, NULL, (uint32_t)(v.len / 12));
    if (st == RT_OK) st = rt_mesh_set_update(self->scene, mesh, policy);
    if (st != RT_OK) result_set(&res, st, rt_scene_error(self->scene));
    LOCKED_END(self)
    PyBuffer_Release(&v);
    if (res.status != RT_OK) return raise_result(&res);
    Py_RETURN_NONE;
}

/* The renderer for a thread count, on backend (made, or switched to when
 * the last call asked for another; "": whichever it has, "cpu" for a new
 * one); called with the lock held. NULL with res set on failure. */
static rt_renderer *renderer_for(SceneObject *self, int threads, const char *backend,
                                 call_result *res) {
    for (int i = 0; i < self->renderer_count; i++) {
        renderer_slot *s = &self->renderers[i];
        if (s->threads != threads) continue;
        if (backend[0] && strcmp(s->backend, backend) != 0) {
            rt_status st = rt_renderer_set_backend(s->renderer, backend);
            if (st != RT_OK) {
                result_set(res, st, rt_renderer_error(s->renderer));
                return NULL;
            }
            snprintf(s->backend, sizeof s->backend, "%s", backend);
        }
        return s->renderer;
    }
    rt_renderer_options o = rt_renderer_options_default();
    o.backend = backend[0] ? backend : "cpu";
    o.threads = threads;
    rt_renderer *r = NULL;
    rt_error err;
    memset(&err, 0, sizeof err);
    rt_status st = rt_renderer_create(&o, &r, &err);
    if (st != RT_OK) {
        result_set(res, st, err.message);
        return NULL;
    }
    int slot;
    if (self->renderer_count < RENDERERS) {
        slot = self->renderer_count++;
    } else {
        slot = self->renderer_next;
        self->renderer_next = (slot + 1) % RENDERERS;
        rt_renderer_destroy(self->renderers[slot].renderer);
    }
    renderer_slot *s = &self->renderers[slot];
    s->threads = threads;
    s->renderer = r;
    snprintf(s->backend, sizeof s->backend, "%s", o.backend);
    return r;
}

/* An output array of exactly n items; 0 with an exception otherwise. */
static int get_output(PyObject *obj, Py_buffer *view, const char *name, const char *codes,
                      Py_ssize_t itemsize, Py_ssize_t n) {
    if (!get_array(obj, view, name, codes, itemsize, 1)) return 0;
    if (view->len != n * itemsize) {
        PyErr_Format(PyExc_ValueError, "%s: %zd items where %zd were expected", name,
                     view->len / itemsize, n);
        PyBuffer_Release(view);
        return 0;
    }
    return 1;
}

/* Whether an input of len floats holds n rays' 3 floats from offset with
 * step floats between rays. */
static int covers(Py_ssize_t len_floats, Py_ssize_t n, Py_ssize_t offset, Py_ssize_t step) {
    if (n == 0) return 1;
    if (offset < 0 || step < 0) return 0;
    /* (n - 1) * step + offset + 3 <= len, without overflow. */
    if (len_floats < offset + 3) return 0;
    return step == 0 || (n - 1) <= (len_floats - offset - 3) / step;
}

enum { MAX_OUTPUTS = 6 };

/* query(kind, n, org, org_offset, org_step, dir, dir_offset, dir_step,
 *       tmin, tmax, backend, threads, outputs): see rtcl_query. org and dir
 * are float32 arrays read from the offsets with the steps (in floats); tmin
 * and tmax float32 arrays of 1 or n items; outputs a tuple: cast (t, prim,
 * mesh, inst, uv, normal), occlusion (occluded bool), count (counts int32 or
 * uint32). backend "" (count): the renderer's. threads 0: every core. */
static PyObject *scene_query(SceneObject *self, PyObject *args) {
    int kind, threads;
    Py_ssize_t n, org_offset, org_step, dir_offset, dir_step;
    PyObject *org_obj, *dir_obj, *tmin_obj, *tmax_obj, *outputs;
    const char *backend;
    if (!PyArg_ParseTuple(args, "inOnnOnnOOsiO!:query", &kind, &n, &org_obj, &org_offset, &org_step,
                          &dir_obj, &dir_offset, &dir_step, &tmin_obj, &tmax_obj, &backend,
                          &threads, &PyTuple_Type, &outputs))
        return NULL;
    if (kind < RTCL_CAST || kind > RTCL_COUNT)
        return PyErr_Format(PyExc_ValueError, "unknown query kind %d", kind);
    if (n < 0) return PyErr_Format(PyExc_ValueError, "negative ray count %zd", n);
    if (threads < 0) return PyErr_Format(PyExc_ValueError, "negative thread count %d", threads);
    if (strlen(backend) >= sizeof self->renderers[0].backend)
        return PyErr_Format(PyExc_ValueError, "backend name too long: '%.40s...'", backend);
    const Py_ssize_t want_outputs = kind == RTCL_CAST ? 6 : 1;
    if (PyTuple_GET_SIZE(outputs) != want_outputs)
        return PyErr_Format(PyExc_ValueError, "%zd output arrays where %zd were expected",
                            PyTuple_GET_SIZE(outputs), want_outputs);

    Py_buffer in[4], out[MAX_OUTPUTS];
    int have_in = 0, have_out = 0;
    PyObject *ret = NULL;
    rtcl_query q;
    memset(&q, 0, sizeof q);
    q.kind = kind;
    q.n = (size_t)n;
    PyObject *in_obj[4] = {org_obj, dir_obj, tmin_obj, tmax_obj};
    static const char *in_name[4] = {"origins", "directions", "tmin", "tmax"};
    for (; have_in < 4; have_in++)
        if (!get_array(in_obj[have_in], &in[have_in], in_name[have_in], "f", 4, 0)) goto done;
    if (!covers(in[0].len / 4, n, org_offset, org_step) ||
        !covers(in[1].len / 4, n, dir_offset, dir_step)) {
        PyErr_SetString(PyExc_ValueError, "origins or directions: too few numbers for the rays");
        goto done;
    }
    const float *ends[2];
    size_t end_steps[2];
    for (int k = 0; k < 2; k++) {
        const Py_ssize_t len = in[2 + k].len / 4;
        if (len != 1 && len != n) {
            PyErr_Format(PyExc_ValueError, "%s: 1 or %zd numbers, got %zd", in_name[2 + k], n, len);
            goto done;
        }
        ends[k] = in[2 + k].buf;
        end_steps[k] = len == 1 ? 0 : 1;
    }
    q.org = (const float *)in[0].buf + org_offset;
    q.org_step = (size_t)org_step;
    q.dir = (const float *)in[1].buf + dir_offset;
    q.dir_step = (size_t)dir_step;
    q.tmin = ends[0];
    q.tmin_step = end_steps[0];
    q.tmax = ends[1];
    q.tmax_step = end_steps[1];
    if (kind == RTCL_CAST) {
        static const char *names[6] = {"t_hit",        "primitive_ids", "geometry_ids",
                                       "instance_ids", "primitive_uvs", "primitive_normals"};
        static const char *codes[6] = {"f", "IL", "IL", "IL", "f", "f"};
        static const Py_ssize_t per_ray[6] = {1, 1, 1, 1, 2, 3};
        for (; have_out < 6; have_out++)
            if (!get_output(PyTuple_GET_ITEM(outputs, have_out), &out[have_out], names[have_out],
                            codes[have_out], 4, per_ray[have_out] * n))
                goto done;
        q.t = out[0].buf;
        q.prim = out[1].buf;
        q.mesh = out[2].buf;
        q.inst = out[3].buf;
        q.uv = out[4].buf;
        q.normal = out[5].buf;
    } else if (kind == RTCL_OCCLUSION) {
        if (!get_output(PyTuple_GET_ITEM(outputs, 0), &out[0], "occluded", "?B", 1, n)) goto done;
        have_out = 1;
        q.occluded = out[0].buf;
    } else {
        if (!get_output(PyTuple_GET_ITEM(outputs, 0), &out[0], "counts", "iIlL", 4, n)) goto done;
        have_out = 1;
        q.counts = out[0].buf;
    }

    call_result res = {RT_OK, ""};
    char used[32] = "";
    LOCKED_BEGIN(self)
    rt_renderer *r = renderer_for(self, threads, backend, &res);
    if (r) {
        rt_status st = rtcl_run_query(r, self->scene, &q);
        if (st != RT_OK) result_set(&res, st, rt_renderer_error(r));
        snprintf(used, sizeof used, "%s", rt_renderer_backend(r));
    }
    LOCKED_END(self)
    if (used[0] && kind != RTCL_COUNT) memcpy(self->last_backend, used, sizeof used);
    if (res.status != RT_OK) {
        raise_result(&res);
        goto done;
    }
    ret = Py_None;
    Py_INCREF(ret);
done:
    for (int i = 0; i < have_in; i++) PyBuffer_Release(&in[i]);
    for (int i = 0; i < have_out; i++) PyBuffer_Release(&out[i]);
    return ret;
}

/* mesh_count (closure NULL) and instance_count (non-NULL). */
static PyObject *scene_count(SceneObject *self, void *closure) {
    uint32_t n;
    LOCKED_BEGIN(self)
    n = closure ? rt_scene_object_count(self->scene) : rt_scene_mesh_count(self->scene);
    LOCKED_END(self)
    return PyLong_FromUnsignedLong(n);
}

static PyObject *scene_last_backend(SceneObject *self, void *closure) {
    (void)closure;
    if (!self->last_backend[0]) Py_RETURN_NONE;
    return PyUnicode_FromString(self->last_backend);
}

static PyMethodDef scene_methods[] = {
    {"add_mesh", (PyCFunction)scene_add_mesh, METH_VARARGS,
     "add_mesh(vertices, triangles, accel) -> mesh id (float32 and uint32 buffers)"},
    {"add_instance", (PyCFunction)scene_add_instance, METH_VARARGS,
     "add_instance(mesh, transform or None) -> instance id (16 float32)"},
    {"update_vertices", (PyCFunction)scene_update_vertices, METH_VARARGS,
     "update_vertices(mesh, vertices, policy)"},
    {"query", (PyCFunction)scene_query, METH_VARARGS,
     "query(kind, n, org, org_offset, org_step, dir, dir_offset, dir_step, tmin, tmax, "
     "backend, threads, outputs)"},
    {NULL, NULL, 0, NULL}};

static PyGetSetDef scene_getset[] = {
    {"mesh_count", (getter)scene_count, NULL, "meshes in the scene", NULL},
    {"instance_count", (getter)scene_count, NULL, "instances (objects) in the scene", "objects"},
    {"last_backend", (getter)scene_last_backend, NULL,
     "the backend that ran the last cast or occlusion query (None before the first)", NULL},
    {NULL, NULL, NULL, NULL, NULL}};

static PyTypeObject SceneType = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "rtcl._rtcl.Scene",
    .tp_basicsize = sizeof(SceneObject),
    .tp_dealloc = (destructor)scene_dealloc,
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "The library's scene and the renderers that query it (use rtcl.Scene).",
    .tp_methods = scene_methods,
    .tp_getset = scene_getset,
    .tp_new = scene_new,
};

static PyMethodDef module_methods[] = {
    {"load", scene_load, METH_VARARGS, "load(path) -> Scene: any scene file rtcl reads"},
    {NULL, NULL, 0, NULL}};

static struct PyModuleDef module_def = {
    PyModuleDef_HEAD_INIT,
    .m_name = "rtcl._rtcl",
    .m_doc = "The rtcl library's C API for the rtcl package.",
    .m_size = -1,
    .m_methods = module_methods,
};

PyMODINIT_FUNC PyInit__rtcl(void) {
    if (PyType_Ready(&SceneType) < 0) return NULL;
    PyObject *m = PyModule_Create(&module_def);
    if (!m) return NULL;
    Py_INCREF(&SceneType);
    if (PyModule_AddObject(m, "Scene", (PyObject *)&SceneType) < 0 ||
        PyModule_AddIntConstant(m, "CAST", RTCL_CAST) < 0 ||
        PyModule_AddIntConstant(m, "OCCLUSION", RTCL_OCCLUSION) < 0 ||
        PyModule_AddIntConstant(m, "COUNT", RTCL_COUNT) < 0 ||
        PyModule_AddStringConstant(m, "version", RTCL_PY_VERSION) < 0) {
        Py_DECREF(m);
        return NULL;
    }
    return m;
}
