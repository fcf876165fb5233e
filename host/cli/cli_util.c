/* SPDX-License-Identifier: Apache-2.0 */
/* cli_util.c - shared parts of the rtcl commands (cli_util.h). */
#include "cli_util.h"

#include "frame_image.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

void cli_error(const char *command, const char *fmt, ...) {
    va_list args;
    va_start(args, fmt);
    fprintf(stderr, "rtcl %s: ", command);
    vfprintf(stderr, fmt, args);
    fputc('\n', stderr);
    va_end(args);
}

const char *cli_json_bool(int v) {
    return v ? "true" : "false";
}

double cli_now_ms(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1000.0 + (double)ts.tv_nsec / 1e6;
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

/* ---- scene options ------------------------------------------------------- */

/* The library's names for its enums, value by value while they name one
 * (cli_option.choice_name). */
const char *cli_accel_name(int v) {
    const char *name = rt_accel_name((rt_accel)v);
    rt_accel back;
    return rt_accel_parse(name, &back) && (int)back == v ? name : NULL;
}

static int update_parse(const char *text, int *value) {
    rt_update_policy p;
    if (!rt_update_policy_parse(text, &p)) return 0;
    *value = (int)p;
    return 1;
}

static const char *update_name(int v) {
    const char *name = rt_update_policy_name((rt_update_policy)v);
    rt_update_policy back;
    return rt_update_policy_parse(name, &back) && (int)back == v ? name : NULL;
}

const cli_option cli_scene_options[] = {
    {"--accel", 0, CLI_CHOICE, "A", offsetof(cli_scene_args, accel), .choice_name = cli_accel_name,
     .help = "the structure of every static mesh (one that is no keyframe of an animated "
             "object): {choices} (kd: the exact SAH kd-tree, kd-binned: a binned one); all give "
             "the same bits",
     .fallback = "each mesh's \"accel\" in the scene file, else bvh"},
    {"--animation", 0, CLI_STRING, "CLIP", offsetof(cli_scene_args, animation),
     .flags = CLI_NONEMPTY,
     .help = "the animation clip a glTF scene plays, by name or index ('rtcl info' lists them)",
     .fallback = "the file's first (index 0)"},
    {NULL}};

const cli_option cli_time_options[] = {
    {"--time", 0, CLI_FLOAT, "T", offsetof(cli_scene_args, time), -INFINITY, INFINITY,
     .help = "the scene at time T seconds: its keyframes, transform keys and camera path "
             "(docs/SCENE_FORMAT.md, \"Time\")",
     .fallback = "0"},
    {NULL}};

void cli_scene_args_init(cli_scene_args *a) {
    a->accel = -1;
    a->time = NAN;
    a->update = -1;
    a->animation = NULL;
}

rt_scene *cli_scene_open(const char *command, const char *source, const cli_scene_args *a,
                         int threads) {
    rt_scene *s = NULL;
    rt_error err;
    if (rt_scene_open(source, &s, &err) != RT_OK) {
        cli_error(command, "%s", err.message);
        return NULL;
    }
    /* The loader's notices (a material name defined twice), a line each. */
    for (const char *p = rt_scene_notices(s); *p;) {
        const char *eol = strchr(p, '\n');
        int n = eol ? (int)(eol - p) : (int)strlen(p);
        fprintf(stderr, "rtcl %s: notice: %.*s\n", command, n, p);
        p += n + (eol ? 1 : 0);
    }
    rt_scene_set_threads(s, threads);
    if ((a->accel >= 0 && rt_scene_set_static_accel(s, (rt_accel)a->accel) != RT_OK) ||
        (a->animation && rt_scene_select_clip(s, a->animation) != RT_OK) ||
        (!isnan(a->time) && rt_scene_set_time(s, a->time) != RT_OK)) {
        cli_error(command, "%s", rt_scene_error(s));
        rt_scene_destroy(s);
        return NULL;
    }
    if (a->update >= 0) {
        rt_scene_info info;
        rt_scene_describe(s, &info);
        for (uint32_t m = 0; m < info.meshes; m++)
            rt_mesh_set_update(s, m, (rt_update_policy)a->update);
    }
    return s;
}

const cli_option cli_update_options[] = {
    {"--update", 0, CLI_CHOICE, "P", offsetof(cli_scene_args, update), .choice_name = update_name,
     .choice_parse = update_parse,
     .help = "every mesh's BVH update policy after its vertices move: {choices} "
             "(docs/SCENE_FORMAT.md; the names before 0.2, rebuild for sah and fast for lbvh, "
             "are read too); all give the same bits",
     .fallback = "each mesh's \"update\" in the scene file, else sah"},
    {NULL}};

/* ---- image options -------------------------------------------------------- */

const cli_option cli_frame_options[] = {
    {"--width", 0, CLI_INT, "W", offsetof(cli_frame_args, width), 1, 32768,
     .help = "image width in pixels, overriding the scene camera's", .fallback = "the scene's"},
    {"--height", 0, CLI_INT, "H", offsetof(cli_frame_args, height), 1, 32768,
     .help = "image height in pixels, overriding the scene camera's", .fallback = "the scene's"},
    {"--direct", 0, CLI_FLAG, NULL, offsetof(cli_frame_args, direct),
     .help = "primary and shadow rays only, no reflection or refraction (the thesis's benchmark "
             "set-up)"},
    {NULL}};

const cli_option cli_aov_options[] = {
    {"--aov", 0, CLI_CHOICE, "AOV", offsetof(cli_frame_args, aov), .choices = cli_aov_choices,
     .help = "an arbitrary output variable instead of the shaded image: {choices}. In EXR the "
             "raw values; in 8-bit formats depth and counters scaled to [0,1] by their maximum, "
             "ids in false colour, normals as 0.5 + 0.5 n",
     .fallback = "the shaded image"},
    {NULL}};

const cli_option cli_sample_options[] = {
    {"--spp", 0, CLI_INT, "N", offsetof(cli_frame_args, spp), 1, RT_MAX_SAMPLES,
     .help = "samples per pixel of the shaded image: N passes, each with every primary ray "
             "through the same point of its pixel (a k x k grid when N = k * k, else stratified "
             "columns), averaged; each pass, and so the image, is the same on every backend",
     .fallback = "1: the pixel's centre"},
    {"--exposure", 0, CLI_FLOAT, "EV", offsetof(cli_frame_args, exposure), -64.0, 64.0,
     .help = "multiply the shaded image by 2^EV (stops), overriding the scene's \"exposure\"",
     .fallback = "the scene's, else 0"},
    {NULL}};

void cli_frame_args_init(cli_frame_args *a) {
    memset(a, 0, sizeof *a);
    a->aov = RT_AOV_NONE;
    a->exposure = NAN;
}

int cli_apply_frame_size(const char *command, rt_scene *scene, const cli_frame_args *a) {
    rt_camera cam;
    rt_camera_get(scene, &cam);
    if (a->width) cam.width = a->width;
    if (a->height) cam.height = a->height;
    if (rt_camera_set(scene, &cam) != RT_OK ||
        (!isnan(a->exposure) && rt_scene_set_exposure(scene, (float)a->exposure) != RT_OK)) {
        cli_error(command, "%s", rt_scene_error(scene));
        return 0;
    }
    return 1;
}

/* ---- renderer options ---------------------------------------------------- */

/* --backend's help from the backend registry: every backend, what it is,
 * and whether this build has it. */
static void backend_help(const char *help, char *buf, size_t cap) {
    size_t used = (size_t)snprintf(buf, cap, "the backend:");
    rt_backend_info b;
    for (int i = 0; rt_backend_name(i) && used < cap; i++) {
        if (rt_backend_describe(rt_backend_name(i), &b, NULL) != RT_OK) continue;
        const char *exact = !strcmp(b.name, "auto") ? ""
                            : b.exact_always        ? "; the CPU oracle's bits everywhere"
                                                    : "; the oracle's bits where the device "
                                                      "promises them (rtcl devices)";
        used += (size_t)snprintf(buf + used, cap - used, "\n%s%s: %s%s%s", b.name,
                                 b.takes_device ? "[:D]" : "", b.summary, exact,
                                 b.built ? "" : " (not in this build)");
    }
    if (used < cap)
        snprintf(buf + used, cap - used,
                 "\nA device backend fails when it finds no device; :D picks one, as --device");
}

static const cli_choice lane_choices[] = {{"4", 4}, {"8", 8}, {"16", 16}, {NULL, 0}};

const cli_choice cli_device_math_choices[] = {{"auto", RT_DEVICE_MATH_AUTO},
                                              {"native", RT_DEVICE_MATH_NATIVE},
                                              {"portable", RT_DEVICE_MATH_PORTABLE},
                                              {NULL, 0}};
const cli_choice cli_denormals_choices[] = {
    {"preserve", RT_DENORMALS_PRESERVE}, {"flush", RT_DENORMALS_FLUSH}, {NULL, 0}};

/* Row 0 is --backend (cli_util.h: rtcl view replaces it). */
const cli_option cli_renderer_options[] = {
    {"--backend", 0, CLI_STRING, "B", offsetof(cli_renderer_args, backend), .flags = CLI_NONEMPTY,
     .dynamic_help = backend_help, .fallback = "cpu"},
    {"--device", 0, CLI_STRING, "D", offsetof(cli_renderer_args, device), .flags = CLI_NONEMPTY,
     .help = "the device of a device backend (or of the one auto picks): an index or a part of "
             "its name, as 'rtcl devices' lists them",
     .fallback = "the first device, an exact one where there is one"},
    {"--threads", 0, CLI_INT, "N", offsetof(cli_renderer_args, threads), 0, 1024,
     .help = "worker threads of the CPU backends and the BVH builders, 0: one per core",
     .fallback = "0"},
    {"--packet-isa", 0, CLI_STRING, "I", offsetof(cli_renderer_args, packet_isa),
     .flags = CLI_NONEMPTY,
     .help = "the packet backend's instruction set: generic, avx2 or avx512 (x86-64); all give "
             "the same bits",
     .fallback = "the widest the CPU runs"},
    {"--verbose", 0, CLI_FLAG, NULL, offsetof(cli_renderer_args, verbose),
     .help = "print the backend and device that ran, and the device compiler's messages (the "
             "build log, and what the driver printed while building), on stderr; without it "
             "the build messages are shown only when the kernels fail to build"},
    {NULL}};

const cli_option cli_backend_auto_options[] = {
    {"--backend", 0, CLI_STRING, "B", offsetof(cli_renderer_args, backend), .flags = CLI_NONEMPTY,
     .dynamic_help = backend_help, .fallback = "auto"},
    {NULL}};

const cli_option cli_kernel_options[] = {
    {"--cl-options", 0, CLI_STRING, "OPTS", offsetof(cli_renderer_args, cl_options),
     .help = "extra OpenCL compiler options, e.g. -cl-mad-enable, -cl-fast-relaxed-math, "
             "-DRT_NATIVE_MATH, appended to the kernels' build; results may then differ from the "
             "CPU oracle, and --stats says so (the speed-versus-error study)",
     .fallback = "none: the exact build"},
    {"--device-math", 0, CLI_CHOICE, "M", offsetof(cli_renderer_args, device_math),
     .choices = cli_device_math_choices,
     .help = "device backends' divide and sqrt: {choices} (native: the device's, correctly "
             "rounded where it promises it; portable: software, from integer operations, exact "
             "on any conforming device; auto: native where promised, else portable); --stats "
             "says which ran",
     .fallback = "auto"},
    {"--denormals", 0, CLI_CHOICE, "P", offsetof(cli_renderer_args, denormals),
     .choices = cli_denormals_choices,
     .help = "{choices}: IEEE gradual underflow, or flush-to-zero and denormals-are-zero as "
             "most GPUs do (the CPU backends set their threads' FTZ/DAZ, kernels are built with "
             "-cl-denorms-are-zero); compare a device with the oracle in the mode 'rtcl devices' "
             "names",
     .fallback = "preserve"},
    {NULL}};

const cli_option cli_test_options[] = {
    {"--cl-one-ray", 0, CLI_FLAG, NULL, offsetof(cli_renderer_args, cl_one_ray),
     .help = "OpenCL: one ray per work-item on CPU devices too"},
    {"--cl-packet-lanes", 0, CLI_CHOICE, "N", offsetof(cli_renderer_args, cl_packet_lanes),
     .choices = lane_choices,
     .help = "OpenCL on CPU devices: {choices} rays per work-item (2x2, 4x2, 4x4)",
     .fallback = "16"},
    {"--cl-no-wavefront", 0, CLI_FLAG, NULL, offsetof(cli_renderer_args, cl_no_wavefront),
     .help = "OpenCL: shade every image in one kernel, never as wavefront passes"},
    {"--cl-wave-cap", 0, CLI_INT, "N", offsetof(cli_renderer_args, cl_wave_cap), 1, 1 << 30,
     .help = "OpenCL: wavefront queues of at most N rays (they overflow sooner)",
     .fallback = "the tile's size"},
    {NULL}};

void cli_renderer_args_init(cli_renderer_args *a) {
    memset(a, 0, sizeof *a);
    a->backend = "cpu";
    a->device_math = RT_DEVICE_MATH_AUTO;
    a->denormals = RT_DENORMALS_PRESERVE;
}

/* The backend's name in spec (NAME or NAME:DEVICE) into buf. */
static void backend_of(const char *spec, char *buf, size_t cap) {
    const char *colon = strchr(spec, ':');
    size_t n = colon ? (size_t)(colon - spec) : strlen(spec);
    snprintf(buf, cap, "%.*s", (int)(n < cap ? n : cap - 1), spec);
}

int cli_backend_takes_device(const char *spec) {
    char name[64];
    backend_of(spec, name, sizeof name);
    rt_backend_info b;
    return rt_backend_describe(name, &b, NULL) == RT_OK && b.takes_device;
}

/* "opencl, vulkan or auto": the backends that take a device. */
static void device_backends(char *buf, size_t cap) {
    size_t used = 0;
    int count = 0, total = 0;
    rt_backend_info b;
    for (int i = 0; rt_backend_name(i); i++)
        total += rt_backend_describe(rt_backend_name(i), &b, NULL) == RT_OK && b.takes_device;
    buf[0] = '\0';
    for (int i = 0; rt_backend_name(i) && used < cap; i++) {
        if (rt_backend_describe(rt_backend_name(i), &b, NULL) != RT_OK || !b.takes_device) continue;
        count++;
        const char *sep = count == 1 ? "" : count == total ? " or " : ", ";
        used += (size_t)snprintf(buf + used, cap - used, "%s%s", sep, b.name);
    }
}

/* rt_renderer_options.on_compile: one line on a terminal before the first
 * kernel build from source of the process (a pipe or a log file gets
 * nothing: tests and scripts see no noise). user is the command's name. */
static void compile_notice(void *user, const char *backend, const char *device,
                           const char *cache_dir) {
    static int shown;
    if (shown || !isatty(STDERR_FILENO)) return;
    shown = 1;
    cli_progress_done();
    if (cache_dir)
        fprintf(stderr, "rtcl %s: compiling the %s kernels for %s (once; cached in %s)\n",
                (const char *)user, !strcmp(backend, "opencl") ? "OpenCL" : backend, device,
                cache_dir);
    else
        fprintf(stderr,
                "rtcl %s: compiling the %s kernels for %s (not cached: RTCL_CACHE_DIR=off "
                "or no writable cache folder)\n",
                (const char *)user, !strcmp(backend, "opencl") ? "OpenCL" : backend, device);
    fflush(stderr);
}

rt_renderer *cli_renderer_create(const char *command, cli_renderer_args *a) {
    if (a->device) {
        if (!cli_backend_takes_device(a->backend) || strchr(a->backend, ':')) {
            char names[128];
            device_backends(names, sizeof names);
            if (strchr(a->backend, ':'))
                cli_error(command, "--device %s and --backend %s both name a device: give one",
                          a->device, a->backend);
            else
                cli_error(command, "--device applies to --backend %s, not '%s'", names, a->backend);
            return NULL;
        }
        snprintf(a->spec, sizeof a->spec, "%s:%s", a->backend, a->device);
    } else {
        snprintf(a->spec, sizeof a->spec, "%s", a->backend);
    }
    rt_renderer_options o = rt_renderer_options_default();
    o.backend = a->spec;
    o.threads = a->threads;
    o.device_options = a->cl_options;
    o.packet_isa = a->packet_isa;
    o.device_math = (rt_device_math)a->device_math;
    o.denormals = (rt_denormals)a->denormals;
    o.opencl.one_ray_kernels = a->cl_one_ray;
    o.opencl.no_wavefront = a->cl_no_wavefront;
    o.opencl.packet_lanes = a->cl_packet_lanes;
    o.opencl.wave_queue_cap = (uint32_t)a->cl_wave_cap;
    o.on_compile = compile_notice;
    o.on_compile_user = (void *)command;
    rt_renderer *r = NULL;
    rt_error err;
    memset(&err, 0, sizeof err);
    if (rt_renderer_create(&o, &r, &err) != RT_OK) {
        cli_error(command, "%s", err.message);
        return NULL;
    }
    return r;
}

void cli_args_init(cli_frame_args *frame, cli_scene_args *scene, cli_renderer_args *renderer) {
    if (frame) cli_frame_args_init(frame);
    if (scene) cli_scene_args_init(scene);
    if (renderer) cli_renderer_args_init(renderer);
}

int cli_session_open(cli_session *out, const char *command, const char *source,
                     cli_renderer_args *renderer, const cli_scene_args *scene,
                     const cli_frame_args *frame) {
    out->scene = NULL;
    out->renderer = cli_renderer_create(command, renderer);
    if (out->renderer) out->scene = cli_scene_open(command, source, scene, renderer->threads);
    if (out->scene && (!frame || cli_apply_frame_size(command, out->scene, frame))) return 1;
    cli_session_close(out);
    return 0;
}

void cli_session_close(cli_session *out) {
    rt_scene_destroy(out->scene);
    rt_renderer_destroy(out->renderer);
    out->scene = NULL;
    out->renderer = NULL;
}

void cli_print_backend_choice(const char *command, const cli_renderer_args *a, const char *backend,
                              const char *device, const char *notice) {
    if (notice) {
        fprintf(stderr, "rtcl %s: notice: %s\n", command, notice);
    } else if (a->verbose && backend) {
        fprintf(stderr, "rtcl %s: backend: %s (%s)\n", command, backend,
                device && device[0] ? device : "the CPU");
    }
}

const char *cli_backend_text(const char *backend, const char *device, char *buf, size_t cap) {
    if (device && device[0])
        snprintf(buf, cap, "backend %s, %s", backend ? backend : "?", device);
    else
        snprintf(buf, cap, "backend %s", backend ? backend : "?");
    return buf;
}

void cli_print_build_log(const char *command, const rt_renderer *renderer) {
    const char *log = rt_renderer_build_log(renderer);
    if (log[0])
        fprintf(stderr, "rtcl %s: %s build log:\n%s\n", command, rt_renderer_backend(renderer),
                log);
}
