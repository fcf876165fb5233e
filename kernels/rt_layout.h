/* SPDX-License-Identifier: Apache-2.0 */
/* rt_layout.h - the flattened scene layout, shared by the host, the CPU oracle
 * and the OpenCL kernels.
 *
 * This header is valid C99 and valid OpenCL C. It holds plain structs of
 * 32-bit scalars only (no float3: its 16-byte alignment differs between C and
 * OpenCL), so that the bytes the host writes are the bytes every backend reads.
 */
#ifndef RT_LAYOUT_H
#define RT_LAYOUT_H

#if defined(__OPENCL_VERSION__) || defined(__OPENCL_C_VERSION__)
#define RT_OPENCL 1
typedef uint rt_u32;
typedef int rt_i32;
#else
#include <stdint.h>
typedef uint32_t rt_u32;
typedef int32_t rt_i32;
#endif

/* Bit 31 of rt_node.b marks a leaf; the low 31 bits are then the count. */
#define RT_NODE_LEAF_FLAG  0x80000000u
#define RT_NODE_COUNT_MASK 0x7fffffffu

/* The thesis's 32-byte BVH node (Langr 2016, section 3.4).
 * Inner node: a = index of the left child, b = index of the right child.
 * Leaf:       a = first entry in the primitive index array,
 *             b = primitive count | RT_NODE_LEAF_FLAG.
 * The root is node 0. */
typedef struct rt_node {
    float bmin[3];
    float bmax[3];
    rt_u32 a;
    rt_u32 b;
} rt_node;

/* One triangle as three vertices, stored in the order the BVH leaves
 * reference them (36 bytes). */
typedef struct rt_tri {
    float v0[3];
    float v1[3];
    float v2[3];
} rt_tri;

/* ---- the flattened scene (host/flatten.c writes it, backends read it) ----
 *
 * Arrays, each indexed as described; all node and triangle indices are
 * absolute (the host has already added each mesh's base):
 *   nodes        every mesh BVH, then the object BVH; leaves of a mesh BVH
 *                reference 'tris' directly (entry a .. a+count-1), leaves of
 *                the object BVH reference 'inst_ids'.
 *   tris         triangles of every used mesh in the leaf order of its BVH.
 *   tri_ids      per entry of 'tris': the triangle's 0-based index in its
 *                mesh (file order), reported as 'prim'.
 *   tri_normals  per entry of 'tris': 9 floats (vertex normals n0, n1, n2),
 *                only when some mesh has normals (else empty).
 *   tri_mats     per entry of 'tris': a material overriding the instance's,
 *                RT_NO_MATERIAL for none; only when some mesh has them.
 *   instances    one per scene object, in object order ('inst').
 *   inst_ids     leaf entries of the object BVH -> instance index.
 *   materials, lights.
 * A degenerate triangle (edge cross product exactly zero) is stored with all
 * three vertices equal to v0, which every triangle test rejects. */

#define RT_NO_MATERIAL 0xffffffffu

/* Instance flags. */
#define RT_INST_IDENTITY 1u /* object-to-world is the identity: no ray transform */
#define RT_INST_NORMALS  2u /* the mesh has per-vertex normals */
#define RT_INST_KD       4u /* the mesh has a kd-tree: see rt_kd_node */

typedef struct rt_instance {
    float world_to_object[12]; /* rows 0..2 of the inverse matrix, row-major */
    float object_to_world[12]; /* rows 0..2 of the matrix, row-major */
    rt_u32 root;               /* index of the mesh BVH's root node */
    rt_u32 material;
    rt_u32 flags;
    rt_u32 mesh;      /* the scene's mesh id (for information) */
    rt_u32 tri_first; /* the mesh's entries in tris: tri_first .. + tri_count - 1 */
    rt_u32 tri_count;
    /* The world box the object BVH was built over (its leaves hold one
     * instance each): a hit must lie in its slabs (rt_hit_accepted). */
    float bmin[3];
    float bmax[3];
    /* The object's ray mask (rt_object_set_mask, 0xffffffff unless set): a
     * ray of mask m skips the instance when (m & mask) == 0 (rt_trace). */
    rt_u32 mask;
} rt_instance;

typedef struct rt_material_d {
    float color[3];
    float ambient;
    float diffuse;
    float specular;
    rt_i32 shininess;
    float reflectivity;
    float transparency;
    float ior;
    float emission[3]; /* light the surface gives off, added before the lights (rt_phong_ambient) */
} rt_material_d;

typedef struct rt_light_d {
    float position[3];
    float color[3];
} rt_light_d;

/* Triangle tests (rt_scene_header.tri_method). */
#define RT_TRI_WATERTIGHT 0 /* Woop, Benthin, Wald 2013 (the default) */
#define RT_TRI_MOLLER     1 /* Moller-Trumbore 1997 */
#define RT_TRI_PLUECKER   2 /* signed volumes (Pluecker coordinates) */
#define RT_TRI_BADOUEL    3 /* plane hit, then 2D test on a projection (Badouel; Wald) */

/* Scene header flags: what the scene uses ("model only what a scene needs"). */
#define RT_SCENE_SECONDARY 1u /* some material reflects or refracts */
#define RT_SCENE_SINGLE    2u /* one identity instance: skip the object BVH */
#define RT_SCENE_NORMALS   4u /* tri_normals present */
#define RT_SCENE_TRI_MATS  8u /* tri_mats present */

/* Camera, computed by the host (rt_flatten) from rt_camera. The primary ray
 * through pixel (px, py), px to the right and py down from the top-left:
 *   sx = (2 * (px + 0.5)) / width - 1
 *   sy = 1 - (2 * (py + 0.5)) / height
 *   dir[i] = (forward[i] + sx * right[i]) + sy * up[i]
 * with forward the unit view direction, right = unit right * tan(hfov / 2) and
 * up = unit up * tan(hfov / 2) * height / width; org = position; the ray's
 * t range is [0, inf]. Every backend evaluates exactly this (rt_camera_ray in
 * rt_camera.h). */
/* The most reflection/refraction bounces (rt_scene_header.max_depth):
 * host/layout/flatten.c caps a scene's at this, and the shading stack
 * (RT_SHADE_STACK, rt_shade.h) is sized for it. */
#define RT_MAX_DEPTH 8

typedef struct rt_scene_header {
    rt_u32 flags;
    rt_u32 top_root; /* root node of the object BVH */
    rt_u32 instance_count;
    rt_u32 light_count;
    rt_u32 material_count;
    rt_u32 tri_method; /* RT_TRI_* */
    rt_u32 max_depth;  /* reflection/refraction bounces */
    rt_i32 width;
    rt_i32 height;
    float min_weight; /* contribution cutoff for secondary rays */
    float ambient[3];
    float background[3];
    float cam_pos[3];
    float cam_forward[3];
    float cam_right[3];
    float cam_up[3];
} rt_scene_header;

/* ---- kd-trees (host/accel/kd.h builds them, kernels/rt_kd.h traverses) ----
 *
 * A mesh with a kd-tree (instance flag RT_INST_KD) has one rt_node in 'nodes'
 * at the instance's root: its box is the tree's root cell and a is the index
 * of the tree's root in 'kd_nodes'; b is RT_NODE_LEAF_FLAG with count 0, so
 * code that knows only BVHs sees an empty mesh, never a wrong index.
 * kd nodes (8 bytes, Wald 2004) are in depth-first order:
 *   inner: a = the split position's float bits, b = (right child << 2) | axis;
 *          the left child is the next node;
 *   leaf:  a = first entry in 'tris', b = (entry count << 2) | RT_KD_LEAF.
 * A triangle that straddles leaves has one entry in 'tris' per leaf (with
 * its tri_ids, tri_normals and tri_mats entries), so a leaf is a range of
 * entries like a BVH leaf and is tested by the same code. */
#define RT_KD_LEAF 3u

typedef struct rt_kd_node {
    rt_u32 a;
    rt_u32 b;
} rt_kd_node;

#endif /* RT_LAYOUT_H */
