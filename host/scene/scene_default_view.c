/* SPDX-License-Identifier: Apache-2.0 */
/* scene_default_view.c - scene_default_view.h. */
#include "scene/scene_default_view.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene.h"

/* One emitter: an object's triangles of one emissive material, summed. */
typedef struct emitter {
    uint32_t object, material;
    double area, centroid[3], normal[3]; /* centroid: area-weighted sum until the end */
    double power;                        /* max channel of emission x area, for ranking */
} emitter;

static void to_world(const float m[16], const float p[3], double out[3]) {
    for (int r = 0; r < 3; r++)
        out[r] = (double)m[4 * r] * p[0] + (double)m[4 * r + 1] * p[1] +
                 (double)m[4 * r + 2] * p[2] + (double)m[4 * r + 3];
}

static int emits(const rt_material *m) {
    return m->emission[0] > 0.0f || m->emission[1] > 0.0f || m->emission[2] > 0.0f;
}

/* The emitter of (object, material) in list, made when new; NULL when the
 * list is full (cap) or out of memory. */
static emitter *find(emitter **list, uint32_t *count, uint32_t *cap, uint32_t object,
                     uint32_t material) {
    for (uint32_t i = *count; i-- > 0;)
        if ((*list)[i].object == object && (*list)[i].material == material) return &(*list)[i];
    if (*count == *cap) {
        uint32_t grown = *cap ? 2 * *cap : 8;
        emitter *p = realloc(*list, grown * sizeof *p);
        if (!p) return NULL;
        *list = p;
        *cap = grown;
    }
    emitter *e = &(*list)[(*count)++];
    memset(e, 0, sizeof *e);
    e->object = object;
    e->material = material;
    return e;
}

static int by_power(const void *a, const void *b) {
    const emitter *x = a, *y = b;
    return (x->power < y->power) - (x->power > y->power); /* strongest first */
}

rt_status rt_scene_add_emitter_lights(rt_scene *scene, uint32_t *added) {
    *added = 0;
    int any = 0;
    for (uint32_t i = 0; i < scene->material_count; i++) any |= emits(&scene->materials[i]);
    if (!any) return RT_OK;
    float bmin[3], bmax[3];
    if (!rt_scene_bounds(scene, bmin, bmax)) return RT_OK;
    double diag = 0.0;
    for (int k = 0; k < 3; k++) diag += ((double)bmax[k] - bmin[k]) * ((double)bmax[k] - bmin[k]);
    diag = sqrt(diag);
    emitter *list = NULL;
    uint32_t count = 0, cap = 0;
    rt_status st = RT_OK;
    for (uint32_t o = 0; o < scene->object_count && st == RT_OK; o++) {
        const rt_object_data *ob = &scene->objects[o];
        if (!ob->mesh_count) continue;
        const rt_mesh_data *me = &scene->meshes[rt_object_shown_mesh(ob)];
        for (uint32_t t = 0; t < me->triangle_count; t++) {
            uint32_t mat = me->tri_materials && me->tri_materials[t] != UINT32_MAX
                               ? me->tri_materials[t]
                               : ob->material;
            if (mat >= scene->material_count || !emits(&scene->materials[mat])) continue;
            double p[3][3], e1[3], e2[3], n[3];
            for (int v = 0; v < 3; v++)
                to_world(ob->transform, me->positions + 3 * (size_t)me->indices[3 * (size_t)t + v],
                         p[v]);
            for (int k = 0; k < 3; k++) e1[k] = p[1][k] - p[0][k], e2[k] = p[2][k] - p[0][k];
            n[0] = e1[1] * e2[2] - e1[2] * e2[1];
            n[1] = e1[2] * e2[0] - e1[0] * e2[2];
            n[2] = e1[0] * e2[1] - e1[1] * e2[0];
            double area = 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            if (!(area > 0.0) || !isfinite(area)) continue;
            emitter *e = find(&list, &count, &cap, o, mat);
            if (!e) {
                st = RT_ERROR_OUT_OF_MEMORY;
                break;
            }
            e->area += area;
            for (int k = 0; k < 3; k++) {
                e->centroid[k] += area * (p[0][k] + p[1][k] + p[2][k]) / 3.0;
                e->normal[k] += 0.5 * n[k]; /* area-weighted: |n| / 2 is the area */
            }
        }
    }
    if (st == RT_OK && count) {
        for (uint32_t i = 0; i < count; i++) {
            const float *em = scene->materials[list[i].material].emission;
            double m = em[0] > em[1] ? em[0] : em[1];
            list[i].power = (m > em[2] ? m : em[2]) * list[i].area;
        }
        qsort(list, count, sizeof *list, by_power);
        if (count > RT_MAX_EMITTER_LIGHTS) count = RT_MAX_EMITTER_LIGHTS;
        double sum[3] = {0.0, 0.0, 0.0};
        for (uint32_t i = 0; i < count; i++)
            for (int k = 0; k < 3; k++)
                sum[k] += (double)scene->materials[list[i].material].emission[k] * list[i].area;
        double top = sum[0] > sum[1] ? sum[0] : sum[1];
        top = top > sum[2] ? top : sum[2];
        for (uint32_t i = 0; i < count && st == RT_OK; i++) {
            const emitter *e = &list[i];
            double nl = sqrt(e->normal[0] * e->normal[0] + e->normal[1] * e->normal[1] +
                             e->normal[2] * e->normal[2]);
            float pos[3], colour[3];
            for (int k = 0; k < 3; k++) {
                double c = e->centroid[k] / e->area;
                if (nl > 0.0) c += 1e-3 * diag * e->normal[k] / nl;
                pos[k] = (float)c;
                colour[k] =
                    (float)((double)scene->materials[e->material].emission[k] * e->area / top);
            }
            uint32_t id;
            st = rt_light_add(scene, pos, colour, &id);
            if (st == RT_OK) (*added)++;
        }
    }
    free(list);
    return st;
}

rt_status rt_scene_apply_default_view(rt_scene *scene, int width, int height) {
    float bmin[3], bmax[3];
    if (!rt_scene_bounds(scene, bmin, bmax))
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT, "the scene has no triangles");
    float c[3], ext[3];
    for (int k = 0; k < 3; k++) c[k] = 0.5f * (bmin[k] + bmax[k]), ext[k] = bmax[k] - bmin[k];
    float d = sqrtf(rt_scene_dot3(ext, ext));
    if (!isfinite(d)) {
        /* An extent whose square overflows a float (an object scaled by
         * 1e30): its length in double, where it cannot; a scene whose
         * extent itself is not a float has no default view. */
        double e2 = (double)ext[0] * ext[0] + (double)ext[1] * ext[1] + (double)ext[2] * ext[2];
        d = (float)sqrt(e2);
        if (!isfinite(d) || !rt_scene_finite3(ext))
            return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                                 "the scene's bounds (%g, %g, %g) .. (%g, %g, %g) are too large "
                                 "for a default camera: give the scene a camera",
                                 (double)bmin[0], (double)bmin[1], (double)bmin[2], (double)bmax[0],
                                 (double)bmax[1], (double)bmax[2]);
    }
    if (!(d > 0.0f)) d = 1.0f; /* a single point: any distance will do */
    float dir[3] = {0.3f, 0.35f, 1.0f};
    const float len = sqrtf(rt_scene_dot3(dir, dir));
    for (int k = 0; k < 3; k++) dir[k] /= len;
    rt_camera cam;
    for (int k = 0; k < 3; k++) {
        cam.position[k] = c[k] + dir[k] * 0.9f * d;
        cam.look_at[k] = c[k];
    }
    cam.up[0] = 0.0f, cam.up[1] = 1.0f, cam.up[2] = 0.0f;
    cam.hfov_degrees = 60.0f;
    cam.width = width > 0 ? width : 1024;
    cam.height = height > 0 ? height : 576;
    rt_status st = rt_camera_set(scene, &cam);
    if (st == RT_OK && !scene->no_default_light) st = rt_scene_add_default_lights(scene);
    if (st != RT_OK) return st;
    const float ambient[3] = {0.1f, 0.1f, 0.1f};
    return rt_scene_set_ambient(scene, ambient);
}

rt_status rt_scene_add_default_lights(rt_scene *scene) {
    uint32_t added, id;
    rt_status st = rt_scene_add_emitter_lights(scene, &added);
    if (st != RT_OK || added) return st;
    /* One white light on the camera's side of the scene, above and to the
     * right of the eye by 0.3 and 0.2 of the distance to the look-at point:
     * near the viewpoint, it lights most of what the camera sees (a light
     * above the scene's box, as before, lit only the roof of a room seen
     * through an opening, such as the Cornell box), and far enough off the
     * view axis for the shading to show shape. */
    const rt_camera *cam = &scene->camera;
    double f[3], r[3], u[3], dist = 0.0;
    for (int k = 0; k < 3; k++)
        dist += ((double)cam->look_at[k] - cam->position[k]) *
                ((double)cam->look_at[k] - cam->position[k]);
    dist = sqrt(dist);
    if (!rt_camera_frame_d(cam, f, r, u)) return RT_OK; /* rt_camera_set refuses such cameras */
    float light[3];
    for (int k = 0; k < 3; k++)
        light[k] = (float)(cam->position[k] + (0.3 * u[k] + 0.2 * r[k]) * dist);
    const float white[3] = {1.0f, 1.0f, 1.0f};
    return rt_light_add(scene, light, white, &id);
}
