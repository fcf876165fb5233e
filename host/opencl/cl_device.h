/* SPDX-License-Identifier: Apache-2.0 */
/* cl_device.h - OpenCL platforms and devices (host/opencl/cl_device.c): listing,
 * capabilities that decide bit-exactness with the CPU oracle, and selection
 * by index or name. Compiled only when the build found the OpenCL ICD loader
 * (RT_HAVE_OPENCL). No OpenCL types here, so callers need no CL headers. */
#ifndef RT_CL_DEVICE_H
#define RT_CL_DEVICE_H

#include <stddef.h>
#include <stdint.h>

#include "rt.h"

typedef struct rt_cl_device_info {
    int index;          /* over all platforms: the number --device takes */
    int platform_index; /* the platform's position in the ICD loader's list */
    char platform[128];
    char name[128];
    char vendor[128];
    char version[128]; /* "OpenCL 3.0 ..." */
    char driver[64];
    uint32_t compute_units;
    uint64_t global_mem; /* bytes */
    uint64_t max_alloc;  /* the largest single buffer, bytes */
    int cr_div_sqrt;     /* CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT for float */
    int fma;             /* CL_FP_FMA for float (hardware FMA; kernels do not contract) */
    int fp64;            /* cl_khr_fp64 (shown only: no kernel uses double) */
    int denorms;         /* CL_FP_DENORM for float: it keeps denormals */
    /* The oracle's bits are promised with the defaults (maths profile auto,
     * denormals preserved): the device keeps denormals. */
    int exact;
    int cpu;           /* CL_DEVICE_TYPE_CPU: the backend runs the packet kernel there */
    void *platform_id; /* cl_platform_id */
    void *device_id;   /* cl_device_id */
} rt_cl_device_info;

/* Every device of every platform. RT_ERROR_UNSUPPORTED with a message when
 * there is no platform or no device; *out is then NULL. free() the list. */
rt_status rt_cl_devices(rt_cl_device_info **out, int *count, rt_error *err);

/* Picks a device: selector NULL or "" is the first device (an exact one when
 * there is one), a number is an index, anything else the first device whose
 * name contains it (case-insensitive). Returns the position in devs, or -1
 * with a message. */
int rt_cl_select(const rt_cl_device_info *devs, int count, const char *selector, rt_error *err);

/* How the kernels do their maths on a device, and whether that gives the
 * oracle's bits. */
typedef struct rt_cl_math_plan {
    int portable;     /* 1: -DRT_PORTABLE_MATH (software divide/sqrt) */
    int flush;        /* 1: -cl-denorms-are-zero -DRT_FLUSH_DENORMALS */
    int needs_probe;  /* flush on a device that keeps denormals: exact only if
                         its compiler honours -cl-denorms-are-zero (the backend
                         checks with a probe kernel) */
    int exact;        /* promised (before any probe) */
    const char *note; /* why, one line */
} rt_cl_math_plan;

/* The plan for a device, a maths profile asked for and a denormal policy
 * (1: flush). Auto is native where the device's divide/sqrt are correctly
 * rounded, else portable. */
rt_cl_math_plan rt_cl_plan_math(const rt_cl_device_info *d, rt_device_math math, int flush);

/* The denormal policy to compare this device with the oracle, one line. */
const char *rt_cl_denormals_note(const rt_cl_device_info *d);

/* Which kernels the backend runs on the device, one line: the packet kernel
 * (kernels/rt_ray_packet.cl) on CPU devices, one ray per work-item elsewhere. */
const char *rt_cl_kernels_note(const rt_cl_device_info *d);

/* A name for an OpenCL error code ("CL_OUT_OF_RESOURCES"). */
const char *rt_cl_error_name(int code);

#endif /* RT_CL_DEVICE_H */
