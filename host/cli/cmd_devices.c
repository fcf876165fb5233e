/* SPDX-License-Identifier: Apache-2.0 */
/* cmd_devices.c - 'rtcl devices': the devices of every device backend the
 * backend registry names (OpenCL platforms and devices, Vulkan devices), and
 * whether each promises the CPU oracle's bits, as text or JSON (--json). */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_util.h"
#include "commands.h"
#include "engines/bench_print.h"

typedef struct devices_args {
    int api; /* --api: index among device_api_name's, or -1: all */
    const char *device;
    int json;
} devices_args;

/* The device backends of the registry (not "auto"), k = 0, 1, ... */
static const char *device_api_name(int k) {
    rt_backend_info b;
    for (int i = 0, found = 0; rt_backend_name(i); i++)
        if (rt_backend_describe(rt_backend_name(i), &b, NULL) == RT_OK && b.takes_device &&
            strcmp(b.name, "auto") != 0 && found++ == k)
            return b.name;
    return NULL;
}

static const cli_option devices_options[] = {
    {"--api", 0, CLI_CHOICE, "API", offsetof(devices_args, api), .choice_name = device_api_name,
     .help = "list only that backend's devices: {choices} (exit status 2 when it has none, "
             "with the reason); without it, every device backend, and status 2 only when none "
             "has a device",
     .fallback = "all"},
    {"--device", 0, CLI_STRING, "N|NAME", offsetof(devices_args, device), .flags = CLI_NONEMPTY,
     .help = "show only that device: an index or a part of its name", .fallback = "all"},
    {"--json", 0, CLI_FLAG, NULL, offsetof(devices_args, json),
     .help = "the same as one JSON object on stdout: {\"backends\": [{\"backend\", \"devices\": "
             "[{index, name, platform, ..., exact, exact_note, ...}]} or {\"backend\", "
             "\"error\"}]}"},
    {NULL}};

static const cli_group devices_groups[] = {{NULL, devices_options, 0}, {NULL}};

const cli_command cmd_devices_spec = {
    "devices",
    "list OpenCL and Vulkan devices, and which are bit-exact",
    "",
    "argument",
    0,
    0,
    "Lists the OpenCL platforms and devices the ICD loader finds, then the Vulkan\n"
    "devices the Vulkan loader finds (each API's own numbering: --device N, or\n"
    "--backend opencl:N / vulkan:N on render, trace, animate and view).\n"
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
    "denormals and keeps signed zeros, infs and NaNs when the shader asks for it.\n",
    devices_groups,
    NULL,
    NULL};

static const char *yes_no(int v) {
    return v ? "yes" : "no";
}

/* The text listing of one backend's devices (fields the backend does not
 * report are left out). */
static void print_text(const char *backend, const rt_device_info *devs, int count) {
    printf("%s\n", backend);
    int last_platform = -1;
    for (int i = 0; i < count; i++) {
        const rt_device_info *d = &devs[i];
        if (d->platform_index >= 0 && d->platform_index != last_platform) {
            printf("platform %d: %s\n", d->platform_index, d->platform);
            last_platform = d->platform_index;
        }
        printf("  device %d: %s\n", d->index, d->name);
        if (d->vendor[0]) printf("    vendor            %s\n", d->vendor);
        if (d->type[0]) printf("    type              %s\n", d->type);
        printf("    version           %s (driver %s)\n", d->version, d->driver);
        if (d->compute_units) printf("    compute units     %u\n", d->compute_units);
        printf("    memory            %.1f MiB (largest buffer %.1f MiB)\n",
               (double)d->memory / 1048576.0, (double)d->max_buffer / 1048576.0);
        if (d->cr_div_sqrt >= 0)
            printf("    float div/sqrt    %s\n",
                   d->cr_div_sqrt ? "correctly rounded" : "NOT correctly rounded");
        if (d->fma >= 0) printf("    float fma         %s\n", yes_no(d->fma));
        if (d->fp64 >= 0) printf("    fp64              %s\n", d->fp64 ? "yes (not used)" : "no");
        if (d->timestamps >= 0) printf("    timestamps        %s\n", yes_no(d->timestamps));
        if (d->float_controls > 0)
            printf("    float controls    round to nearest even %s, denormals kept %s, "
                   "flushed %s, signed zeros/inf/NaN kept %s\n",
                   yes_no(d->rte), yes_no(d->denorm_preserve), yes_no(d->denorm_flush),
                   yes_no(d->signed_zero_inf_nan));
        else if (d->float_controls == 0)
            printf("    float controls    not reported (Vulkan before 1.2)\n");
        if (d->denormals_note[0]) printf("    denormals         %s\n", d->denormals_note);
        printf("    maths             %s\n",
               !strcmp(d->math_profile, "portable")
                   ? "portable (software division and sqrt, no fp64, no contraction)"
                   : "native (the device's correctly rounded division and sqrt)");
        printf("    exact             %s: %s\n", yes_no(d->exact), d->exact_note);
        printf("    exact (flush)     %s: %s\n", yes_no(d->exact_flush), d->exact_flush_note);
        if (d->kernels_note[0]) printf("    kernels           %s\n", d->kernels_note);
    }
}

static void json_key_string(const char *key, const char *value) {
    printf(", \"%s\": ", key);
    json_out_string(value);
}

/* One device as a JSON object; -1 fields (not reported) are null. */
static void print_json_device(const rt_device_info *d) {
    printf("{\"index\": %d", d->index);
    json_key_string("name", d->name);
    if (d->platform_index >= 0) {
        printf(", \"platform_index\": %d", d->platform_index);
        json_key_string("platform", d->platform);
    }
    json_key_string("vendor", d->vendor);
    json_key_string("type", d->type);
    json_key_string("version", d->version);
    json_key_string("driver", d->driver);
    printf(", \"compute_units\": %u, \"memory\": %llu, \"max_buffer\": %llu", d->compute_units,
           (unsigned long long)d->memory, (unsigned long long)d->max_buffer);
    const struct {
        const char *key;
        int v;
    } flags[] = {{"cr_div_sqrt", d->cr_div_sqrt},
                 {"fma", d->fma},
                 {"fp64", d->fp64},
                 {"timestamps", d->timestamps},
                 {"float_controls", d->float_controls},
                 {"rte", d->float_controls > 0 ? d->rte : -1},
                 {"denorm_preserve", d->float_controls > 0 ? d->denorm_preserve : -1},
                 {"denorm_flush", d->float_controls > 0 ? d->denorm_flush : -1},
                 {"signed_zero_inf_nan", d->float_controls > 0 ? d->signed_zero_inf_nan : -1}};
    for (size_t k = 0; k < sizeof flags / sizeof flags[0]; k++)
        printf(", \"%s\": %s", flags[k].key, flags[k].v < 0 ? "null" : cli_json_bool(flags[k].v));
    json_key_string("maths", d->math_profile);
    printf(", \"exact\": %s", cli_json_bool(d->exact));
    json_key_string("exact_note", d->exact_note);
    printf(", \"exact_flush\": %s", cli_json_bool(d->exact_flush));
    json_key_string("exact_flush_note", d->exact_flush_note);
    json_key_string("denormals_note", d->denormals_note);
    json_key_string("kernels_note", d->kernels_note);
    putchar('}');
}

int cmd_devices(int argc, char **argv) {
    devices_args a = {-1, NULL, 0};
    int code;
    if (cli_parse(&cmd_devices_spec, &a, argc, argv, &code) < 0) return code;
    int listed = 0, failed = 0, first = 1;
    if (a.json) printf("{\"backends\": [");
    for (int k = 0; device_api_name(k); k++) {
        if (a.api >= 0 && k != a.api) continue;
        const char *backend = device_api_name(k);
        rt_device_info *devs = NULL;
        int count = 0;
        rt_error err;
        memset(&err, 0, sizeof err);
        rt_status st = rt_devices(backend, a.device, &devs, &count, &err);
        if (a.json) {
            printf("%s{\"backend\": \"%s\"", first ? "" : ", ", backend);
            if (st != RT_OK) {
                json_key_string("error", err.message);
            } else {
                printf(", \"devices\": [");
                for (int i = 0; i < count; i++) {
                    if (i) printf(", ");
                    print_json_device(&devs[i]);
                }
                putchar(']');
            }
            putchar('}');
        } else if (st != RT_OK) {
            /* An error when this backend was asked for, else a line of the
             * listing (another backend may have devices). */
            if (a.api >= 0)
                cli_error("devices", "%s", err.message);
            else
                printf("%s\n", err.message);
        } else {
            print_text(backend, devs, count);
        }
        if (st != RT_OK && a.api >= 0) failed = 2;
        listed += st == RT_OK ? count : 0;
        first = 0;
        free(devs);
    }
    if (a.json) printf("]}\n");
    if (a.api >= 0) return failed;
    if (!listed) {
        cli_error("devices", "no device found by any device backend");
        return 2;
    }
    return 0;
}
