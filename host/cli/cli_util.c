/* cli_util.c - shared helpers of the rtcl commands. */
#include "cli_util.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "scene/scene_builtin.h"

void cli_error(const char *command, const char *fmt, ...) {
    va_list args;
    va_start(args, fmt);
    fprintf(stderr, "rtcl %s: ", command);
    vfprintf(stderr, fmt, args);
    fputc('\n', stderr);
    va_end(args);
}

const char *cli_value(int argc, char **argv, int *i, const char *command) {
    if (*i + 1 >= argc) {
        cli_error(command, "option %s needs a value (see rtcl %s --help)", argv[*i], command);
        return NULL;
    }
    return argv[++*i];
}

int cli_int(const char *command, const char *option, const char *text, long min, long max,
            int *out) {
    char *end;
    errno = 0;
    long v = strtol(text, &end, 10);
    if (errno || end == text || *end || v < min || v > max) {
        cli_error(command, "%s: '%s' is not an integer in %ld..%ld", option, text, min, max);
        return 0;
    }
    *out = (int)v;
    return 1;
}

int cli_float(const char *command, const char *option, const char *text, double *out) {
    char *end;
    errno = 0;
    double v = strtod(text, &end);
    if (errno || end == text || *end || !isfinite(v)) {
        cli_error(command, "%s: '%s' is not a finite number", option, text);
        return 0;
    }
    *out = v;
    return 1;
}

rt_status cli_load_scene(const char *arg, rt_scene **out, rt_error *err) {
    if (strncmp(arg, "builtin:", 8) == 0) return rt_scene_builtin(arg + 8, out, err);
    rt_status st = rt_scene_load(arg, out, err);
    /* The loader's notices, one "rtcl: notice: " line each. */
    for (const char *p = st == RT_OK ? rt_scene_notices(*out) : ""; *p;) {
        const char *eol = strchr(p, '\n');
        int n = eol ? (int)(eol - p) : (int)strlen(p);
        fprintf(stderr, "rtcl: notice: %.*s\n", n, p);
        p += n + (eol ? 1 : 0);
    }
    return st;
}

static int progress_drawn;

void cli_progress(void *user, double done) {
    static int last_percent = -1;
    if (!isatty(STDERR_FILENO)) return;
    int percent = (int)(done * 100.0 + 0.5);
    if (percent == last_percent && done < 1.0) return;
    last_percent = percent;
    const int width = 30;
    int filled = (int)(done * width + 0.5);
    char bar[64];
    for (int k = 0; k < width; k++) bar[k] = k < filled ? '#' : '.';
    bar[width] = 0;
    fprintf(stderr, "\r%s [%s] %3d%%", user ? (const char *)user : "", bar, percent);
    fflush(stderr);
    progress_drawn = 1;
}

void cli_progress_done(void) {
    if (progress_drawn) fputc('\n', stderr);
    progress_drawn = 0;
}

const char cli_renderer_usage[] =
    "  --backend B    cpu (the scalar oracle), packet (SIMD ray packets), opencl or\n"
    "                 vulkan (fail when no device exists; opencl:D, vulkan:D pick a\n"
    "                 device), or auto (opencl, else vulkan, when a device exists,\n"
    "                 else cpu with a notice) [cpu]\n"
    "  --device D     the OpenCL or Vulkan device: an index or part of a name (rtcl\n"
    "                 devices)\n"
    "  --threads N    worker threads, 0 = one per core [0]\n"
    "  --accel A      the structure of every static mesh (one that is no keyframe of\n"
    "                 an animated object): bvh, kd (exact SAH kd-tree) or kd-binned;\n"
    "                 without it each mesh's \"accel\" from the scene file [bvh]. All\n"
    "                 give the same bits\n"
    "  --cl-options OPTS\n"
    "                 extra OpenCL compiler options, e.g. -cl-mad-enable,\n"
    "                 -cl-fast-relaxed-math, -DRT_NATIVE_MATH (options appended to\n"
    "                 the kernels' build); results may then differ from the CPU\n"
    "                 oracle, and --stats says so (the speed-versus-error study)\n"
    "  --packet-isa I the packet backend's instruction set: generic, avx2, avx512\n"
    "                 (x86-64) [the widest the CPU runs]; all give the same bits\n"
    "  --verbose      print the OpenCL compiler's messages (build log, and what the\n"
    "                 driver printed while building) on stderr; without it they are\n"
    "                 shown only when the kernels fail to build\n"
    "  --device-math M\n"
    "                 device backends' divide and sqrt: native (the device's, correctly\n"
    "                 rounded where it promises it), portable (software, from integer\n"
    "                 operations: exact on any conforming device), or auto (native\n"
    "                 where promised, else portable) [auto]; --stats says which ran\n"
    "  --denormals P  preserve (IEEE) or flush (flush-to-zero and denormals-are-zero,\n"
    "                 as most GPUs: the CPU backends set their threads' FTZ/DAZ and\n"
    "                 kernels are built with -cl-denorms-are-zero) [preserve]; compare a\n"
    "                 device with the oracle in the mode 'rtcl devices' names\n"
    "For tests and comparisons (every choice gives the same bits):\n"
    "  --cl-one-ray   OpenCL: one ray per work-item on CPU devices too\n"
    "  --cl-packet-lanes N\n"
    "                 OpenCL on CPU devices: 4 (2x2), 8 (4x2) or 16 (4x4) rays per\n"
    "                 work-item [16]\n"
    "  --cl-no-wavefront\n"
    "                 OpenCL: shade every image in one kernel, never as wavefront passes\n"
    "  --cl-wave-cap N\n"
    "                 OpenCL: wavefront queues of at most N rays (overflows sooner)\n";

void cli_renderer_args_init(cli_renderer_args *a) {
    memset(a, 0, sizeof *a);
    a->opt = rt_renderer_options_default();
    a->backend = "cpu";
}

int cli_maths_arg(int argc, char **argv, int *i, const char *command, rt_device_math *math,
                  rt_denormals *denormals) {
    const char *o = argv[*i], *v;
    int is_math = !strcmp(o, "--device-math");
    if (!is_math && strcmp(o, "--denormals") != 0) return 0;
    if (!(v = cli_value(argc, argv, i, command))) return -1;
    if (is_math && !strcmp(v, "auto"))
        *math = RT_DEVICE_MATH_AUTO;
    else if (is_math && !strcmp(v, "native"))
        *math = RT_DEVICE_MATH_NATIVE;
    else if (is_math && !strcmp(v, "portable"))
        *math = RT_DEVICE_MATH_PORTABLE;
    else if (!is_math && !strcmp(v, "preserve"))
        *denormals = RT_DENORMALS_PRESERVE;
    else if (!is_math && !strcmp(v, "flush"))
        *denormals = RT_DENORMALS_FLUSH;
    else {
        cli_error(command, "%s takes %s, not '%s'", o,
                  is_math ? "auto, native or portable" : "preserve or flush", v);
        return -1;
    }
    return 1;
}

int cli_renderer_arg(int argc, char **argv, int *i, const char *command, cli_renderer_args *a) {
    const char *o = argv[*i], *v;
    int n;
    if (!strcmp(o, "--backend")) {
        if (!(a->backend = cli_value(argc, argv, i, command))) return -1;
    } else if (!strcmp(o, "--device")) {
        if (!(a->device = cli_value(argc, argv, i, command))) return -1;
    } else if (!strcmp(o, "--accel")) {
        if (!(v = cli_value(argc, argv, i, command))) return -1;
        if (!rt_accel_parse(v, &a->accel)) {
            cli_error(command, "--accel takes bvh, kd or kd-binned, not '%s'", v);
            return -1;
        }
        a->accel_set = 1;
    } else if (!strcmp(o, "--threads")) {
        if (!(v = cli_value(argc, argv, i, command)) ||
            !cli_int(command, o, v, 0, 1024, &a->opt.threads))
            return -1;
    } else if (!strcmp(o, "--cl-options")) {
        if (!(a->opt.device_options = cli_value(argc, argv, i, command))) return -1;
    } else if (!strcmp(o, "--packet-isa")) {
        if (!(a->opt.packet_isa = cli_value(argc, argv, i, command))) return -1;
    } else if (!strcmp(o, "--verbose")) {
        a->verbose = 1;
    } else if ((n = cli_maths_arg(argc, argv, i, command, &a->opt.device_math,
                                  &a->opt.denormals)) != 0) {
        return n;
    } else if (!strcmp(o, "--cl-one-ray")) {
        a->opt.opencl.one_ray_kernels = 1;
    } else if (!strcmp(o, "--cl-no-wavefront")) {
        a->opt.opencl.no_wavefront = 1;
    } else if (!strcmp(o, "--cl-packet-lanes")) {
        if (!(v = cli_value(argc, argv, i, command)) || !cli_int(command, o, v, 4, 16, &n))
            return -1;
        if (n != 4 && n != 8 && n != 16) {
            cli_error(command, "--cl-packet-lanes takes 4, 8 or 16, not %d", n);
            return -1;
        }
        a->opt.opencl.packet_lanes = n;
    } else if (!strcmp(o, "--cl-wave-cap")) {
        if (!(v = cli_value(argc, argv, i, command)) || !cli_int(command, o, v, 1, 1 << 30, &n))
            return -1;
        a->opt.opencl.wave_queue_cap = (uint32_t)n;
    } else {
        return 0;
    }
    return 1;
}

rt_renderer *cli_renderer_create(const char *command, cli_renderer_args *a) {
    if (a->device) {
        if (strcmp(a->backend, "opencl") != 0 && strcmp(a->backend, "vulkan") != 0 &&
            strcmp(a->backend, "auto") != 0) {
            cli_error(command, "--device applies to --backend opencl, vulkan or auto, not '%s'",
                      a->backend);
            return NULL;
        }
        snprintf(a->spec, sizeof a->spec, "%s:%s", a->backend, a->device);
    } else {
        snprintf(a->spec, sizeof a->spec, "%s", a->backend);
    }
    a->opt.backend = a->spec;
    rt_renderer *r = NULL;
    rt_error err;
    memset(&err, 0, sizeof err);
    if (rt_renderer_create(&a->opt, &r, &err) != RT_OK) {
        cli_error(command, "%s", err.message);
        return NULL;
    }
    return r;
}

int cli_apply_accel(const char *command, const cli_renderer_args *a, rt_scene *scene) {
    if (!a->accel_set) return 1;
    if (rt_scene_set_static_accel(scene, a->accel) != RT_OK) {
        cli_error(command, "%s", rt_scene_error(scene));
        return 0;
    }
    return 1;
}

void cli_print_build_log(const char *command, const rt_renderer *renderer) {
    const char *log = rt_renderer_build_log(renderer);
    if (log[0])
        fprintf(stderr, "rtcl %s: %s build log:\n%s\n", command, rt_renderer_backend(renderer),
                log);
}
