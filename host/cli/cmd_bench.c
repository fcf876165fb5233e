/* SPDX-License-Identifier: Apache-2.0 */
/* cmd_bench.c - 'rtcl bench': the command line of the benchmark engines
 * (bench/engines/): BVH builds and renders beside Embree (bench_build.h),
 * the keyframe benchmark (--animate, bench_animate.h) and incoherent rays
 * (--incoherent, incoherent_bench.h). The engines measure and print; this
 * file reads the options and says which apply to which benchmark. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "cli_util.h"
#include "commands.h"
#include "engines/bench_animate.h"
#include "engines/bench_build.h"
#include "engines/bench_print.h"
#include "engines/incoherent_bench.h"

typedef struct bench_args {
    int json, reps, threads, no_render, width, height;
    int accel, device_math, denormals, verbose; /* build and render */
    int animate, frames, series;                /* --animate */
    double fps;
    const char *animation; /* --animation (glTF clip) */
    int incoherent, rays;  /* --incoherent */
} bench_args;

static const cli_option bench_options[] = {
    {"--json", 0, CLI_FLAG, NULL, offsetof(bench_args, json),
     .help = "one JSON object per scene per line (without --animate or --incoherent: \"build\", "
             "\"reference\" and \"render\" arrays)"},
    {"--reps", 0, CLI_INT, "N", offsetof(bench_args, reps), 1, 1000,
     .help = "timed repetitions, frames or rounds, after one warm-up that is not counted",
     .fallback = "5"},
    {"--threads", 0, CLI_INT, "N", offsetof(bench_args, threads), 1, 1000,
     .help = "threads of the threaded builders, the renderers and Embree (PoCL uses its own "
             "pool of all cores)",
     .fallback = "all cores"},
    {"--width", 0, CLI_INT, "W", offsetof(bench_args, width), 1, 32768, .help = "the frames' width",
     .fallback = "1024, the thesis's"},
    {"--height", 0, CLI_INT, "H", offsetof(bench_args, height), 1, 32768,
     .help = "the frames' height", .fallback = "576"},
    {"--no-render", 0, CLI_FLAG, NULL, offsetof(bench_args, no_render),
     .help = "builds only (with --incoherent: no Whitted frames); not with --animate"},
    {NULL}};

static const cli_option build_options[] = {
    {"--accel", 0, CLI_CHOICE, "A", offsetof(bench_args, accel), .choice_name = cli_accel_name,
     .help = "{choices}: the structure of every static mesh in the render part; kd and "
             "kd-binned also add the build rows kd-exact and kd-binned (one SAH kd-tree over all "
             "triangles, SAH with Ct = 1, Ci = 2 as for the BVH rows, and bytes)",
     .fallback = "each mesh's own"},
    {"--device-math", 0, CLI_CHOICE, "M", offsetof(bench_args, device_math),
     .choices = cli_device_math_choices,
     .help = "the opencl row's maths profile: {choices}; with portable there is no separate "
             "opencl-portable row",
     .fallback = "auto"},
    {"--denormals", 0, CLI_CHOICE, "P", offsetof(bench_args, denormals),
     .choices = cli_denormals_choices, .help = "{choices}, for every row", .fallback = "preserve"},
    {"--verbose", 0, CLI_FLAG, NULL, offsetof(bench_args, verbose),
     .help = "print the device compiler's messages (build log) on stderr"},
    {NULL}};

static const cli_option animate_options[] = {
    {"--animate", 0, CLI_FLAG, NULL, offsetof(bench_args, animate),
     .help =
         "the keyframe benchmark instead (Langr 2016, section 4.1): each SCENE's first "
         "morphing object played frame by frame, frame k at time k/F, on the packet backend "
         "with the update policies sah, refit, lbvh and auto, beside Embree (when built "
         "with it) updating and tracing the same frames at build quality REFIT, LOW and "
         "MEDIUM (its widest packets); N runs, rows interleaved frame by frame; per row the "
         "mesh update, trace and whole-frame ms (the update included), each a mean over the "
         "frames (min and median over the runs), the SAH cost (Embree's: of rtcBuildBVH's "
         "trees of that quality) and whether every frame's image is the sah policy's, bit for bit; "
         "with --json a \"dynamic\" array per scene. Frame 0 (the first build) is not "
         "counted"},
    {"--frames", 0, CLI_INT, "K", offsetof(bench_args, frames), 1, 100000,
     .help = "frames after frame 0", .fallback = "one per keyframe"},
    {"--fps", 0, CLI_FLOAT, "F", offsetof(bench_args, fps), 0.0, 100000.0, CLI_MIN_OPEN,
     .help = "frames per second", .fallback = "the keyframe rate"},
    {"--series", 0, CLI_FLAG, NULL, offsetof(bench_args, series),
     .help = "with --json: each row's per-frame medians too"},
    {"--animation", 0, CLI_STRING, "CLIP", offsetof(bench_args, animation), .flags = CLI_NONEMPTY,
     .help = "a glTF scene's clip, by name or index: a glTF scene without a morphing object "
             "plays it (skinned meshes deform, rigid parts move as objects)",
     .fallback = "its first"},
    {NULL}};

static const cli_option incoherent_options[] = {
    {"--incoherent", 0, CLI_FLAG, NULL, offsetof(bench_args, incoherent),
     .help = "the incoherent-ray benchmark instead: per SCENE two sets of rays (diffuse bounces "
             "from the camera rays' closest hits, random rays inside the scene; fixed seed 7), "
             "each traced for the closest hit and for any hit by rt_trace_rays on cpu (the "
             "oracle) and packet (auto path), and by Embree's rtcIntersect1/rtcOccluded1 and "
             "rtcIntersect16/rtcOccluded16 (16 consecutive rays per call) where this build has "
             "Embree (else the output says why its rows are absent), same thread count; min and "
             "median ms and Mrays/s over N rounds after a warm-up round (interleaved), speed "
             "against Embree, packet hits unlike the oracle's; then Whitted frames (W x H) on "
             "packet and cpu. With --json an \"incoherent\" array of {scene, rays, query, engine, "
             "path, ms_min, ms_median, mrays_min, mrays_median, ...} and a \"whitted\" array per "
             "scene"},
    {"--rays", 0, CLI_INT, "N", offsetof(bench_args, rays), 1, 100000000, .help = "rays per set",
     .fallback = "1000000"},
    {NULL}};

static const cli_group bench_groups[] = {
    {NULL, bench_options, 0},
    {"Builds and renders (without --animate or --incoherent)", build_options, 0},
    {"The keyframe benchmark", animate_options, 0},
    {"Incoherent rays", incoherent_options, 0},
    {NULL}};

const cli_command cmd_bench_spec = {
    "bench",
    "measure BVH builds and renders on scenes, beside Embree",
    "SCENE...",
    "scene",
    1,
    -1,
    "Each SCENE is a .json scene, a bare .obj, a .gltf or .glb, or builtin:NAME.\n"
    "\n"
    "Build: one BVH over all triangles of each scene with every builder\n"
    "(thesis-scalar, thesis-neon, thesis-mt, fast, and embree when available):\n"
    "min and median build time over N repetitions (after one warm-up run that\n"
    "is not counted), SAH cost and node count. Embree's rtcCommitScene at low\n"
    "and medium quality is shown for reference.\n"
    "Render: the thesis's set-up (one point light, primary plus shadow rays,\n"
    "Phong) on the backends cpu, packet, opencl, opencl-portable (the\n"
    "portable maths profile: software divide and sqrt) and vulkan (always the\n"
    "portable profile), and Embree tracing the same rays (rtcIntersect1,\n"
    "packets of 4, 8 and 16 where native, rtcOccluded for shadow rays) with the\n"
    "same thread count: min and median frame time over N frames after one\n"
    "warm-up frame (frames interleaved round by round over every backend and\n"
    "width, so that a busy machine slows them alike; each timed frame follows an\n"
    "untimed one of its own, for its own warm caches), Mrays/s, box and triangle\n"
    "tests per ray, pixels that differ from the cpu oracle's image, and each rate\n"
    "against Embree's fastest packet width.\n",
    bench_groups,
    NULL,
    NULL};

static void print_build_log(const rt_renderer *renderer) {
    cli_print_build_log("bench", renderer);
}

/* Options of one benchmark given to another would be ignored: the reason
 * they are refused, or NULL. */
static const char *misplaced(const bench_args *a) {
    int maths = a->device_math != RT_DEVICE_MATH_AUTO || a->denormals != RT_DENORMALS_PRESERVE;
    int animate_only = a->frames || a->fps > 0.0 || a->series || a->animation;
    /* The first rule that holds gives the reason. */
    const struct {
        int holds;
        const char *reason;
    } rules[] = {
        {a->animate && a->incoherent,
         "--animate and --incoherent are two benchmarks: run one at a time"},
        {a->animate && a->accel >= 0,
         "--accel does not apply to --animate (morphing meshes keep BVHs)"},
        {a->animate && a->no_render,
         "--no-render does not apply to --animate (it renders every frame)"},
        {a->animate && maths,
         "--device-math and --denormals do not apply to --animate (it runs the packet backend)"},
        {a->animate && a->verbose,
         "--verbose does not apply to --animate (it runs the packet backend)"},
        {!a->animate && animate_only, "--frames, --fps, --series and --animation need --animate"},
        {a->incoherent && a->accel >= 0,
         "--accel does not apply to --incoherent (it traces the scene's own structures)"},
        {a->incoherent && maths,
         "--device-math and --denormals do not apply to --incoherent (it runs the CPU backends)"},
        {a->incoherent && a->verbose,
         "--verbose does not apply to --incoherent (it runs the CPU backends)"},
        {a->rays && !a->incoherent, "--rays applies to --incoherent only"},
    };
    for (size_t i = 0; i < sizeof rules / sizeof rules[0]; i++)
        if (rules[i].holds) return rules[i].reason;
    return NULL;
}

int cmd_bench(int argc, char **argv) {
    bench_args a;
    memset(&a, 0, sizeof a);
    a.reps = 5;
    a.width = 1024;
    a.height = 576;
    a.accel = -1;
    a.device_math = RT_DEVICE_MATH_AUTO;
    a.denormals = RT_DENORMALS_PRESERVE;
    int status, n = cli_parse(&cmd_bench_spec, &a, argc, argv, &status);
    if (n < 0) return status;
    const char *odd = misplaced(&a);
    if (odd) {
        cli_usage_error(&cmd_bench_spec, "%s", odd);
        return 2;
    }
    if (a.threads <= 0) {
        long cores = sysconf(_SC_NPROCESSORS_ONLN);
        a.threads = cores < 1 ? 1 : (int)cores;
    }
    const char *const *scenes = (const char *const *)argv;
    void (*progress)(const char *, const char *) = isatty(2) ? bench_progress_line : NULL;
    if (a.incoherent) {
        incoh_setup su = incoh_setup_default();
        if (a.rays) su.rays = (size_t)a.rays;
        su.reps = a.reps;
        su.threads = a.threads;
        su.width = a.width;
        su.height = a.height;
        su.whitted = !a.no_render;
        su.progress = progress;
        return incoh_run(scenes, n, &su, a.json, "rtcl bench");
    }
    if (a.animate) {
        bench_anim_setup su = {a.reps,   a.frames, a.fps, a.threads, a.width,
                               a.height, "packet", 1,     progress,  a.animation};
        return bench_anim_run(scenes, n, &su, a.json, a.series, "rtcl bench");
    }
    bench_build_setup su = {"rtcl bench",
                            a.json,
                            a.reps,
                            a.threads,
                            progress != NULL,
                            !a.no_render,
                            a.width,
                            a.height,
                            (rt_device_math)a.device_math,
                            (rt_denormals)a.denormals,
                            a.accel,
                            a.verbose ? print_build_log : NULL};
    return bench_build_run(scenes, n, &su);
}
