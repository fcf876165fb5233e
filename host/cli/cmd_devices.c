/* cmd_devices.c - 'rtcl devices': OpenCL platforms and devices, and whether
 * each promises the CPU oracle's bits. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_util.h"
#include "commands.h"
#ifdef RT_HAVE_OPENCL
#include "opencl/cl_device.h"
#endif

static const char usage[] =
    "usage: rtcl devices [--device N|NAME] [--help]\n"
    "\n"
    "Lists the OpenCL platforms and devices the ICD loader finds, by index (the\n"
    "number --device takes on render, trace and here), with compute units, global\n"
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
    "  --device N|NAME  show only that device (an index or a part of its name)\n";

int cmd_devices(int argc, char **argv) {
    const char *selector = NULL;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            fputs(usage, stdout);
            return 0;
        } else if (!strcmp(argv[i], "--device")) {
            if (!(selector = cli_value(argc, argv, &i, "devices"))) return 2;
        } else {
            cli_error("devices", "unexpected argument '%s'\n%s", argv[i], usage);
            return 2;
        }
    }
#ifndef RT_HAVE_OPENCL
    cli_error("devices", "this build has no OpenCL backend (configure with -DRT_OPENCL=ON and "
                         "the OpenCL ICD loader installed)");
    return 2;
#else
    rt_cl_device_info *devs;
    int count;
    rt_error msg;
    memset(&msg, 0, sizeof msg);
    if (rt_cl_devices(&devs, &count, &msg) != RT_OK) {
        cli_error("devices", "%s", msg.message);
        return 2;
    }
    int only = -1;
    if (selector && (only = rt_cl_select(devs, count, selector, &msg)) < 0) {
        cli_error("devices", "%s", msg.message);
        free(devs);
        return 2;
    }
    int last_platform = -1;
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
    }
    free(devs);
    return 0;
#endif
}
