/* SPDX-License-Identifier: Apache-2.0 */
/* gltf_module.h - the interface between the library and its glTF module
 * (librtcl_gltf.so, host/gltf/gltf_module.cpp), which reads .gltf and .glb
 * files through tinygltf and hands back their content as plain C arrays.
 *
 * The module is loaded with dlopen on the first glTF file
 * (formats/gltf_load.c), so that programs that never read one do not map
 * tinygltf and the C++ runtime. It exports one symbol,
 * RT_GLTF_MODULE_SYMBOL, returning the table below. It calls nothing in the
 * library (base/error.c is built into it).
 *
 * What the module does: parses the file (buffers from the file itself, from
 * data: URIs, or from files inside the file's own folder: a URI that leaves
 * the folder, or names a directory, a FIFO or any other non-regular file,
 * is refused), decodes every accessor the scene uses into floats or
 * integers (every component type, normalized integers, sparse accessors,
 * byte strides; every read checked against its buffer view and buffer),
 * turns strips and fans into triangle lists. What it leaves to the library
 * (formats/gltf_load.c, gltf_eval.c): every index between objects (node
 * children, meshes, skins, joints, animation targets) is passed as it is in
 * the file and checked there, as are the node graph (cycles), vertex indices
 * and keyframe times. */
#ifndef RT_GLTF_MODULE_H
#define RT_GLTF_MODULE_H

#include <stddef.h>
#include <stdint.h>

#include "rt.h"

#ifdef __cplusplus
extern "C" {
#endif

#define RT_GLTF_MODULE_ABI    1
#define RT_GLTF_MODULE_FILE   "librtcl_gltf.so"
#define RT_GLTF_MODULE_SYMBOL "rtcl_gltf_module"

#define RT_GLTF_NONE (-1)

typedef struct rt_gltf_prim {
    int32_t material;        /* index into materials, or RT_GLTF_NONE */
    uint32_t vertex_count;   /* the POSITION accessor's count */
    float *positions;        /* 3 per vertex */
    float *normals;          /* 3 per vertex, or NULL */
    uint32_t triangle_count; /* after strips and fans became lists */
    uint32_t *indices;       /* 3 per triangle, as in the file (unchecked) */
    uint32_t joint_sets;     /* 0, 1 or 2 sets of JOINTS_n / WEIGHTS_n */
    uint32_t *joints;        /* 4 * joint_sets per vertex (unchecked) */
    float *weights;          /* 4 * joint_sets per vertex */
    uint32_t target_count;   /* morph targets */
    float *target_positions; /* 3 per vertex per target, target-major; 0 where absent */
    float *target_normals;   /* the same for NORMAL, or NULL */
} rt_gltf_prim;

typedef struct rt_gltf_mesh {
    char name[96];
    uint32_t prim_count; /* the triangle primitives only */
    rt_gltf_prim *prims;
    uint32_t skipped_prims; /* points and lines, left out */
    uint32_t weight_count;
    float *weights; /* the mesh's default morph weights, or NULL */
} rt_gltf_mesh;

typedef struct rt_gltf_node {
    char name[96];
    int has_matrix;
    double matrix[16];     /* column-major, as in the file */
    double translation[3]; /* TRS (defaults where absent) */
    double rotation[4];    /* x y z w */
    double scale[3];
    int32_t mesh, skin, camera, light; /* RT_GLTF_NONE when absent */
    uint32_t child_count;
    int32_t *children;
    uint32_t weight_count;
    float *weights; /* node weights, overriding the mesh's, or NULL */
} rt_gltf_node;

typedef struct rt_gltf_skin {
    uint32_t joint_count;
    int32_t *joints;      /* node indices (unchecked) */
    double *inverse_bind; /* 16 per joint, column-major (identity where absent) */
} rt_gltf_skin;

enum { RT_GLTF_LINEAR = 0, RT_GLTF_STEP = 1, RT_GLTF_CUBICSPLINE = 2 };
enum {
    RT_GLTF_PATH_TRANSLATION = 0,
    RT_GLTF_PATH_ROTATION,
    RT_GLTF_PATH_SCALE,
    RT_GLTF_PATH_WEIGHTS
};

typedef struct rt_gltf_sampler {
    int interpolation;
    uint32_t key_count;
    float *times;         /* key_count */
    uint32_t value_count; /* elements of the output accessor */
    uint32_t components;  /* floats per element (1 scalar, 3, 4) */
    float *values;        /* value_count * components */
    char where[64];       /* its JSON pointer, "/animations/0/samplers/3" */
} rt_gltf_sampler;

typedef struct rt_gltf_channel {
    int32_t node;    /* RT_GLTF_NONE: no target node (ignored) */
    int path;        /* RT_GLTF_PATH_*, or -1: a path we do not play (ignored) */
    int32_t sampler; /* index into the animation's samplers (unchecked) */
} rt_gltf_channel;

typedef struct rt_gltf_animation {
    char name[96];
    uint32_t channel_count;
    rt_gltf_channel *channels;
    uint32_t sampler_count;
    rt_gltf_sampler *samplers;
} rt_gltf_animation;

typedef struct rt_gltf_material {
    double base_color[4];
    double metallic, roughness;
    double emissive[3];
    int textured; /* some texture is referenced */
} rt_gltf_material;

typedef struct rt_gltf_camera {
    int perspective;     /* 0: orthographic */
    double yfov, aspect; /* aspect 0 when absent */
} rt_gltf_camera;

enum {
    RT_GLTF_LIGHT_POINT = 0,
    RT_GLTF_LIGHT_SPOT,
    RT_GLTF_LIGHT_DIRECTIONAL,
    RT_GLTF_LIGHT_OTHER
};

typedef struct rt_gltf_light {
    int type;
    double color[3];
    double intensity;
} rt_gltf_light;

typedef struct rt_gltf_doc {
    uint32_t node_count, mesh_count, skin_count, animation_count;
    uint32_t material_count, camera_count, light_count, texture_count;
    rt_gltf_node *nodes;
    rt_gltf_mesh *meshes;
    rt_gltf_skin *skins;
    rt_gltf_animation *animations;
    rt_gltf_material *materials;
    rt_gltf_camera *cameras;
    rt_gltf_light *lights;
    uint32_t root_count;
    int32_t *roots;     /* the default scene's (or the first scene's) nodes */
    char warnings[512]; /* tinygltf's warnings, one line, or "" */
} rt_gltf_doc;

typedef struct rt_gltf_module {
    int abi;             /* RT_GLTF_MODULE_ABI of the module's build */
    size_t doc_size;     /* sizeof(rt_gltf_doc) there */
    size_t error_size;   /* sizeof(rt_error) there */
    const char *library; /* "tinygltf 2.7" */
    /* Reads path (.gltf or .glb by its extension) into *out (allocated;
     * rt_gltf_free). On failure err names the file and, where it can, the
     * JSON pointer of what is wrong; *out is NULL. */
    rt_status (*read)(const char *path, rt_gltf_doc **out, rt_error *err);
    void (*free_doc)(rt_gltf_doc *doc);
} rt_gltf_module;

typedef const rt_gltf_module *(*rt_gltf_module_entry)(void);

/* The module on first use, NULL when it cannot be had (err says why:
 * which file, where looked, what to install). Thread-safe. Defined in
 * formats/gltf_module_load.c. */
const rt_gltf_module *rt_gltf_module_get(rt_error *err);

#ifdef __cplusplus
}
#endif
#endif /* RT_GLTF_MODULE_H */
