/* rt_layout.h - the flattened scene layout, shared by the host, the CPU oracle
 * and the OpenCL kernels.
 *
 * This header is valid C99 and valid OpenCL C. It holds plain structs of
 * 32-bit scalars only (no float3: its 16-byte alignment differs between C and
 * OpenCL), so that the bytes the host writes are the bytes every backend reads.
 */
#ifndef RT_LAYOUT_H
#define RT_LAYOUT_H

#ifdef __OPENCL_VERSION__
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

#endif /* RT_LAYOUT_H */
