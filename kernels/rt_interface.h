/* SPDX-License-Identifier: Apache-2.0 */
/* rt_interface.h - the C side of the GPU interface table (rt_interface.def):
 * the buffer slots of both backends, the Vulkan push constants and
 * specialization constants, the AOV codes and the shared numbers, each
 * expanded from the table's rows. Valid C99 and OpenCL C (the OpenCL kernels
 * take the AOV codes from here). The OpenCL kernel arguments are
 * rt_kernel_arg_index.h's; the GLSL side is generated
 * (kernels/vulkan/gen_interface.c). */
#ifndef RT_KERNELS_INTERFACE_H
#define RT_KERNELS_INTERFACE_H

#include "rt_layout.h"

/* The scene view's arrays, arguments 0..10 of every tracing OpenCL kernel,
 * in rt_scene_view's order. */
#include "rt_interface_rows.h"
#undef RT_VIEW_BUFFER
#define RT_VIEW_BUFFER(ID, name, type, form, binding, what) RT_ARG_##ID,
enum {
#include "rt_interface.def"
    RT_ARG_VIEW_COUNT
};

/* The OpenCL backend's buffers: the view's (as their arguments), the
 * per-dispatch ones, then its own. */
#include "rt_interface_rows.h"
#undef RT_VIEW_BUFFER
#undef RT_IO_BUFFER
#undef RT_CL_BUFFER
#define RT_VIEW_BUFFER(ID, name, type, form, binding, what) RT_CL_BUF_##ID,
#define RT_IO_BUFFER(ID, name, type, access, binding, what) RT_CL_BUF_##ID,
#define RT_CL_BUFFER(ID, what)                              RT_CL_BUF_##ID,
enum {
#include "rt_interface.def"
    RT_CL_BUF_COUNT
};

/* The OpenCL kernels, in the table's order: each kernel's completion
 * counter in the DONE buffer (done[RT_CL_DONE_<KERNEL>], the work-items that
 * reached their end). */
#include "rt_interface_rows.h"
#undef RT_CL_KERNEL
#define RT_CL_KERNEL(ID, name, view) RT_CL_DONE_##ID,
enum {
#include "rt_interface.def"
    RT_CL_DONE_COUNT
};

/* The Vulkan backend's buffers, each numbered by its binding; the bindings
 * are 0 .. RT_VK_BUF_COUNT - 1 (test_vulkan_interface checks it). */
#include "rt_interface_rows.h"
#undef RT_VIEW_BUFFER
#undef RT_IO_BUFFER
#undef RT_VK_BUFFER
#define RT_VIEW_BUFFER(ID, name, type, form, binding, what) RT_VK_BUF_##ID = (binding),
#define RT_IO_BUFFER(ID, name, type, access, binding, what) RT_VK_BUF_##ID = (binding),
#define RT_VK_BUFFER(ID, name, type, binding, what)         RT_VK_BUF_##ID = (binding),
enum {
#include "rt_interface.def"
};
#include "rt_interface_rows.h"
#undef RT_VIEW_BUFFER
#undef RT_IO_BUFFER
#undef RT_VK_BUFFER
#define RT_VIEW_BUFFER(ID, name, type, form, binding, what) +1
#define RT_IO_BUFFER(ID, name, type, access, binding, what) +1
#define RT_VK_BUFFER(ID, name, type, binding, what)         +1
enum {
    RT_VK_BUF_COUNT = 0
#include "rt_interface.def"
};

/* The push constants of every Vulkan shader (Push in the generated
 * rt_vk_interface.glsl). */
#define RT_IF_U32 rt_u32
#define RT_IF_I32 rt_i32
#include "rt_interface_rows.h"
#undef RT_PUSH
#define RT_PUSH(type, name) RT_IF_##type name;
typedef struct rt_vk_push {
#include "rt_interface.def"
} rt_vk_push;

/* The specialization constants' ids (constant_id) and defaults. */
#include "rt_interface_rows.h"
#undef RT_SPEC
#define RT_SPEC(NAME, id, value) RT_VK_SPEC_##NAME = (id),
enum {
#include "rt_interface.def"
};
#include "rt_interface_rows.h"
#undef RT_SPEC
#define RT_SPEC(NAME, id, value) +1
enum {
    RT_VK_SPEC_COUNT = 0
#include "rt_interface.def"
};
#include "rt_interface_rows.h"
#undef RT_SPEC
#define RT_SPEC(NAME, id, value) RT_VK_SPEC_DEFAULT_##NAME = (value),
enum {
#include "rt_interface.def"
};

/* The AOV codes (rt_aov in rt.h). */
#include "rt_interface_rows.h"
#undef RT_AOV
#define RT_AOV(NAME, code) AOV_##NAME = (code),
enum {
#include "rt_interface.def"
};

/* The shared numbers, RT_NAME. */
#include "rt_interface_rows.h"
#undef RT_CONST
#define RT_CONST(NAME, value) RT_##NAME = (value),
enum {
#include "rt_interface.def"
};

#ifndef RT_OPENCL
/* What error messages call OpenCL buffer b (RT_CL_BUF_*). */
static inline const char *rt_cl_buffer_what(int b) {
#include "rt_interface_rows.h"
#undef RT_VIEW_BUFFER
#undef RT_IO_BUFFER
#undef RT_CL_BUFFER
#define RT_VIEW_BUFFER(ID, name, type, form, binding, what)                                        \
    if (b == RT_CL_BUF_##ID) return what;
#define RT_IO_BUFFER(ID, name, type, access, binding, what)                                        \
    if (b == RT_CL_BUF_##ID) return what;
#define RT_CL_BUFFER(ID, what)                                                                     \
    if (b == RT_CL_BUF_##ID) return what;
#include "rt_interface.def"
    return "?";
}

/* The name of the OpenCL kernel RT_CL_DONE_<KERNEL> = k. */
static inline const char *rt_cl_kernel_name(int k) {
#include "rt_interface_rows.h"
#undef RT_CL_KERNEL
#define RT_CL_KERNEL(ID, name, view)                                                               \
    if (k == RT_CL_DONE_##ID) return #name;
#include "rt_interface.def"
    return "?";
}

/* What error messages call the Vulkan buffer at binding b (RT_VK_BUF_*). */
static inline const char *rt_vk_buffer_what(int b) {
#include "rt_interface_rows.h"
#undef RT_VIEW_BUFFER
#undef RT_IO_BUFFER
#undef RT_VK_BUFFER
#define RT_VIEW_BUFFER(ID, name, type, form, binding, what)                                        \
    if (b == RT_VK_BUF_##ID) return what;
#define RT_IO_BUFFER(ID, name, type, access, binding, what)                                        \
    if (b == RT_VK_BUF_##ID) return what;
#define RT_VK_BUFFER(ID, name, type, binding, what)                                                \
    if (b == RT_VK_BUF_##ID) return what;
#include "rt_interface.def"
    return "?";
}

/* The specialization constants' defaults, by constant_id. */
static inline void rt_vk_spec_defaults(rt_u32 spec[RT_VK_SPEC_COUNT]) {
#include "rt_interface_rows.h"
#undef RT_SPEC
#define RT_SPEC(NAME, id, value) spec[RT_VK_SPEC_##NAME] = (value);
#include "rt_interface.def"
}
#endif

#include "rt_interface_rows.h"

#endif /* RT_KERNELS_INTERFACE_H */
