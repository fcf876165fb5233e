/* SPDX-License-Identifier: Apache-2.0 */
/* scene_json.c - JSON scene files (docs/SCENE_FORMAT.md) into a scene.
 *
 * jansson parses the text; this file checks every key, type and range and
 * builds the scene through the rt.h calls, which validate once more. Every
 * error names the scene file, the line and column of the offending value and
 * its path in the document ("objects[2].material: ..."). jansson keeps no
 * positions in its values, so the position is found afterwards by scanning
 * the text along the path (json_locate.h); the loader tracks that path as it
 * descends. The first error stops the load; rt_scene_load then destroys the
 * scene, so nothing is half-loaded.
 */
#include "formats/gltf_load.h"
#include "formats/scene_load.h"
#include "formats/scene_obj.h"

#include <errno.h>
#include <jansson.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/file_read.h"
#include "formats/json_bulk.h"
#include "formats/json_locate.h"
#include "scene/scene.h"
#include "scene/scene_default_view.h"

/* Deep enough for the deepest value of the format,
 * objects[i].transform.rotate.axis[k]. */
#define MAX_DEPTH 8

typedef struct loader {
    rt_scene *scene;
    rt_error *err;
    const char *path; /* the scene file, for messages and relative mesh paths */
    const char *text; /* its content, for positions */
    size_t len;
    rt_json_step steps[MAX_DEPTH]; /* the path of the value being read */
    size_t depth;
    json_t *materials;       /* the document's "materials" (names for messages), or NULL */
    json_t *meshes;          /* the document's "meshes", or NULL */
    json_t *material_ids;    /* name -> material id */
    json_t *mesh_ids;        /* name -> mesh id */
    uint32_t white;          /* the default material, UINT32_MAX until an object needs it */
    rt_json_bulk_table bulk; /* the big number arrays, read from the text (json_bulk.h) */
    size_t at;               /* where the value failing is when known, else SIZE_MAX */
} loader;

/* ---- where we are, and errors there ----------------------------------- */

static void enter_key(loader *L, const char *key) {
    if (L->depth < MAX_DEPTH) {
        L->steps[L->depth].key = key;
        L->steps[L->depth].index = 0;
    }
    L->depth++;
}

static void enter_index(loader *L, size_t index) {
    if (L->depth < MAX_DEPTH) {
        L->steps[L->depth].key = NULL;
        L->steps[L->depth].index = index;
    }
    L->depth++;
}

static void leave(loader *L) {
    L->depth--;
}

/* The current path as text: "objects[2].material"; "" at the top. */
static void path_text(const loader *L, char *out, size_t cap) {
    size_t n = 0, depth = L->depth < MAX_DEPTH ? L->depth : MAX_DEPTH;
    out[0] = '\0';
    for (size_t i = 0; i < depth && n < cap; i++) {
        int w;
        if (L->steps[i].key)
            w = snprintf(out + n, cap - n, "%s%s", i ? "." : "", L->steps[i].key);
        else
            w = snprintf(out + n, cap - n, "[%zu]", L->steps[i].index);
        if (w < 0) break;
        n += (size_t)w;
    }
}

/* Fails at the current value (or, with at_key, at the key that names it),
 * the reason prefixed with the value's path when prefix is set. */
static rt_status fail_v(loader *L, int at_key, int prefix, const char *fmt, va_list args) {
    int line = 0, column = 0;
    size_t depth = L->depth < MAX_DEPTH ? L->depth : MAX_DEPTH;
    if (L->at != SIZE_MAX) /* a number of a bulk array: its place is known */
        rt_json_offset_position(L->text, L->len, L->at, &line, &column);
    else if (!rt_json_locate(L->text, L->len, L->steps, depth, at_key, &line, &column))
        line = column = 0;
    char where[256], reason[640];
    path_text(L, where, sizeof where);
    vsnprintf(reason, sizeof reason, fmt, args);
    if (prefix && where[0])
        return rt_error_set(L->err, RT_ERROR_PARSE, L->path, line, column, "%s: %s", where, reason);
    return rt_error_set(L->err, RT_ERROR_PARSE, L->path, line, column, "%s", reason);
}

#if defined(__GNUC__)
#define PRINTF_LIKE(i, j) __attribute__((format(printf, i, j)))
#else
#define PRINTF_LIKE(i, j)
#endif

/* An error about the current value: "path: reason" at the value. */
PRINTF_LIKE(2, 3) static rt_status fail(loader *L, const char *fmt, ...) {
    va_list args;
    va_start(args, fmt);
    rt_status st = fail_v(L, 0, 1, fmt, args);
    va_end(args);
    return st;
}

/* An error about the current member's key: "reason" at the key. */
PRINTF_LIKE(2, 3) static rt_status fail_key(loader *L, const char *fmt, ...) {
    va_list args;
    va_start(args, fmt);
    rt_status st = fail_v(L, 1, 0, fmt, args);
    va_end(args);
    return st;
}

/* A failure of an rt.h call, its message placed at the current value. */
static rt_status fail_scene(loader *L) {
    const char *msg = L->scene->error.message;
    /* "camera: ..." at the path camera says camera once. */
    char where[256];
    path_text(L, where, sizeof where);
    size_t n = strlen(where);
    if (n && strncmp(msg, where, n) == 0 && msg[n] == ':' && msg[n + 1] == ' ') msg += n + 2;
    return fail(L, "%s", msg[0] ? msg : "invalid value");
}

/* ---- types and values ------------------------------------------------------ */

static const char *type_name(const json_t *v) {
    switch (json_typeof(v)) {
    case JSON_OBJECT:
        return "an object";
    case JSON_ARRAY:
        return "an array";
    case JSON_STRING:
        return "a string";
    case JSON_INTEGER:
        return "an integer";
    case JSON_REAL:
        return "a number";
    case JSON_TRUE:
    case JSON_FALSE:
        return "a boolean";
    case JSON_NULL:
        return "null";
    }
    return "an unknown value";
}

static rt_status expect_object(loader *L, const json_t *v) {
    return json_is_object(v) ? RT_OK : fail(L, "expected an object, found %s", type_name(v));
}

static rt_status expect_array(loader *L, const json_t *v) {
    return json_is_array(v) ? RT_OK : fail(L, "expected an array, found %s", type_name(v));
}

/* "a, b, c" from the keys of obj (or "none"), cut short with "..." to fit. */
static void list_keys(const json_t *obj, char *out, size_t cap) {
    size_t n = 0;
    const char *key;
    json_t *value;
    out[0] = '\0';
    if (obj) {
        json_object_foreach((json_t *)obj, key, value) {
            size_t need = strlen(key) + (n ? 2 : 0);
            if (n + need + 5 > cap) {
                memcpy(out + n, n ? ", ..." : "...", n ? 6 : 4);
                return;
            }
            if (n) memcpy(out + n, ", ", 2);
            memcpy(out + n + need - strlen(key), key, strlen(key) + 1);
            n += need;
        }
    }
    if (!n) memcpy(out, "none", 5);
}

/* Rejects keys of obj not in valid (NULL-terminated), pointing at the key. */
static rt_status check_keys(loader *L, json_t *obj, const char *const *valid) {
    const char *key;
    json_t *value;
    json_object_foreach(obj, key, value) {
        int known = 0;
        for (size_t i = 0; valid[i] && !known; i++) known = strcmp(key, valid[i]) == 0;
        if (known) continue;
        char where[256], list[512];
        size_t n = 0;
        path_text(L, where, sizeof where);
        list[0] = '\0';
        for (size_t i = 0; valid[i]; i++) {
            int w = snprintf(list + n, sizeof list - n, "%s%s", i ? ", " : "", valid[i]);
            if (w > 0 && (size_t)w < sizeof list - n) n += (size_t)w;
        }
        enter_key(L, key);
        return fail_key(L, "unknown key '%s' in %s (valid keys: %s)", key,
                        where[0] ? where : "the scene", list);
    }
    return RT_OK;
}

static rt_status read_number(loader *L, const json_t *v, double *out) {
    *out = 0.0;
    if (!json_is_number(v)) return fail(L, "expected a number, found %s", type_name(v));
    *out = json_number_value(v);
    return RT_OK;
}

/* A number that fits a float (JSON itself has no NaN or infinity, but 1e39
 * is finite only as a double). */
static rt_status read_float(loader *L, const json_t *v, float *out) {
    double d;
    rt_status st = read_number(L, v, &d);
    if (st != RT_OK) return st;
    if (!isfinite((float)d)) return fail(L, "%g is out of range for a 32-bit float", d);
    *out = (float)d;
    return RT_OK;
}

/* A whole number in min..max; 3.0 counts as whole, 2.5 does not. */
static rt_status read_int(loader *L, const json_t *v, long long min, long long max,
                          long long *out) {
    long long i;
    if (json_is_integer(v)) {
        i = json_integer_value(v);
    } else if (json_is_real(v)) {
        double d = json_real_value(v);
        if (d != floor(d) || d < (double)min || d > (double)max)
            return fail(L, "expected an integer in %lld..%lld, found %g", min, max, d);
        i = (long long)d;
    } else {
        return fail(L, "expected an integer, found %s", type_name(v));
    }
    if (i < min || i > max) return fail(L, "%lld is outside %lld..%lld", i, min, max);
    *out = i;
    return RT_OK;
}

/* An array of exactly n numbers. */
static rt_status read_floats(loader *L, const json_t *v, float *out, size_t n) {
    if (!json_is_array(v))
        return fail(L, "expected an array of %zu numbers, found %s", n, type_name(v));
    if (json_array_size(v) != n)
        return fail(L, "expected %zu numbers, found %zu", n, json_array_size(v));
    for (size_t i = 0; i < n; i++) {
        enter_index(L, i);
        rt_status st = read_float(L, json_array_get(v, i), &out[i]);
        leave(L);
        if (st != RT_OK) return st;
    }
    return RT_OK;
}

static rt_status read_color(loader *L, const json_t *v, float out[3]) {
    rt_status st = read_floats(L, v, out, 3);
    for (size_t i = 0; st == RT_OK && i < 3; i++) {
        if (out[i] >= 0.0f && out[i] <= RT_MAX_COLOUR) continue;
        enter_index(L, i);
        if (out[i] < 0.0f)
            st = fail(L, "a colour component must be >= 0, found %g", (double)out[i]);
        else
            st = fail(L, "%g is outside 0..%g (the colour limit)", (double)out[i],
                      (double)RT_MAX_COLOUR);
        leave(L);
    }
    return st;
}

/* Which values a number may take. */
typedef enum range { ANY, NON_NEGATIVE, POSITIVE, UNIT, FOV, COLOUR } range;

static rt_status check_range(loader *L, float f, range r) {
    double d = f;
    switch (r) {
    case ANY:
        return RT_OK;
    case NON_NEGATIVE:
        return f >= 0.0f ? RT_OK : fail(L, "must be >= 0, found %g", d);
    case POSITIVE:
        return f > 0.0f ? RT_OK : fail(L, "must be > 0, found %g", d);
    case UNIT:
        return f >= 0.0f && f <= 1.0f ? RT_OK : fail(L, "must be between 0 and 1, found %g", d);
    case COLOUR:
        if (f < 0.0f) return fail(L, "must be >= 0, found %g", d);
        return f <= RT_MAX_COLOUR
                   ? RT_OK
                   : fail(L, "%g is outside 0..%g (the colour limit)", d, (double)RT_MAX_COLOUR);
    case FOV:
        return f > 0.0f && f < 180.0f ? RT_OK
                                      : fail(L,
                                             "the field of view must be between 0 and 180 degrees "
                                             "(both excluded), found %g",
                                             d);
    }
    return RT_OK;
}

/* obj.key, entered (the path of its errors), or NULL when it is absent. */
static json_t *opt_enter(loader *L, json_t *obj, const char *key) {
    json_t *v = json_object_get(obj, key);
    if (v) enter_key(L, key);
    return v;
}

/* Leaves the key opt_enter entered; returns st. */
static rt_status opt_leave(loader *L, rt_status st) {
    leave(L);
    return st;
}

/* obj.key, when present, into *out (else *out keeps its default). */
static rt_status opt_float(loader *L, json_t *obj, const char *key, float *out, range r) {
    json_t *v = opt_enter(L, obj, key);
    if (!v) return RT_OK;
    rt_status st = read_float(L, v, out);
    if (st == RT_OK) st = check_range(L, *out, r);
    return opt_leave(L, st);
}

static rt_status opt_int(loader *L, json_t *obj, const char *key, long long min, long long max,
                         long long *out) {
    json_t *v = opt_enter(L, obj, key);
    return v ? opt_leave(L, read_int(L, v, min, max, out)) : RT_OK;
}

static rt_status opt_vec3(loader *L, json_t *obj, const char *key, float out[3]) {
    json_t *v = opt_enter(L, obj, key);
    return v ? opt_leave(L, read_floats(L, v, out, 3)) : RT_OK;
}

static rt_status opt_color(loader *L, json_t *obj, const char *key, float out[3]) {
    json_t *v = opt_enter(L, obj, key);
    return v ? opt_leave(L, read_color(L, v, out)) : RT_OK;
}

static rt_status require(loader *L, json_t *obj, const char *key) {
    return json_object_get(obj, key) ? RT_OK : fail(L, "missing key '%s'", key);
}

/* Two keys that exclude each other: the error points at the second. */
static rt_status exclusive(loader *L, json_t *obj, const char *a, const char *b) {
    if (!json_object_get(obj, a) || !json_object_get(obj, b)) return RT_OK;
    enter_key(L, b);
    rt_status st = fail_key(L, "'%s' and '%s' exclude each other: give one of them", a, b);
    leave(L);
    return st;
}

/* ---- camera, colours, materials, lights ---------------------------------- */

/* A strictly increasing "time" of a key, at index i of an array of keys. */
static rt_status read_key_time(loader *L, json_t *key, double prev, size_t i, double *t) {
    enter_key(L, "time");
    rt_status st = read_number(L, json_object_get(key, "time"), t);
    if (st == RT_OK && i > 0 && !(*t > prev))
        st = fail(L, "key times must increase: %g follows %g", *t, prev);
    leave(L);
    return st;
}

/* For an array of keys: its length n (at least 1) and *keys, n zeroed
 * keys of size bytes, to free. */
static rt_status new_keys(loader *L, json_t *v, size_t size, void **keys, size_t *n) {
    rt_status st = expect_array(L, v);
    if (st == RT_OK && json_array_size(v) == 0)
        st = fail(L, "expected at least one key, found an empty array");
    if (st == RT_OK && json_array_size(v) > UINT32_MAX) st = fail(L, "too many keys");
    if (st != RT_OK) return st;
    *n = json_array_size(v);
    *keys = calloc(*n, size);
    if (!*keys) return rt_error_set(L->err, RT_ERROR_OUT_OF_MEMORY, L->path, 0, 0, "out of memory");
    return RT_OK;
}

/* The camera's path: [{time, position, look_at}, ...]. */
static rt_status load_camera_path(loader *L, json_t *v, rt_camera *cam) {
    static const char *const keys[] = {"time", "position", "look_at", NULL};
    rt_camera_key *k;
    size_t n;
    rt_status st = new_keys(L, v, sizeof *k, (void **)&k, &n);
    if (st != RT_OK) return st;
    for (size_t i = 0; st == RT_OK && i < n; i++) {
        json_t *e = json_array_get(v, i);
        enter_index(L, i);
        st = expect_object(L, e);
        if (st == RT_OK) st = check_keys(L, e, keys);
        if (st == RT_OK) st = require(L, e, "time");
        if (st == RT_OK) st = require(L, e, "position");
        if (st == RT_OK) st = require(L, e, "look_at");
        if (st == RT_OK) st = read_key_time(L, e, i ? k[i - 1].time : 0.0, i, &k[i].time);
        if (st == RT_OK) st = opt_vec3(L, e, "position", k[i].position);
        if (st == RT_OK) st = opt_vec3(L, e, "look_at", k[i].look_at);
        if (st == RT_OK && memcmp(k[i].position, k[i].look_at, sizeof k[i].position) == 0) {
            enter_key(L, "look_at");
            st = fail(L, "the look-at point equals the position");
            leave(L);
        }
        leave(L);
    }
    if (st == RT_OK) {
        memcpy(cam->position, k[0].position, sizeof cam->position);
        memcpy(cam->look_at, k[0].look_at, sizeof cam->look_at);
        if (rt_camera_set_path(L->scene, k, (uint32_t)n) != RT_OK) st = fail_scene(L);
    }
    free(k);
    return st;
}

static rt_status load_camera(loader *L, json_t *v) {
    static const char *const keys[] = {"position", "look_at", "direction", "up", "fov",
                                       "width",    "height",  "path",      NULL};
    rt_status st = expect_object(L, v);
    if (st == RT_OK) st = check_keys(L, v, keys);
    json_t *path = json_object_get(v, "path");
    if (path) {
        /* The path places the eye and the look-at point at every time. */
        static const char *const placed[] = {"position", "look_at", "direction"};
        for (size_t i = 0; st == RT_OK && i < 3; i++) st = exclusive(L, v, "path", placed[i]);
    } else {
        if (st == RT_OK) st = require(L, v, "position");
        if (st == RT_OK) st = exclusive(L, v, "look_at", "direction");
        if (st == RT_OK && !json_object_get(v, "look_at") && !json_object_get(v, "direction"))
            st = fail(L, "missing key 'look_at' or 'direction'");
    }
    if (st != RT_OK) return st;

    rt_camera cam = {{0, 0, 0}, {0, 0, 0}, {0, 1, 0}, 60.0f, 1024, 576};
    float dir[3] = {0, 0, 0};
    long long width = cam.width, height = cam.height;
    if (path) {
        enter_key(L, "path");
        st = load_camera_path(L, path, &cam);
        leave(L);
    }
    if (st == RT_OK) st = opt_vec3(L, v, "position", cam.position);
    if (st == RT_OK) st = opt_vec3(L, v, "look_at", cam.look_at);
    if (st == RT_OK) st = opt_vec3(L, v, "direction", dir);
    if (st == RT_OK) st = opt_vec3(L, v, "up", cam.up);
    if (st == RT_OK) st = opt_float(L, v, "fov", &cam.hfov_degrees, FOV);
    if (st == RT_OK) st = opt_int(L, v, "width", 1, 32768, &width);
    if (st == RT_OK) st = opt_int(L, v, "height", 1, 32768, &height);
    if (st != RT_OK) return st;
    if (json_object_get(v, "direction")) {
        if (dir[0] == 0.0f && dir[1] == 0.0f && dir[2] == 0.0f) {
            enter_key(L, "direction");
            st = fail(L, "the view direction must not be zero");
            leave(L);
            return st;
        }
        for (int k = 0; k < 3; k++) cam.look_at[k] = cam.position[k] + dir[k];
    }
    cam.width = (int)width;
    cam.height = (int)height;
    if (rt_camera_set(L->scene, &cam) != RT_OK) return fail_scene(L);
    return RT_OK;
}

static rt_status load_material(loader *L, json_t *v, uint32_t *id) {
    static const char *const keys[] = {
        "color",        "ambient",      "diffuse", "specular", "shininess",
        "reflectivity", "transparency", "ior",     "emission", NULL};
    rt_material m = rt_material_default();
    long long shininess = m.shininess;
    rt_status st = expect_object(L, v);
    if (st == RT_OK) st = check_keys(L, v, keys);
    if (st == RT_OK) st = opt_color(L, v, "color", m.color);
    if (st == RT_OK) st = opt_float(L, v, "ambient", &m.ambient, COLOUR);
    if (st == RT_OK) st = opt_float(L, v, "diffuse", &m.diffuse, COLOUR);
    if (st == RT_OK) st = opt_float(L, v, "specular", &m.specular, COLOUR);
    if (st == RT_OK) st = opt_int(L, v, "shininess", 0, 100000, &shininess);
    if (st == RT_OK) st = opt_float(L, v, "reflectivity", &m.reflectivity, UNIT);
    if (st == RT_OK) st = opt_float(L, v, "transparency", &m.transparency, UNIT);
    if (st == RT_OK) st = opt_float(L, v, "ior", &m.ior, POSITIVE);
    if (st == RT_OK) st = opt_color(L, v, "emission", m.emission);
    if (st != RT_OK) return st;
    m.shininess = (int)shininess;
    if (m.reflectivity + m.transparency > 1.0f)
        return fail(L, "reflectivity + transparency is %g; it must not exceed 1",
                    (double)(m.reflectivity + m.transparency));
    if (rt_material_add(L->scene, &m, id) != RT_OK) return fail_scene(L);
    return RT_OK;
}

static rt_status load_materials(loader *L, json_t *v) {
    rt_status st = expect_object(L, v);
    const char *name;
    json_t *m;
    if (st != RT_OK) return st;
    json_object_foreach(v, name, m) {
        uint32_t id;
        enter_key(L, name);
        st = load_material(L, m, &id);
        leave(L);
        if (st != RT_OK) return st;
        if (json_object_set_new(L->material_ids, name, json_integer(id)) != 0)
            return rt_error_set(L->err, RT_ERROR_OUT_OF_MEMORY, L->path, 0, 0, "out of memory");
    }
    return RT_OK;
}

static rt_status load_lights(loader *L, json_t *v) {
    static const char *const keys[] = {"position", "color", NULL};
    rt_status st = expect_array(L, v);
    for (size_t i = 0; st == RT_OK && i < json_array_size(v); i++) {
        json_t *light = json_array_get(v, i);
        float position[3] = {0, 0, 0}, color[3] = {1, 1, 1};
        uint32_t id;
        enter_index(L, i);
        st = expect_object(L, light);
        if (st == RT_OK) st = check_keys(L, light, keys);
        if (st == RT_OK) st = require(L, light, "position");
        if (st == RT_OK) st = opt_vec3(L, light, "position", position);
        if (st == RT_OK) st = opt_color(L, light, "color", color);
        if (st == RT_OK && rt_light_add(L->scene, position, color, &id) != RT_OK)
            st = fail_scene(L);
        leave(L);
    }
    return st;
}

/* ---- meshes ---------------------------------------------------------------- */

/* The bulk array (json_bulk.h) whose placeholder v is, taken now; NULL
 * when v is none (then it is read as the value it is). */
static rt_json_bulk *take_bulk(loader *L, const json_t *v) {
    if (!json_is_array(v) || json_array_size(v) != 1) return NULL;
    const json_t *o = json_array_get(v, 0);
    const json_t *offset =
        json_is_object(o) && json_object_size(o) == 1 ? json_object_get(o, "") : NULL;
    if (!json_is_integer(offset) || json_integer_value(offset) < 0) return NULL;
    rt_json_bulk *b = rt_json_bulk_at(&L->bulk, (size_t)json_integer_value(offset));
    if (!b || b->taken) return NULL;
    b->taken = 1;
    return b;
}

/* The numbers of a bulk array: as floats (out_f: jansson's value, then the
 * float cast read_float makes, each checked as read_float does) or as
 * vertex indices below vertex_count (out_i, each checked as read_triple_element
 * does). An element that fails is named with its index and place. */
static rt_status read_bulk(loader *L, const rt_json_bulk *b, float *out_f, uint32_t *out_i,
                           uint32_t vertex_count) {
    size_t pos = b->start, at = 0;
    int integer;
    long long iv = 0;
    double rv = 0.0;
    for (size_t i = 0; i < b->count; i++) {
        if (!rt_json_bulk_next(L->text, b->end, &pos, &at, &integer, &iv, &rv))
            return rt_error_set(L->err, RT_ERROR_PARSE, L->path, 0, 0, "a bulk array changed");
        double d = integer ? (double)iv : rv;
        if (out_f) {
            out_f[i] = (float)d;
            if (isfinite(out_f[i])) continue;
        } else if (integer && iv >= 0 && iv < (long long)vertex_count) {
            out_i[i] = (uint32_t)iv;
            continue;
        }
        enter_index(L, i);
        L->at = at;
        rt_status st =
            out_f ? fail(L, "%g is out of range for a 32-bit float", d)
            : !integer
                ? fail(L, "expected a vertex index (an integer), found a number")
                : fail(L, "vertex index %lld is out of range: the mesh has %u vertices (0..%lld)",
                       iv, vertex_count, (long long)vertex_count - 1);
        L->at = SIZE_MAX;
        leave(L);
        return st;
    }
    return RT_OK;
}

/* Element i of a JSON array of triples: a float into f[i], or (f NULL) a
 * vertex index below vertex_count into idx[i]. */
static rt_status read_triple_element(loader *L, json_t *e, size_t i, float *f, uint32_t *idx,
                                     uint32_t vertex_count) {
    if (f) return read_float(L, e, &f[i]);
    if (!json_is_integer(e))
        return fail(L, "expected a vertex index (an integer), found %s", type_name(e));
    if (json_integer_value(e) < 0 || json_integer_value(e) >= (json_int_t)vertex_count)
        return fail(L, "vertex index %lld is out of range: the mesh has %u vertices (0..%lld)",
                    (long long)json_integer_value(e), vertex_count, (long long)vertex_count - 1);
    idx[i] = (uint32_t)json_integer_value(e);
    return RT_OK;
}

/* A flat array (or bulk array) whose length is a multiple of 3, into a new
 * buffer: floats (out_f, 3 per what) or vertex indices below vertex_count
 * (out_i, 3 per triangle); the other of out_f and out_i is NULL. */
static rt_status read_triples(loader *L, json_t *v, const char *what, uint32_t vertex_count,
                              float **out_f, uint32_t **out_i, size_t *count) {
    void **out = out_f ? (void **)out_f : (void **)out_i;
    const char *unit = out_f ? "numbers" : "vertex indices";
    const size_t size = out_f ? sizeof(float) : sizeof(uint32_t);
    *out = NULL;
    *count = 0;
    rt_json_bulk *bulk = take_bulk(L, v);
    if (!bulk && !json_is_array(v))
        return fail(L, "expected a flat array of %s, found %s", unit, type_name(v));
    size_t n = bulk ? bulk->count : json_array_size(v);
    if (n % 3 != 0)
        return fail(L, "expected 3 %s per %s, but %zu is not a multiple of 3", unit, what, n);
    if (n / 3 > UINT32_MAX / 3)
        return out_f ? fail(L, "too many values (%zu)", n)
                     : fail(L, "too many triangles (%zu)", n / 3);
    void *buf = malloc((bulk || n ? n : 1) * size);
    if (!buf) return rt_error_set(L->err, RT_ERROR_OUT_OF_MEMORY, L->path, 0, 0, "out of memory");
    float *f = out_f ? buf : NULL;
    uint32_t *idx = out_f ? NULL : buf;
    rt_status st = RT_OK;
    if (bulk) st = read_bulk(L, bulk, f, idx, vertex_count);
    for (size_t i = 0; !bulk && st == RT_OK && i < n; i++) {
        enter_index(L, i);
        st = read_triple_element(L, json_array_get(v, i), i, f, idx, vertex_count);
        leave(L);
    }
    if (st != RT_OK) {
        free(buf);
        return st;
    }
    *out = buf;
    *count = n;
    return RT_OK;
}

static rt_status load_inline_mesh(loader *L, json_t *v, const char *name, uint32_t *id) {
    float *positions = NULL, *normals = NULL;
    uint32_t *indices = NULL;
    size_t npos = 0, nnorm = 0, nidx = 0;
    rt_status st = require(L, v, "positions");
    if (st == RT_OK) st = require(L, v, "triangles");
    if (st == RT_OK) {
        enter_key(L, "positions");
        st = read_triples(L, json_object_get(v, "positions"), "vertex", 0, &positions, NULL, &npos);
        leave(L);
    }
    json_t *nv = json_object_get(v, "normals");
    if (st == RT_OK && nv) {
        enter_key(L, "normals");
        st = read_triples(L, nv, "normal", 0, &normals, NULL, &nnorm);
        if (st == RT_OK && nnorm != npos)
            st = fail(L, "expected one normal per vertex (%zu numbers), found %zu numbers", npos,
                      nnorm);
        leave(L);
    }
    if (st == RT_OK) {
        enter_key(L, "triangles");
        st = read_triples(L, json_object_get(v, "triangles"), "triangle", (uint32_t)(npos / 3),
                          NULL, &indices, &nidx);
        leave(L);
    }
    if (st == RT_OK) {
        /* An empty mesh is only created: rt_mesh_add_triangles would hand
         * memcpy a NULL array (undefined even for 0 bytes). */
        if (rt_mesh_create(L->scene, id) != RT_OK ||
            (npos > 0 &&
             rt_mesh_add_triangles(L->scene, *id, positions, normals, (uint32_t)(npos / 3), indices,
                                   (uint32_t)(nidx / 3)) != RT_OK))
            st = fail_scene(L);
        else
            snprintf(L->scene->meshes[*id].name, sizeof L->scene->meshes[*id].name, "%s", name);
    }
    free(positions);
    free(normals);
    free(indices);
    return st;
}

static rt_status white_material(loader *L, uint32_t *id) {
    if (L->white == UINT32_MAX) {
        rt_material m = rt_material_default();
        if (rt_material_add(L->scene, &m, &L->white) != RT_OK) return fail_scene(L);
    }
    *id = L->white;
    return RT_OK;
}

/* An OBJ or glTF file (gltf_load.h: rt_gltf_add_mesh), its path relative to
 * the scene file's folder. */
static rt_status load_mesh_file(loader *L, json_t *v, uint32_t *id) {
    json_t *file = json_object_get(v, "file");
    rt_status st;
    enter_key(L, "file");
    if (!json_is_string(file)) {
        st = fail(L, "expected a file name (a string), found %s", type_name(file));
        leave(L);
        return st;
    }
    const char *name = json_string_value(file);
    if (!name[0]) {
        st = fail(L, "the file name is empty");
        leave(L);
        return st;
    }
    const char *slash = strrchr(L->path, '/');
    size_t dir_len = (name[0] == '/' || !slash) ? 0 : (size_t)(slash - L->path) + 1;
    char *full = malloc(dir_len + strlen(name) + 1);
    if (!full) {
        leave(L);
        return rt_error_set(L->err, RT_ERROR_OUT_OF_MEMORY, L->path, 0, 0, "out of memory");
    }
    memcpy(full, L->path, dir_len);
    strcpy(full + dir_len, name);
    st = rt_gltf_is_gltf_path(full) ? rt_gltf_add_mesh(L->scene, full, id, L->err)
                                    : rt_scene_add_obj(L->scene, full, id, L->err);
    if (st != RT_OK && L->err) {
        /* The OBJ loader's message names the OBJ file and line; add where the
         * scene refers to it. */
        int line, column;
        size_t depth = L->depth < MAX_DEPTH ? L->depth : MAX_DEPTH;
        if (rt_json_locate(L->text, L->len, L->steps, depth, 0, &line, &column)) {
            size_t n = strlen(L->err->message);
            snprintf(L->err->message + n, sizeof L->err->message - n,
                     " (mesh file named at %s:%d:%d)", L->path, line, column);
        }
    }
    free(full);
    leave(L);
    return st;
}

/* A mesh's string key whose value one of the library's name tables reads:
 * parse gives the enum (1: known), set applies it to mesh id; expected
 * lists the valid names for the messages. Absent: nothing changes. */
static rt_status load_mesh_choice(loader *L, json_t *m, uint32_t id, const char *key,
                                  const char *expected, int (*parse)(const char *, int *),
                                  rt_status (*set)(rt_scene *, uint32_t, int)) {
    json_t *a = json_object_get(m, key);
    if (!a) return RT_OK;
    enter_key(L, key);
    int value;
    rt_status st = RT_OK;
    if (!json_is_string(a))
        st = fail(L, "expected %s, found %s", expected, type_name(a));
    else if (!parse(json_string_value(a), &value))
        st = fail(L, "expected %s, found \"%s\"", expected, json_string_value(a));
    else if (set(L->scene, id, value) != RT_OK)
        st = fail_scene(L);
    leave(L);
    return st;
}

/* "accel": the mesh's structure, "bvh" (the default), "kd" or "kd-binned". */
static int parse_accel(const char *name, int *value) {
    rt_accel a;
    return rt_accel_parse(name, &a) ? (*value = (int)a, 1) : 0;
}
static rt_status set_accel(rt_scene *scene, uint32_t id, int value) {
    return rt_mesh_set_accel(scene, id, (rt_accel)value);
}

/* "update": the mesh's BVH update policy (and the names before 0.2). */
static int parse_update(const char *name, int *value) {
    rt_update_policy p;
    return rt_update_policy_parse(name, &p) ? (*value = (int)p, 1) : 0;
}
static rt_status set_update(rt_scene *scene, uint32_t id, int value) {
    return rt_mesh_set_update(scene, id, (rt_update_policy)value);
}

static rt_status load_meshes(loader *L, json_t *v) {
    static const char *const keys[] = {"file",   "positions", "triangles", "normals",
                                       "update", "accel",     NULL};
    static const char *const inline_keys[] = {"positions", "triangles", "normals"};
    rt_status st = expect_object(L, v);
    const char *name;
    json_t *m;
    if (st != RT_OK) return st;
    json_object_foreach(v, name, m) {
        uint32_t id = 0;
        enter_key(L, name);
        st = expect_object(L, m);
        if (st == RT_OK) st = check_keys(L, m, keys);
        for (size_t i = 0; st == RT_OK && i < 3; i++) st = exclusive(L, m, "file", inline_keys[i]);
        if (st == RT_OK)
            st = json_object_get(m, "file") ? load_mesh_file(L, m, &id)
                                            : load_inline_mesh(L, m, name, &id);
        if (st == RT_OK)
            st = load_mesh_choice(L, m, id, "update",
                                  "an update policy: \"sah\", \"refit\", \"lbvh\" or \"auto\"",
                                  parse_update, set_update);
        if (st == RT_OK)
            st = load_mesh_choice(L, m, id, "accel", "\"bvh\", \"kd\" or \"kd-binned\"",
                                  parse_accel, set_accel);
        leave(L);
        if (st != RT_OK) return st;
        if (json_object_set_new(L->mesh_ids, name, json_integer(id)) != 0)
            return rt_error_set(L->err, RT_ERROR_OUT_OF_MEMORY, L->path, 0, 0, "out of memory");
    }
    return RT_OK;
}

/* ---- objects ----------------------------------------------------------------- */

/* The id that names (a string) refers to in ids, a name -> id map. */
static rt_status lookup(loader *L, const json_t *value, const json_t *ids, const json_t *defined,
                        const char *what, const char *what_plural, uint32_t *id) {
    if (!json_is_string(value))
        return fail(L, "expected a %s name (a string), found %s", what, type_name(value));
    json_t *found = json_object_get(ids, json_string_value(value));
    if (!found) {
        char names[400];
        list_keys(defined, names, sizeof names);
        return fail(L, "no %s named '%s' (defined %s: %s)", what, json_string_value(value),
                    what_plural, names);
    }
    *id = (uint32_t)json_integer_value(found);
    return RT_OK;
}

/* Rotation by degrees about axis (Rodrigues), then translation: M = T R. */
static void rigid_matrix(const float axis[3], float degrees, const float translate[3],
                         float m[16]) {
    rt_mat4_identity(m);
    double len =
        sqrt((double)axis[0] * axis[0] + (double)axis[1] * axis[1] + (double)axis[2] * axis[2]);
    if (len > 0.0) {
        double x = axis[0] / len, y = axis[1] / len, z = axis[2] / len;
        double a = degrees * (3.14159265358979323846 / 180.0), c = cos(a), s = sin(a), t = 1 - c;
        double r[9] = {t * x * x + c,     t * x * y - s * z, t * x * z + s * y,
                       t * x * y + s * z, t * y * y + c,     t * y * z - s * x,
                       t * x * z - s * y, t * y * z + s * x, t * z * z + c};
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) m[i * 4 + j] = (float)r[i * 3 + j];
    }
    m[3] = translate[0];
    m[7] = translate[1];
    m[11] = translate[2];
}

static rt_status load_rotation(loader *L, json_t *v, float axis[3], float *degrees) {
    static const char *const keys[] = {"axis", "degrees", NULL};
    rt_status st = expect_object(L, v);
    if (st == RT_OK) st = check_keys(L, v, keys);
    if (st == RT_OK) st = require(L, v, "axis");
    if (st == RT_OK) st = require(L, v, "degrees");
    if (st == RT_OK) st = opt_vec3(L, v, "axis", axis);
    if (st == RT_OK) st = opt_float(L, v, "degrees", degrees, ANY);
    if (st == RT_OK && axis[0] == 0.0f && axis[1] == 0.0f && axis[2] == 0.0f) {
        enter_key(L, "axis");
        st = fail(L, "the rotation axis must not be zero");
        leave(L);
    }
    return st;
}

static rt_status load_transform(loader *L, json_t *v, uint32_t object) {
    static const char *const keys[] = {"matrix", "translate", "rotate", NULL};
    rt_status st = expect_object(L, v);
    if (st == RT_OK) st = check_keys(L, v, keys);
    if (st == RT_OK) st = exclusive(L, v, "matrix", "translate");
    if (st == RT_OK) st = exclusive(L, v, "matrix", "rotate");
    if (st != RT_OK) return st;
    float m[16];
    json_t *matrix = json_object_get(v, "matrix");
    if (matrix) {
        /* Any invertible affine matrix, as rt_object_transform accepts. */
        enter_key(L, "matrix");
        st = read_floats(L, matrix, m, 16);
        if (st == RT_OK && rt_object_transform(L->scene, object, m) != RT_OK) st = fail_scene(L);
        leave(L);
        return st;
    }
    float axis[3] = {0, 1, 0}, degrees = 0.0f, translate[3] = {0, 0, 0};
    json_t *rotate = json_object_get(v, "rotate");
    if (rotate) {
        enter_key(L, "rotate");
        st = load_rotation(L, rotate, axis, &degrees);
        leave(L);
    }
    if (st == RT_OK) st = opt_vec3(L, v, "translate", translate);
    if (st != RT_OK) return st;
    rigid_matrix(axis, degrees, translate, m);
    if (rt_object_transform(L->scene, object, m) != RT_OK) return fail_scene(L);
    return RT_OK;
}

static rt_status add_keyframe(loader *L, const json_t *name, uint32_t object) {
    uint32_t mesh;
    rt_status st = lookup(L, name, L->mesh_ids, L->meshes, "mesh", "meshes", &mesh);
    if (st == RT_OK && rt_object_add_mesh(L->scene, object, mesh) != RT_OK) st = fail_scene(L);
    return st;
}

/* An object's "animation": {"keyframe_rate": R, "interpolate": bool}. */
static rt_status load_animation(loader *L, json_t *v, uint32_t object) {
    static const char *const keys[] = {"keyframe_rate", "interpolate", NULL};
    rt_status st = expect_object(L, v);
    if (st == RT_OK) st = check_keys(L, v, keys);
    if (st == RT_OK) st = require(L, v, "keyframe_rate");
    float rate = 0.0f;
    if (st == RT_OK) st = opt_float(L, v, "keyframe_rate", &rate, POSITIVE);
    json_t *interp = json_object_get(v, "interpolate");
    if (st == RT_OK && interp && !json_is_boolean(interp)) {
        enter_key(L, "interpolate");
        st = fail(L, "expected true or false, found %s", type_name(interp));
        leave(L);
    }
    if (st == RT_OK &&
        rt_object_set_animation(L->scene, object, rate, interp && json_is_true(interp)) != RT_OK)
        st = fail_scene(L);
    return st;
}

/* An object's "transform_keys": [{time, translate, rotate, scale}, ...]. */
static rt_status load_transform_keys(loader *L, json_t *v, uint32_t object) {
    static const char *const keys[] = {"time", "translate", "rotate", "scale", NULL};
    rt_transform_key *k;
    size_t n;
    rt_status st = new_keys(L, v, sizeof *k, (void **)&k, &n);
    if (st != RT_OK) return st;
    for (size_t i = 0; st == RT_OK && i < n; i++) {
        json_t *e = json_array_get(v, i);
        k[i].axis[1] = 1.0f;
        k[i].scale = 1.0f;
        enter_index(L, i);
        st = expect_object(L, e);
        if (st == RT_OK) st = check_keys(L, e, keys);
        if (st == RT_OK) st = require(L, e, "time");
        if (st == RT_OK) st = read_key_time(L, e, i ? k[i - 1].time : 0.0, i, &k[i].time);
        if (st == RT_OK) st = opt_vec3(L, e, "translate", k[i].translate);
        json_t *rotate = json_object_get(e, "rotate");
        if (st == RT_OK && rotate) {
            enter_key(L, "rotate");
            st = load_rotation(L, rotate, k[i].axis, &k[i].degrees);
            leave(L);
        }
        if (st == RT_OK) st = opt_float(L, e, "scale", &k[i].scale, POSITIVE);
        leave(L);
    }
    if (st == RT_OK && rt_object_set_transform_keys(L->scene, object, k, (uint32_t)n) != RT_OK)
        st = fail_scene(L);
    free(k);
    return st;
}

static rt_status load_object(loader *L, json_t *v) {
    static const char *const keys[] = {"mesh",           "keyframes", "frame",
                                       "material",       "transform", "animation",
                                       "transform_keys", "mask",      NULL};
    rt_status st = expect_object(L, v);
    if (st == RT_OK) st = check_keys(L, v, keys);
    if (st == RT_OK) st = exclusive(L, v, "mesh", "keyframes");
    if (st == RT_OK) st = exclusive(L, v, "frame", "animation");
    if (st == RT_OK) st = exclusive(L, v, "transform", "transform_keys");
    if (st == RT_OK && !json_object_get(v, "mesh") && !json_object_get(v, "keyframes"))
        st = fail(L, "missing key 'mesh' or 'keyframes'");
    if (st != RT_OK) return st;

    uint32_t material = 0, object;
    json_t *mv = json_object_get(v, "material");
    if (mv) {
        enter_key(L, "material");
        st = lookup(L, mv, L->material_ids, L->materials, "material", "materials", &material);
        leave(L);
    } else {
        st = white_material(L, &material);
    }
    if (st != RT_OK) return st;
    if (rt_object_create(L->scene, material, &object) != RT_OK) return fail_scene(L);

    json_t *mesh = json_object_get(v, "mesh"), *frames = json_object_get(v, "keyframes");
    uint32_t count = 1;
    if (mesh) {
        enter_key(L, "mesh");
        st = add_keyframe(L, mesh, object);
        leave(L);
    } else {
        enter_key(L, "keyframes");
        st = expect_array(L, frames);
        if (st == RT_OK && json_array_size(frames) == 0)
            st = fail(L, "expected at least one mesh name, found an empty array");
        if (st == RT_OK && json_array_size(frames) > UINT32_MAX) st = fail(L, "too many keyframes");
        count = (uint32_t)json_array_size(frames);
        for (size_t i = 0; st == RT_OK && i < json_array_size(frames); i++) {
            enter_index(L, i);
            st = add_keyframe(L, json_array_get(frames, i), object);
            leave(L);
        }
        leave(L);
    }
    if (st != RT_OK) return st;

    long long frame = 0;
    st = opt_int(L, v, "frame", 0, INT_MAX, &frame);
    if (st == RT_OK && frame >= count) {
        enter_key(L, "frame");
        st = fail(L, "keyframe %lld does not exist: the object has %u keyframe%s (0..%u)", frame,
                  count, count == 1 ? "" : "s", count - 1);
        leave(L);
    }
    if (st == RT_OK && rt_object_select_mesh(L->scene, object, (uint32_t)frame) != RT_OK)
        st = fail_scene(L);
    json_t *transform = json_object_get(v, "transform");
    if (st == RT_OK && transform) {
        enter_key(L, "transform");
        st = load_transform(L, transform, object);
        leave(L);
    }
    json_t *animation = json_object_get(v, "animation");
    if (st == RT_OK && animation) {
        enter_key(L, "animation");
        st = load_animation(L, animation, object);
        leave(L);
    }
    json_t *tkeys = json_object_get(v, "transform_keys");
    if (st == RT_OK && tkeys) {
        enter_key(L, "transform_keys");
        st = load_transform_keys(L, tkeys, object);
        leave(L);
    }
    /* "mask": the object's ray mask (rt_object_set_mask), a whole number. */
    long long mask = 0xffffffffLL;
    if (st == RT_OK) st = opt_int(L, v, "mask", 0, 0xffffffffLL, &mask);
    if (st == RT_OK && rt_object_set_mask(L->scene, object, (uint32_t)mask) != RT_OK)
        st = fail_scene(L);
    return st;
}

static rt_status load_objects(loader *L, json_t *v) {
    rt_status st = expect_array(L, v);
    if (st == RT_OK && json_array_size(v) == 0)
        st = fail(L, "the scene is empty: 'objects' lists no object");
    for (size_t i = 0; st == RT_OK && i < json_array_size(v); i++) {
        enter_index(L, i);
        st = load_object(L, json_array_get(v, i));
        leave(L);
    }
    return st;
}

/* ---- the document ---------------------------------------------------------------- */

/* Runs load(L, root.key) at path "key" when the key is present. */
static rt_status section(loader *L, json_t *root, const char *key,
                         rt_status (*load)(loader *, json_t *)) {
    json_t *v = json_object_get(root, key);
    if (!v) return RT_OK;
    enter_key(L, key);
    rt_status st = load(L, v);
    leave(L);
    return st;
}

static rt_status load_background(loader *L, json_t *v) {
    float c[3];
    rt_status st = read_color(L, v, c);
    if (st == RT_OK && rt_scene_set_background(L->scene, c) != RT_OK) st = fail_scene(L);
    return st;
}

static rt_status load_ambient(loader *L, json_t *v) {
    float c[3];
    rt_status st = read_color(L, v, c);
    if (st == RT_OK && rt_scene_set_ambient(L->scene, c) != RT_OK) st = fail_scene(L);
    return st;
}

static rt_status load_exposure(loader *L, json_t *v) {
    if (!json_is_number(v))
        return fail(L, "exposure must be a number of stops, found %s", type_name(v));
    double ev = json_number_value(v);
    if (!(ev >= -64.0 && ev <= 64.0))
        return fail(L, "exposure %g is out of range (-64 to 64 stops)", ev);
    if (rt_scene_set_exposure(L->scene, (float)ev) != RT_OK) return fail_scene(L);
    return RT_OK;
}

static rt_status load_document(loader *L, json_t *root) {
    static const char *const keys[] = {"camera", "background", "ambient", "exposure", "materials",
                                       "lights", "meshes",     "objects", NULL};
    if (!json_is_object(root))
        return fail(L, "a scene file holds a JSON object, found %s", type_name(root));
    rt_status st = check_keys(L, root, keys);
    if (st == RT_OK) st = section(L, root, "camera", load_camera);
    if (st == RT_OK) st = section(L, root, "background", load_background);
    if (st == RT_OK) st = section(L, root, "ambient", load_ambient);
    if (st == RT_OK) st = section(L, root, "exposure", load_exposure);
    if (st == RT_OK) st = section(L, root, "materials", load_materials);
    if (st == RT_OK) st = section(L, root, "lights", load_lights);
    if (st == RT_OK) st = section(L, root, "meshes", load_meshes);
    if (st == RT_OK && !json_object_get(root, "objects"))
        st = fail(L, "the scene is empty: missing key 'objects'");
    if (st == RT_OK) st = section(L, root, "objects", load_objects);
    if (st != RT_OK) return st;
    rt_scene_commit(L->scene);
    /* An animated scene starts at time 0 (a still one is left as it is). */
    if (rt_scene_is_animated(L->scene) && rt_scene_set_time(L->scene, 0.0) != RT_OK)
        return fail_scene(L);

    enter_key(L, "objects");
    if (rt_scene_triangle_count(L->scene) == 0)
        st = fail(L, "the scene is empty: no object has a triangle");
    leave(L);
    if (st != RT_OK || L->scene->has_camera) return st;

    /* No camera: the default view of a bare OBJ. It also adds a light and
     * sets ambient 0.1; lights or ambient the file gives win over those. */
    uint32_t lights = L->scene->light_count;
    float ambient[3];
    memcpy(ambient, L->scene->ambient, sizeof ambient);
    if (rt_scene_apply_default_view(L->scene, 0, 0) != RT_OK) return fail_scene(L);
    if (json_object_get(root, "lights")) L->scene->light_count = lights;
    if (json_object_get(root, "ambient")) memcpy(L->scene->ambient, ambient, sizeof ambient);
    return RT_OK;
}

/* ---- files ------------------------------------------------------------------------- */

/* Where a syntax error is: jansson gives the offset just past the token it
 * stopped at and quotes that token ("... near 'tru'"); the token's first
 * character is the more useful place. */
static void syntax_position(const char *text, size_t len, const json_error_t *je, int *line,
                            int *column) {
    size_t end = je->position > 0 ? (size_t)je->position : 0;
    if (end > len) end = len;
    const char *near = strstr(je->text, " near '");
    if (near) {
        const char *token = near + 7;
        size_t n = strlen(token);
        if (n > 1 && token[n - 1] == '\'' && n - 1 <= end &&
            memcmp(text + end - (n - 1), token, n - 1) == 0)
            end -= n - 1;
    }
    rt_json_offset_position(text, len, end, line, column);
}

rt_status rt_scene_load_json(rt_scene *scene, const char *path, rt_error *err) {
    rt_error_clear(err);
    if (!scene || !path)
        return rt_error_set(err, RT_ERROR_INVALID_ARGUMENT, path, 0, 0, "no scene or no path");
    char *text = NULL;
    size_t len = 0;
    rt_status st = rt_read_file(path, "scene file", RT_MAX_SCENE_FILE_BYTES, &text, &len, err);
    if (st != RT_OK) return st;

    /* jansson reads the text with the big number arrays held back
     * (json_bulk.h): a value per number would take ten times the text. */
    loader L;
    memset(&L, 0, sizeof L);
    L.at = SIZE_MAX;
    rt_json_bulk_scan(text, len, &L.bulk); /* out of memory: no bulk arrays, all jansson's */
    rt_json_bulk_reader reader = {text, len, 0, &L.bulk, 0};
    json_error_t je;
    json_t *root = json_load_callback(rt_json_bulk_read, &reader, JSON_REJECT_DUPLICATES, &je);
    if (!root) {
        int line, column;
        syntax_position(text, len, &je, &line, &column);
        rt_json_bulk_free(&L.bulk);
        free(text);
        return rt_error_set(err, RT_ERROR_PARSE, path, line, column, "invalid JSON: %s", je.text);
    }
    L.scene = scene;
    L.err = err;
    L.path = path;
    L.text = text;
    L.len = len;
    L.white = UINT32_MAX;
    L.material_ids = json_object();
    L.mesh_ids = json_object();
    if (json_is_object(root)) {
        L.materials = json_object_get(root, "materials");
        L.meshes = json_object_get(root, "meshes");
        if (!json_is_object(L.materials)) L.materials = NULL;
        if (!json_is_object(L.meshes)) L.meshes = NULL;
    }
    if (!L.material_ids || !L.mesh_ids)
        st = rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, path, 0, 0, "out of memory");
    else
        st = load_document(&L, root);
    json_decref(L.material_ids);
    json_decref(L.mesh_ids);
    json_decref(root);
    rt_json_bulk_free(&L.bulk);
    free(text);
    return st;
}
