/* SPDX-License-Identifier: Apache-2.0 */
/* rt_vk_layout.glsl - the GLSL mirror of kernels/rt_layout.h: the flattened
 * scene's structs (std430 puts them at C's offsets) and flags. */
#ifndef RT_VK_LAYOUT_GLSL
#define RT_VK_LAYOUT_GLSL

#define RT_NO_MATERIAL     0xffffffffu
#define RT_NODE_LEAF_FLAG  0x80000000u
#define RT_NODE_COUNT_MASK 0x7fffffffu
#define RT_INST_IDENTITY   1u
#define RT_INST_NORMALS    2u
#define RT_TRI_WATERTIGHT  0u
#define RT_TRI_MOLLER      1u
#define RT_TRI_PLUECKER    2u
#define RT_TRI_BADOUEL     3u
#define RT_SCENE_SECONDARY 1u
#define RT_SCENE_SINGLE    2u
#define RT_SCENE_NORMALS   4u
#define RT_SCENE_TRI_MATS  8u
#define RT_INST_KD         4u
#define RT_KD_LEAF         3u

struct rt_node {
    float bmin[3];
    float bmax[3];
    uint a;
    uint b;
};
struct rt_tri {
    float v0[3];
    float v1[3];
    float v2[3];
};
struct rt_instance {
    float world_to_object[12];
    float object_to_world[12];
    uint root;
    uint material;
    uint flags;
    uint mesh;
    uint tri_first;
    uint tri_count;
    float bmin[3];
    float bmax[3];
    uint mask;
};
struct rt_material_d {
    float color[3];
    float ambient;
    float diffuse;
    float specular;
    int shininess;
    float reflectivity;
    float transparency;
    float ior;
    float emission[3];
};
struct rt_light_d {
    float position[3];
    float color[3];
};
struct rt_scene_header {
    uint flags;
    uint top_root;
    uint instance_count;
    uint light_count;
    uint material_count;
    uint tri_method;
    uint max_depth;
    int width;
    int height;
    float min_weight;
    float ambient[3];
    float background[3];
    float cam_pos[3];
    float cam_forward[3];
    float cam_right[3];
    float cam_up[3];
};
struct rt_kd_node {
    uint a;
    uint b;
};

#endif
