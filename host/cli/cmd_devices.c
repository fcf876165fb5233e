/* cmd_devices.c - 'rtcl devices': OpenCL platforms and devices, Vulkan
 * devices, and whether each promises the CPU oracle's bits. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_util.h"
#include "commands.h"
#ifdef RT_HAVE_OPENCL
#include "opencl/cl_device.h"
#endif
#ifdef RT_HAVE_VULKAN
#include "vulkan/vk_device.h"
#endif

static const char usage[] =
    "usage: rtcl devices [--api opencl|vulkan] [--device N|NAME] [--help]\n"
    "\n"
    "Lists the OpenCL platforms and devices the ICD loader finds, then the Vulkan\n"
    "devices the Vulkan loader finds (each API's own numbering: --device N, or\n"
    "--backend opencl:N / vulkan:N on render, trace and bench).\n"
    "\n"
    "OpenCL devices by index (the number --device takes), with compute units, global\n"
    "memory and single-precision capabilities. 'maths' is the profile render,\n"
    "trace and bench pick (--device-math auto): native where float divide and\n"
    "sqrt are correctly rounded (built with -cl-fp32-correctly-rounded-divide-sqrt),\n"
    "else portable (divide and sqrt in software from 32-bit integer operations;\n"
    "docs/PORTABLE_MATH.md). Neither uses fp64 or FMA: fp64 and FMA are shown for\n"
    "information. 'denormals' says whether the device keeps them and so which\n"
    "--denormals policy compares it with the oracle. 'exact' says whether the\n"
    "device promises the CPU oracle's bits with the defaults, and why; 'flush'\n"
    "the same with --denormals flush.\n"
    "'kernels' says which kernels render there: on a CPU device a packet kernel\n"
    "(a 4x4 block of rays per work-item, as vectors), elsewhere one ray per\n"
    "work-item; both give the oracle's bits.\n"
    "\n"
    "Vulkan devices with their type, driver and float controls\n"
    "(VK_KHR_shader_float_controls, core in Vulkan 1.2). The shaders are exact by\n"
    "construction in the portable maths profile: no contraction (NoContraction on\n"
    "every float operation), division and sqrt in software, no fp64. The oracle's\n"
    "bits are then promised where the device also rounds to nearest even, keeps\n"
    "denormals and keeps signed zeros, infs and NaNs when the shader asks for it.\n"
    "\n"
    "  --api opencl|vulkan  list only that API's devices (exit status 2 when it has\n"
    "                   none, with the reason); without it, every API this build\n"
    "                   has, and status 2 only when none has a device\n"
    "  --device N|NAME  show only that device (an index or a part of its name)\n";

/* A failure of one API: an error (status 2) when that API was asked for,
 * else a line in the listing (another API may have devices). */
static int api_failed(const char *message, int asked) {
    if (asked) {
        cli_error("devices", "%s", message);
        return 2;
    }
    printf("%s\n", message);
    return 0;
}

static int list_opencl(const char *selector, int asked, int *listed) {
#ifndef RT_HAVE_OPENCL
    (void)selector;
    (void)listed;
    return api_failed("this build has no OpenCL backend (configure with -DRT_OPENCL=ON and the "
                      "OpenCL ICD loader installed)",
                      asked);
#else
    rt_cl_device_info *devs;
    int count;
    rt_error msg;
    memset(&msg, 0, sizeof msg);
    if (rt_cl_devices(&devs, &count, &msg) != RT_OK) return api_failed(msg.message, asked);
    int only = -1;
    if (selector && (only = rt_cl_select(devs, count, selector, &msg)) < 0) {
        free(devs);
        return api_failed(msg.message, asked);
    }
    int last_platform = -1;
    printf("opencl\n");
    for (int i = 0; i < count; i++) {
        const rt_cl_device_info *d = &devs[i];
        if (only >= 0 && i != only) continue;
        if (d->platform_index != last_platform) {
            printf("platform %d: %s\n", d->platform_index, d->platform);
            last_platform = d->platform_index;
        }
        printf("  device %d: %s\n", d->index, d->name);
        printf("    vendor            %s\n", d->vendor);
        printf("    version           %s (driver %s)\n", d->version, d->driver);
        printf("    compute units     %u\n", d->compute_units);
        printf("    global memory     %.1f MiB (largest buffer %.1f MiB)\n",
               (double)d->global_mem / 1048576.0, (double)d->max_alloc / 1048576.0);
        printf("    float div/sqrt    %s\n",
               d->cr_div_sqrt ? "correctly rounded" : "NOT correctly rounded");
        printf("    float fma         %s\n", d->fma ? "yes" : "no");
        printf("    fp64              %s\n", d->fp64 ? "yes (cl_khr_fp64; not used)" : "no");
        printf("    denormals         %s\n", rt_cl_denormals_note(d));
        rt_cl_math_plan keep = rt_cl_plan_math(d, RT_DEVICE_MATH_AUTO, 0);
        rt_cl_math_plan flush = rt_cl_plan_math(d, RT_DEVICE_MATH_AUTO, 1);
        printf("    maths             %s\n", keep.portable ? "portable" : "native");
        printf("    exact             %s: %s\n", keep.exact ? "yes" : "no", keep.note);
        printf("    exact (flush)     %s: %s\n", flush.exact ? "yes" : "no", flush.note);
        printf("    kernels           %s\n", rt_cl_kernels_note(d));
        (*listed)++;
    }
    free(devs);
    return 0;
#endif
}

static int list_vulkan(const char *selector, int asked, int *listed) {
#ifndef RT_HAVE_VULKAN
    (void)selector;
    (void)listed;
    return api_failed("this build has no Vulkan backend (configure with -DRT_VULKAN=ON, the Vulkan "
                      "loader and glslang installed: libvulkan-dev, glslang-tools)",
                      asked);
#else
    rt_vk_device_info *devs;
    int count;
    rt_error msg;
    memset(&msg, 0, sizeof msg);
    if (rt_vk_devices(&devs, &count, &msg) != RT_OK) return api_failed(msg.message, asked);
    int only = -1;
    if (selector && (only = rt_vk_select(devs, count, selector, &msg)) < 0) {
        free(devs);
        return api_failed(msg.message, asked);
    }
    printf("vulkan\n");
    for (int i = 0; i < count; i++) {
        const rt_vk_device_info *d = &devs[i];
        if (only >= 0 && i != only) continue;
        printf("  device %d: %s\n", d->index, d->name);
        printf("    type              %s, Vulkan %s\n", d->type, d->api);
        printf("    driver            %s\n", d->driver);
        printf("    memory            %.1f MiB (largest storage buffer %.1f MiB)\n",
               (double)d->memory / 1048576.0, (double)d->max_buffer / 1048576.0);
        printf("    timestamps        %s\n", d->timestamps ? "yes" : "no");
        if (d->float_controls)
            printf("    float controls    round to nearest even %s, denormals kept %s, "
                   "flushed %s, signed zeros/inf/NaN kept %s\n",
                   d->rte ? "yes" : "no", d->denorm_preserve ? "yes" : "no",
                   d->denorm_flush ? "yes" : "no", d->signed_zero_inf_nan ? "yes" : "no");
        else
            printf("    float controls    not reported (Vulkan before 1.2)\n");
        printf("    maths profile     portable (software division and sqrt, no fp64, no "
               "contraction)\n");
        printf("    exact             %s: %s\n", d->exact ? "yes" : "no",
               rt_vk_exactness_note(d, 0));
        printf("    exact (flush)     %s: %s\n", d->exact_flush ? "yes" : "no",
               rt_vk_exactness_note(d, 1));
        (*listed)++;
    }
    free(devs);
    return 0;
#endif
}

int cmd_devices(int argc, char **argv) {
    const char *selector = NULL, *api = NULL;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            fputs(usage, stdout);
            return 0;
        } else if (!strcmp(argv[i], "--device")) {
            if (!(selector = cli_value(argc, argv, &i, "devices"))) return 2;
        } else if (!strcmp(argv[i], "--api")) {
            if (!(api = cli_value(argc, argv, &i, "devices"))) return 2;
        } else {
            cli_error("devices", "unexpected argument '%s'\n%s", argv[i], usage);
            return 2;
        }
    }
    if (api && strcmp(api, "opencl") != 0 && strcmp(api, "vulkan") != 0) {
        cli_error("devices", "unknown --api '%s' (opencl or vulkan)", api);
        return 2;
    }
    int listed = 0, failed = 0;
    if (!api || !strcmp(api, "opencl")) {
        int rc = list_opencl(selector, api != NULL, &listed);
        if (rc) failed = rc;
    }
    if (!api || !strcmp(api, "vulkan")) {
        int rc = list_vulkan(selector, api != NULL, &listed);
        if (rc) failed = rc;
    }
    if (api) return failed;
    if (!listed) {
        cli_error("devices", "no OpenCL or Vulkan device found");
        return 2;
    }
    return 0;
}
