/* SPDX-License-Identifier: Apache-2.0 */
/* test_opencl_kernel_args.c - the host sets kernel arguments by the names of
 * kernels/rt_kernel_arg_index.h, which expands the kernel rows of the GPU
 * interface table (kernels/rt_interface.def); this holds the table to the
 * kernels' signatures. The embedded kernel sources are built with
 * -cl-kernel-arg-info on the first OpenCL device, and for every kernel the
 * argument count and each argument's name at each index must be the
 * table's, and each scene-view argument's type its element type. A
 * parameter added, removed or reordered in a .cl file without the table (or
 * the other way round) fails here instead of passing garbage to a kernel.
 * Skipped (77) without an OpenCL device. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"

#ifdef RT_HAVE_OPENCL
#include <CL/cl.h>

#define RT_KERNEL_SIGNATURES
#include "opencl/cl_device.h"
#include "rt_kernel_arg_index.h"

/* Generated from kernels/ at build time (the library embeds them). */
extern const char rt_cl_source_rt_single_ray[];
extern const char rt_cl_source_rt_ray_packet[];

static void check_kernel(cl_program program, const rt_kernel_signature *sig) {
    cl_int ce;
    cl_kernel k = clCreateKernel(program, sig->kernel, &ce);
    CHECK_MSG(k != NULL, "%s: clCreateKernel failed (%d)", sig->kernel, (int)ce);
    if (!k) return;
    cl_uint n = 0;
    CHECK(clGetKernelInfo(k, CL_KERNEL_NUM_ARGS, sizeof n, &n, NULL) == CL_SUCCESS);
    CHECK_MSG((int)n == sig->args, "%s: %u arguments in the kernel, %d in rt_interface.def",
              sig->kernel, n, sig->args);
    for (cl_uint i = 0; i < n && (int)i < sig->args; i++) {
        char name[64] = "";
        ce = clGetKernelArgInfo(k, i, CL_KERNEL_ARG_NAME, sizeof name, name, NULL);
        CHECK_MSG(ce == CL_SUCCESS, "%s: no name for argument %u (%d)", sig->kernel, i, (int)ce);
        int view = sig->view ? RT_ARG_VIEW_COUNT : 0;
        const char *want = (int)i < view ? rt_kernel_view_names[i] : sig->names[i - (cl_uint)view];
        CHECK_MSG(want && strcmp(name, want) == 0,
                  "%s: argument %u is '%s' in the kernel, '%s' in rt_interface.def", sig->kernel, i,
                  name, want ? want : "(none)");
        if ((int)i < view) {
            char type[64] = "", want_type[64];
            clGetKernelArgInfo(k, i, CL_KERNEL_ARG_TYPE_NAME, sizeof type, type, NULL);
            snprintf(want_type, sizeof want_type, "%s*", rt_kernel_view_types[i]);
            CHECK_MSG(strcmp(type, want_type) == 0,
                      "%s: argument %u (%s) is a %s in the kernel, %s in rt_interface.def",
                      sig->kernel, i, name, type, want_type);
        }
    }
    clReleaseKernel(k);
}

int main(void) {
    rt_cl_device_info *devs;
    int count;
    rt_error err;
    if (rt_cl_devices(&devs, &count, &err) != RT_OK) test_skip(err.message);
    int pick = rt_cl_select(devs, count, NULL, &err);
    if (pick < 0) test_skip(err.message);
    cl_device_id d = devs[pick].device_id;
    cl_context_properties props[] = {CL_CONTEXT_PLATFORM,
                                     (cl_context_properties)devs[pick].platform_id, 0};
    cl_int ce;
    cl_context ctx = clCreateContext(props, 1, &d, NULL, NULL, &ce);
    CHECK(ctx != NULL);
    const char *src[2] = {rt_cl_source_rt_single_ray, rt_cl_source_rt_ray_packet};
    cl_program program = ctx ? clCreateProgramWithSource(ctx, 2, src, NULL, &ce) : NULL;
    CHECK(program != NULL);
    if (program) {
        ce = clBuildProgram(program, 1, &d, "-cl-kernel-arg-info -DRT_PK_LANES=16", NULL, NULL);
        CHECK_MSG(ce == CL_SUCCESS, "building the kernels with -cl-kernel-arg-info: %d", (int)ce);
        if (ce == CL_SUCCESS) {
            size_t kernels = sizeof rt_kernel_signatures / sizeof rt_kernel_signatures[0];
            for (size_t i = 0; i < kernels; i++) check_kernel(program, &rt_kernel_signatures[i]);
            /* Every kernel of the program is in the header. */
            size_t in_program = 0;
            clGetProgramInfo(program, CL_PROGRAM_NUM_KERNELS, sizeof in_program, &in_program, NULL);
            CHECK_MSG(in_program == kernels, "%zu kernels in the program, %zu in rt_interface.def",
                      in_program, kernels);
        }
        clReleaseProgram(program);
    }
    if (ctx) clReleaseContext(ctx);
    free(devs);
    return TEST_END();
}
#else
int main(void) {
    test_skip("this build has no OpenCL backend (RT_OPENCL=OFF or no ICD loader)");
}
#endif
