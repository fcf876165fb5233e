/* SPDX-License-Identifier: Apache-2.0 */
/* scene.h - the scene model behind rt.h (Langr 2016, section 3.2).
 *
 * Plain growable arrays. Every input is validated on its way in (rt.h calls
 * and loaders), so code that reads a scene may trust it: ids are in range,
 * coordinates are finite, indices point at vertices.
 */
#ifndef RT_SCENE_H
#define RT_SCENE_H

#include <math.h>
#include <stdint.h>

#include "rt.h"

typedef struct rt_mesh_data {
    char name[128];   /* where it came from (file name), for messages */
    float *positions; /* 3 per vertex */
    float *normals;   /* 3 per vertex, or NULL */
    uint32_t vertex_count;
    uint32_t vertex_capacity;
    uint32_t *indices; /* 3 per triangle */
    uint32_t triangle_count;
    uint32_t triangle_capacity;
    /* Per-triangle material id overriding the object's, or NULL.
     * UINT32_MAX entries use the object's material. */
    uint32_t *tri_materials;
    /* Bumped by every change of the mesh's geometry, so that a renderer
     * knows when its BVH is stale. */
    uint32_t version;
    uint32_t accel; /* rt_accel: the structure a renderer builds for it */
    /* Bumped when triangles are added (not when vertices move): a BVH of the
     * same topology version may be refitted. */
    uint32_t topology_version;
    uint32_t update_policy; /* rt_update_policy */
    /* 1: the blend mesh the scene made for a morphing object (never saved:
     * the loader makes it again); it stays, emptied, when that object is
     * removed, so that the other meshes keep their ids. */
    int blend;
} rt_mesh_data;

typedef struct rt_object_data {
    uint32_t *meshes; /* keyframes */
    uint32_t mesh_count;
    uint32_t mesh_capacity;
    uint32_t selected; /* index into meshes */
    uint32_t material;
    uint32_t mask;       /* rt_object_set_mask's, 0xffffffff unless set */
    float transform[16]; /* object to world, row-major, p' = M p */
    float pending[16];   /* queued transforms, composed; identity when none */
    int has_pending;
    /* Animation (rt_object_set_animation): keyframe_rate 0 when none. */
    float keyframe_rate;
    int interpolate;
    uint32_t morph_mesh; /* the scene mesh holding the blend, UINT32_MAX: none yet */
    int morphing;        /* 1: morph_mesh is shown instead of meshes[selected] */
    rt_transform_key *transform_keys;
    uint32_t transform_key_count;
} rt_object_data;

/* The mesh an object shows: its selected keyframe, or its blend while it
 * morphs between keyframes. Every reader of a scene goes through this. */
/* Float vector helpers of the scene code (scene.c, scene_default_view.c):
 * every component finite; a . b summed left to right. */
static inline int rt_scene_finite3(const float v[3]) {
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}
static inline float rt_scene_dot3(const float a[3], const float b[3]) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline uint32_t rt_object_shown_mesh(const rt_object_data *o) {
    return o->morphing ? o->morph_mesh : o->meshes[o->selected];
}

typedef struct rt_light_data {
    float position[3];
    float color[3];
} rt_light_data;

/* An animation a loader keeps in the scene (formats/gltf_load.c: a glTF
 * file's clips): rt_scene_set_time calls set_time after the scene's own
 * keyframes and keys, and rt_scene_destroy calls destroy. state is the
 * loader's; NULL set_time: none. The clip calls back the rt.h functions
 * rt_scene_clip_count, rt_scene_clip_info and rt_scene_select_clip. */
typedef struct rt_scene_animator {
    void *state;
    rt_status (*set_time)(rt_scene *scene, void *state, double seconds);
    void (*destroy)(void *state);
    uint32_t (*clip_count)(const void *state);
    /* name and duration of clip index (< clip_count) */
    void (*clip_info)(const void *state, uint32_t index, const char **name, double *duration);
    /* plays clip index from now on (the scene's time is evaluated again) */
    rt_status (*select_clip)(rt_scene *scene, void *state, uint32_t index);
    uint32_t selected;
    int animated; /* 1: set_time changes something (rt_scene_is_animated) */
} rt_scene_animator;

struct rt_scene {
    rt_mesh_data *meshes;
    uint32_t mesh_count, mesh_capacity;
    rt_material *materials;
    uint32_t material_count, material_capacity;
    rt_light_data *lights;
    uint32_t light_count, light_capacity;
    rt_object_data *objects;
    uint32_t object_count, object_capacity;
    float ambient[3];
    float background[3];
    float exposure; /* rt_scene_set_exposure: stops, 0 by default */
    rt_camera camera;
    int has_camera;
    rt_camera_key *camera_path; /* rt_camera_set_path, or NULL */
    uint32_t camera_path_count;
    double time; /* the last rt_scene_set_time */
    /* rt_scene_load_options.no_default_light: rt_scene_apply_default_view
     * adds no light. */
    int no_default_light;
    uint32_t version; /* bumped by every change, so renderers know what to redo */
    /* Bumped by rt_camera_set (and so by the camera path), not version: a
     * camera-only change rewrites the layout's header and nothing else. */
    uint32_t camera_version;
    /* Unique among the scenes of the process (never reused), so that a
     * renderer given another scene knows its caches are not this one's. */
    uint64_t uid;
    char source[512];           /* the file it was loaded from, or "" */
    char *notices;              /* rt_scene_notices: lines, or NULL when none */
    rt_scene_animator animator; /* a loader's animation, zero: none */
    /* rt_scene_set_threads: the threads of the scene's own per-frame work
     * (<= 0: all cores), and their pool, made when first needed. */
    int threads;
    struct rt_pool *pool;
    rt_error error; /* the last error of a call that edited the scene */
};

/* The pool of the scene's per-frame work (rt_scene_set_threads), made on
 * first use; NULL for one thread, or when no thread could be made (then the
 * work runs on the caller's thread). */
struct rt_pool *rt_scene_pool(rt_scene *scene);

/* Identity matrix. */
void rt_mat4_identity(float m[16]);
/* out = a * b (out may alias neither). */
void rt_mat4_mul(const float a[16], const float b[16], float out[16]);
/* Is m exactly the identity? */
int rt_transform_is_identity(const float m[16]);
/* Inverse of an affine matrix (last row 0 0 0 1); returns 0 if singular. */
int rt_mat4_affine_inverse(const float m[16], float out[16]);

/* Adds a line to the scene's notices (rt_scene_notices); dropped when out
 * of memory (a notice is no failure). */
void rt_scene_add_notice(rt_scene *scene, const char *text);

/* Frees the arrays a mesh owns (positions, normals, indices, per-triangle
 * materials) and sets them to NULL; counts and capacities are the caller's. */
void rt_mesh_data_free_arrays(rt_mesh_data *m);

/* Sets the scene's error and returns status. */
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
rt_status
rt_scene_fail(rt_scene *scene, rt_status status, const char *fmt, ...);

/* RT_OK when the vertex_count positions (and normals, when not NULL) of
 * mesh mesh_id are finite; else the scene's error naming the first that is
 * not (rt_mesh_add_triangles, rt_mesh_set_positions). */
rt_status rt_scene_check_finite(rt_scene *scene, uint32_t mesh_id, const float *positions,
                                const float *normals, uint32_t vertex_count);

/* Limits on meshes (docs/ROBUSTNESS.md, "Limits"): beyond them
 * rt_mesh_add_triangles fails with RT_ERROR_UNSUPPORTED naming the limit.
 * The layout's indices are 32-bit and a leaf's count has 31 bits; these
 * leave room for the BVH's nodes (about 2 per triangle) in 32 bits. */
#define RT_MAX_MESH_TRIANGLES  ((uint64_t)1 << 28) /* per mesh */
#define RT_MAX_MESH_VERTICES   ((uint64_t)1 << 28) /* per mesh */
#define RT_MAX_SCENE_TRIANGLES ((uint64_t)1 << 29) /* over all the scene's meshes */

/* The largest image side in pixels (camera width and height); a 32768 x
 * 32768 framebuffer of 4 float channels is 16 GiB. */
#define RT_MAX_IMAGE_SIDE 32768
/* The largest colour or intensity component (material colours and their
 * ambient, diffuse and specular factors, light colours, the ambient light,
 * the background): products of a few such values and their sums over
 * lights and bounces stay far below float's limit, so no pixel becomes
 * infinite. Beyond it (or below 0, or not finite) is refused. */
#define RT_MAX_COLOUR 1e6f

/* The camera's orthonormal frame in double, as the layout stores it
 * (host/layout/flatten.c): forward f, right r = f x up / |f x up|, up u =
 * r x f. Returns 0, leaving the outputs undefined, when the frame is not
 * finite or up is within RT_CAMERA_MIN_SINE of the view direction (sine of
 * the angle): rt_camera_set refuses such cameras, so every accepted camera
 * gives finite rays. */
#define RT_CAMERA_MIN_SINE 1e-6
int rt_camera_frame_d(const rt_camera *c, double f[3], double r[3], double u[3]);

/* Total triangles over the selected keyframe of every object. */
uint64_t rt_scene_triangle_count(const rt_scene *scene);

/* The one rule for a mesh's structure: the kd-tree its accel asks for only
 * while it is static (update policy sah); any other policy deforms the mesh,
 * which keeps a BVH (refittable) whatever its accel says. rt_mesh_accel and
 * the renderer's cache both ask this. */
rt_accel rt_mesh_data_structure(const rt_mesh_data *m);

/* rt_scene_bounds, the world-space box of the current frame, is public (rt.h). */

/* Which features the scene uses; backends specialise to these. */
typedef struct rt_scene_features {
    int reflection;    /* some material has reflectivity > 0 */
    int refraction;    /* some material has transparency > 0 */
    int instancing;    /* more than one object, or a non-identity transform */
    int normals;       /* some mesh has per-vertex normals */
    int keyframes;     /* some object has more than one mesh */
    int tri_materials; /* some mesh has per-triangle materials */
} rt_scene_features;

rt_scene_features rt_scene_features_of(const rt_scene *scene);

#endif /* RT_SCENE_H */
