/* SPDX-License-Identifier: Apache-2.0 */
/* cl_device.c - OpenCL platforms and devices through the ICD loader. */
#include "opencl/cl_device.h"

#include <CL/cl.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend/device_select.h"
#include "base/error.h"

/* The codes it names and their names (cl_error_names.def). */
static const rt_code_name cl_error_names[] = {
#define RT_CL_ERROR(name) {name, #name},
#include "opencl/cl_error_names.def"
#undef RT_CL_ERROR
    {-1001, "CL_PLATFORM_NOT_FOUND_KHR"}, /* cl_ext.h's code, not in every cl.h */
};

const char *rt_cl_error_name(int code) {
    size_t count = sizeof cl_error_names / sizeof *cl_error_names;
    return rt_code_name_find(cl_error_names, count, code, "an OpenCL error");
}

static void get_string(cl_device_id d, cl_device_info what, char *out, size_t size) {
    out[0] = 0;
    if (clGetDeviceInfo(d, what, size, out, NULL) != CL_SUCCESS) out[0] = 0;
    out[size - 1] = 0;
}

static void describe(cl_platform_id p, cl_device_id d, rt_cl_device_info *info) {
    memset(info, 0, sizeof *info);
    info->platform_id = p;
    info->device_id = d;
    if (clGetPlatformInfo(p, CL_PLATFORM_NAME, sizeof info->platform, info->platform, NULL) !=
        CL_SUCCESS)
        info->platform[0] = 0;
    info->platform[sizeof info->platform - 1] = 0;
    get_string(d, CL_DEVICE_NAME, info->name, sizeof info->name);
    get_string(d, CL_DEVICE_VENDOR, info->vendor, sizeof info->vendor);
    get_string(d, CL_DEVICE_VERSION, info->version, sizeof info->version);
    get_string(d, CL_DRIVER_VERSION, info->driver, sizeof info->driver);
    cl_uint cu = 0;
    cl_ulong mem = 0, alloc = 0;
    cl_device_fp_config fp = 0, dp = 0;
    cl_device_type type = 0;
    clGetDeviceInfo(d, CL_DEVICE_MAX_COMPUTE_UNITS, sizeof cu, &cu, NULL);
    clGetDeviceInfo(d, CL_DEVICE_GLOBAL_MEM_SIZE, sizeof mem, &mem, NULL);
    clGetDeviceInfo(d, CL_DEVICE_MAX_MEM_ALLOC_SIZE, sizeof alloc, &alloc, NULL);
    clGetDeviceInfo(d, CL_DEVICE_SINGLE_FP_CONFIG, sizeof fp, &fp, NULL);
    if (clGetDeviceInfo(d, CL_DEVICE_TYPE, sizeof type, &type, NULL) != CL_SUCCESS) type = 0;
    info->cpu = (type & CL_DEVICE_TYPE_CPU) != 0;
    if (clGetDeviceInfo(d, CL_DEVICE_DOUBLE_FP_CONFIG, sizeof dp, &dp, NULL) != CL_SUCCESS) dp = 0;
    info->compute_units = cu;
    info->global_mem = mem;
    info->max_alloc = alloc;
    info->cr_div_sqrt = (fp & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT) != 0;
    info->fma = (fp & CL_FP_FMA) != 0;
    info->denorms = (fp & CL_FP_DENORM) != 0;
    /* fp64: the extension string is the promise OpenCL C's cl_khr_fp64 macro
     * follows; a non-zero double config says the same on 1.2+ devices. */
    size_t ext_size = 0;
    if (clGetDeviceInfo(d, CL_DEVICE_EXTENSIONS, 0, NULL, &ext_size) == CL_SUCCESS && ext_size) {
        char *ext = malloc(ext_size + 1);
        if (ext && clGetDeviceInfo(d, CL_DEVICE_EXTENSIONS, ext_size, ext, NULL) == CL_SUCCESS) {
            ext[ext_size] = 0;
            info->fp64 = strstr(ext, "cl_khr_fp64") != NULL;
        }
        free(ext);
    }
    if (dp == 0) info->fp64 = 0;
    info->exact = rt_cl_plan_math(info, RT_DEVICE_MATH_AUTO, 0).exact;
}

rt_status rt_cl_devices(rt_cl_device_info **out, int *count, rt_error *err) {
    *out = NULL;
    *count = 0;
    cl_uint np = 0;
    cl_int cl_err = clGetPlatformIDs(0, NULL, &np);
    if (cl_err != CL_SUCCESS || np == 0) {
        return rt_fail(err, RT_ERROR_UNSUPPORTED,
                       "no OpenCL platform found (%s): the ICD loader lists no driver in "
                       "/etc/OpenCL/vendors (install one, e.g. pocl-opencl-icd)",
                       cl_err != CL_SUCCESS ? rt_cl_error_name(cl_err) : "none installed");
    }
    cl_platform_id *plats = calloc(np, sizeof *plats);
    if (!plats || clGetPlatformIDs(np, plats, NULL) != CL_SUCCESS) {
        free(plats);
        return rt_fail(err, RT_ERROR_BACKEND, "cannot list OpenCL platforms");
    }
    rt_cl_device_info *list = NULL;
    int n = 0;
    for (cl_uint p = 0; p < np; p++) {
        cl_uint nd = 0;
        if (clGetDeviceIDs(plats[p], CL_DEVICE_TYPE_ALL, 0, NULL, &nd) != CL_SUCCESS || !nd)
            continue;
        cl_device_id *ids = calloc(nd, sizeof *ids);
        rt_cl_device_info *grown = realloc(list, sizeof *list * (size_t)(n + (int)nd));
        if (!ids || !grown) {
            free(ids);
            free(grown ? grown : list);
            free(plats);
            return rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory");
        }
        list = grown;
        if (clGetDeviceIDs(plats[p], CL_DEVICE_TYPE_ALL, nd, ids, NULL) == CL_SUCCESS) {
            for (cl_uint d = 0; d < nd; d++) {
                describe(plats[p], ids[d], &list[n]);
                list[n].index = n;
                list[n].platform_index = (int)p;
                n++;
            }
        }
        free(ids);
    }
    free(plats);
    if (n == 0) {
        free(list);
        return rt_fail(err, RT_ERROR_UNSUPPORTED,
                       "no OpenCL device found (%u platform%s, none with a device)", np,
                       np == 1 ? "" : "s");
    }
    *out = list;
    *count = n;
    return RT_OK;
}

int rt_cl_select(const rt_cl_device_info *devs, int count, const char *sel, rt_error *err) {
    const rt_device_fields fields = {sizeof *devs, offsetof(rt_cl_device_info, name),
                                     offsetof(rt_cl_device_info, exact)};
    return rt_device_select("OpenCL", devs, count, fields, sel, err);
}

rt_cl_math_plan rt_cl_plan_math(const rt_cl_device_info *d, rt_device_math math, int flush) {
    rt_cl_math_plan p;
    memset(&p, 0, sizeof p);
    p.portable =
        math == RT_DEVICE_MATH_PORTABLE || (math == RT_DEVICE_MATH_AUTO && !d->cr_div_sqrt);
    p.flush = flush != 0;
    if (!p.portable && !d->cr_div_sqrt) {
        p.note = "native maths on a device whose float divide/sqrt are not "
                 "correctly rounded (--device-math portable gives the oracle's bits)";
        return p;
    }
    if (!flush && !d->denorms) {
        p.note = "the device flushes denormals and the oracle keeps them "
                 "(--denormals flush compares it with a flushing oracle)";
        return p;
    }
    p.exact = 1;
    p.needs_probe = flush && d->denorms;
    if (p.needs_probe)
        p.note = p.portable ? "if the device flushes under -cl-denorms-are-zero "
                              "(probed at the first frame); software divide/sqrt"
                            : "if the device flushes under -cl-denorms-are-zero "
                              "(probed at the first frame); correctly rounded divide/sqrt";
    else if (p.portable)
        p.note = "software divide/sqrt from integer operations (portable profile)";
    else
        p.note = "the device's correctly rounded divide/sqrt (native profile)";
    return p;
}

const char *rt_cl_denormals_note(const rt_cl_device_info *d) {
    if (d->denorms)
        return "kept (CL_FP_DENORM): exact with --denormals preserve, the default; with "
               "flush if its compiler honours -cl-denorms-are-zero";
    return "flushed (no CL_FP_DENORM): exact only with --denormals flush";
}

const char *rt_cl_kernels_note(const rt_cl_device_info *d) {
    if (d->cpu)
        return "packet: a CPU device, so each work-item traces a 4x4 block of rays as float16 "
               "vectors (kernels/rt_ray_packet.cl)";
    return "one ray per work-item (kernels/rt_single_ray.cl; wavefront passes for reflection and "
           "refraction)";
}
