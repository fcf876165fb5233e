/* SPDX-License-Identifier: Apache-2.0 */
/* rt_kernel_arg_index.h - the position of every argument of every OpenCL
 * kernel (kernels/rt_single_ray.cl, kernels/rt_ray_packet.cl), from the
 * kernel rows of the GPU interface table (rt_interface.def): the host sets
 * arguments by these names (host/opencl/cl_backend.c), and a test holds
 * them to the kernels' signatures (tests/test_opencl_kernel_args.c asks the
 * built program for each argument's name and the view arguments' types).
 * Valid C and OpenCL C.
 *
 * Tracing kernels start with the eleven arrays of the scene view (RT_ARG_*
 * of rt_interface.h, RT_VIEW_ARGS in rt_kernel_args.h), in the order of
 * rt_scene_view; RT_K_<KERNEL>_<ARG> is the position of each further
 * argument and RT_K_<KERNEL>_ARGS the argument count. */
#ifndef RT_KERNEL_ARG_INDEX_H
#define RT_KERNEL_ARG_INDEX_H

#include "rt_interface.h"

#define RT_CL_VIEW    RT_ARG_VIEW_COUNT
#define RT_CL_NO_VIEW 0

/* One enum per kernel: a hidden first enumerator one before the kernel's
 * first own argument, then the arguments, then the count. */
#include "rt_interface_rows.h"
#undef RT_CL_KERNEL
#undef RT_CL_ARG
#undef RT_CL_KERNEL_END
#define RT_CL_KERNEL(ID, name, view) enum { RT_K_##ID##_BEFORE_ = RT_CL_##view - 1,
#define RT_CL_ARG(KERNEL, ARG, name) RT_K_##KERNEL##_##ARG,
#define RT_CL_KERNEL_END(ID)                                                                       \
    RT_K_##ID##_ARGS                                                                               \
    }                                                                                              \
    ;
#include "rt_interface.def"

#ifdef RT_KERNEL_SIGNATURES
/* The argument names of each kernel in signature order, for the test that
 * holds the kernels to the table (defined there only). */
typedef struct rt_kernel_signature {
    const char *kernel;
    int view;              /* 1: the view arguments come first */
    int args;              /* the argument count (the *_ARGS enum) */
    const char *names[20]; /* after the view's */
} rt_kernel_signature;

/* The view arguments' names and element types. */
#include "rt_interface_rows.h"
#undef RT_VIEW_BUFFER
#define RT_VIEW_BUFFER(ID, name, type, form, binding, what) #name,
static const char *const rt_kernel_view_names[RT_ARG_VIEW_COUNT] = {
#include "rt_interface.def"
};
#include "rt_interface_rows.h"
#undef RT_VIEW_BUFFER
#define RT_VIEW_BUFFER(ID, name, type, form, binding, what) #type,
static const char *const rt_kernel_view_types[RT_ARG_VIEW_COUNT] = {
#include "rt_interface.def"
};

#include "rt_interface_rows.h"
#undef RT_CL_KERNEL
#undef RT_CL_ARG
#undef RT_CL_KERNEL_END
#define RT_CL_KERNEL(ID, name, view)                                                               \
    {                                                                                              \
#name, RT_CL_##view != 0, RT_K_##ID##_ARGS, {
#define RT_CL_ARG(KERNEL, ARG, name) #name,
#define RT_CL_KERNEL_END(ID)                                                                       \
    }                                                                                              \
    }                                                                                              \
    ,
static const rt_kernel_signature rt_kernel_signatures[] = {
#include "rt_interface.def"
};
#endif

#include "rt_interface_rows.h"

#endif /* RT_KERNEL_ARG_INDEX_H */
