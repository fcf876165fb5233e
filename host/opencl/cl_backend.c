/* SPDX-License-Identifier: Apache-2.0 */
/* cl_backend.c - the OpenCL backend (host/backend/backend.h): device state
 * kept by the renderer, uploads of what changed, the kernel program
 * specialised to the scene, and frames rendered in bounded tiles
 * (kernels/rt_single_ray.cl).
 *
 * The kernels compute with the CPU oracle's header, built with no contraction
 * and correctly rounded division and sqrt, so on a device that promises both
 * (and fp64) the results are the oracle's bits. Extra build options
 * (rt_renderer_options.device_options, for the speed-versus-error study) are
 * appended to the program's options; the results are then not promised. */
#include <CL/cl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "backend/upload_plan.h"
#include "base/error.h"
#include "opencl/cl_backend.h"
#include "opencl/cl_device.h"
#include "opencl/cl_program_cache.h"
#include "opencl/cl_stderr.h"
#include "rt_kernel_arg_index.h"
#include "rt_shade.h" /* rt_wave_entry, rt_wave_record: the wavefront's buffers */

/* Generated from kernels/ at build time. */
extern const char rt_cl_source_rt_single_ray[];
extern const char rt_cl_source_rt_ray_packet[];

/* Tile sizes in pixels: adapted per frame so that one launch stays near
 * RT_CL_TARGET_MS (a GPU watchdog fires after a few seconds; we keep far from
 * it), within [RT_CL_TILE_MIN, RT_CL_TILE_MAX]. */
#define RT_CL_TILE_MIN   1024u
#define RT_CL_TILE_MAX   (1u << 18)
#define RT_CL_TILE_FIRST 16384u
#define RT_CL_TARGET_MS  50.0
/* The wavefront keeps one rt_wave_record per node of the full shading tree
 * (2^(max_depth + 1) - 1) per pixel of a tile: its tiles are capped so that
 * buffer stays within this many bytes. */
#define RT_CL_WAVE_RECORD_BYTES (64u << 20)

/* ---- device state ------------------------------------------------------- */

/* The buffers are RT_CL_BUF_* of the GPU interface table
 * (kernels/rt_interface.def): the view's first, in the order of their
 * kernel arguments (RT_ARG_*) and of the upload plan's arrays. */
_Static_assert((int)RT_CL_BUF_HDR == (int)RT_ARG_HDR &&
                   (int)RT_CL_BUF_LIGHTS == (int)RT_ARG_LIGHTS &&
                   (int)RT_CL_BUF_KD_NODES == (int)RT_ARG_KD_NODES,
               "the view buffers are the view arguments, in order");

typedef struct cl_state {
    rt_cl_device_info dev;
    char selector[128];       /* the device this state was made for ("": the default) */
    char device_options[256]; /* the renderer's extra build options ("": the exact build) */
    rt_opencl_tuning tune;    /* the renderer's kernel choices (tests, comparisons) */
    rt_device_math math;      /* the maths profile asked for ... */
    int flush;                /* ... and the denormal policy (1: flush) */
    rt_cl_math_plan plan;     /* what they give on the device (after open_device) */
    int probed_flush;         /* needs_probe: 1 when the probe saw the device flush */
    void (*on_compile)(void *user, const char *backend, const char *device, const char *cache_dir);
    void *on_compile_user;
    cl_context ctx;
    cl_command_queue queue;
    cl_program program;
    char options[768]; /* the program's build options (the cache key) */
    char defines[192]; /* the specialisation part of options */
    cl_kernel k_camera, k_trace, k_shade;
    cl_kernel k_wcam, k_wtrace, k_wshade, k_wsum; /* the wavefront */
    cl_kernel k_packet, k_ptrace;                 /* CPU devices: rt_k_packet, rt_k_packet_trace */
    int lanes; /* the program's packet lanes (RT_PK_LANES); 0: no packet kernel */
    cl_mem buf[RT_CL_BUF_COUNT];
    size_t cap[RT_CL_BUF_COUNT];
    /* The completion check: per kernel (RT_CL_DONE_*), the work-items launched
     * since the DONE buffer was last cleared (done_begin, done_check). */
    uint32_t launched[RT_CL_DONE_COUNT];
    unsigned test_skip;  /* RTCL_TEST_OPENCL_SKIP: fault injection (-DRT_TEST_SKIP), 0: off */
    rt_upload_memo memo; /* what the device holds of the layout */
    uint32_t tile;
    /* The last program build's messages: the compiler's log, then what the
     * driver printed on stderr meanwhile (cl_stderr.h). NULL: none yet. */
    char *build_log;
} cl_state;

static void release_wave_kernels(cl_state *s) {
    cl_kernel *k[6] = {&s->k_wcam, &s->k_wtrace, &s->k_wshade,
                       &s->k_wsum, &s->k_packet, &s->k_ptrace};
    for (int i = 0; i < 6; i++) {
        if (*k[i]) clReleaseKernel(*k[i]);
        *k[i] = NULL;
    }
}

static void cl_destroy(void *p) {
    cl_state *s = p;
    if (!s) return;
    for (int i = 0; i < RT_CL_BUF_COUNT; i++)
        if (s->buf[i]) clReleaseMemObject(s->buf[i]);
    if (s->k_camera) clReleaseKernel(s->k_camera);
    if (s->k_trace) clReleaseKernel(s->k_trace);
    if (s->k_shade) clReleaseKernel(s->k_shade);
    release_wave_kernels(s);
    if (s->program) clReleaseProgram(s->program);
    if (s->queue) clReleaseCommandQueue(s->queue);
    if (s->ctx) clReleaseContext(s->ctx);
    rt_upload_memo_free(&s->memo);
    free(s->build_log);
    free(s);
}

static rt_status cl_create(const rt_backend_config *config, void **state, rt_error *err) {
    cl_state *s = calloc(1, sizeof *s);
    if (!s) return rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "opencl: out of memory");
    snprintf(s->selector, sizeof s->selector, "%s", config->device ? config->device : "");
    snprintf(s->device_options, sizeof s->device_options, "%s",
             config->device_options ? config->device_options : "");
    s->tune = config->opencl;
    s->math = config->device_math;
    s->flush = config->flush_denormals;
    s->on_compile = config->on_compile;
    s->on_compile_user = config->on_compile_user;
    s->tile = RT_CL_TILE_FIRST;
    /* Tests only: kernels built to leave every Nth work-item unfinished
     * (rt_kernel_args.h, RT_TEST_SKIP), so that the completion check must
     * fail the frame or the query. */
    const char *skip = getenv("RTCL_TEST_OPENCL_SKIP");
    if (skip && *skip) {
        char *end;
        unsigned long n = strtoul(skip, &end, 10);
        if (*end || n < 1 || n > 1000000u) {
            free(s);
            return rt_fail(err, RT_ERROR_INVALID_ARGUMENT,
                           "opencl: RTCL_TEST_OPENCL_SKIP must be a whole number 1..1000000, not "
                           "'%.64s'",
                           skip);
        }
        s->test_skip = (unsigned)n;
    }
    *state = s;
    return RT_OK;
}

/* Opens the selected device: its context and queue (at the first frame). */
static rt_status open_device(cl_state *s, rt_error *err) {
    rt_cl_device_info *devs;
    int count;
    rt_status st = rt_cl_devices(&devs, &count, err);
    if (st != RT_OK) return st;
    int pick = rt_cl_select(devs, count, s->selector, err);
    if (pick < 0) {
        free(devs);
        return RT_ERROR_INVALID_ARGUMENT;
    }
    s->dev = devs[pick];
    free(devs);
    cl_device_id d = s->dev.device_id;
    cl_context_properties props[] = {CL_CONTEXT_PLATFORM, (cl_context_properties)s->dev.platform_id,
                                     0};
    cl_int ce;
    s->ctx = clCreateContext(props, 1, &d, NULL, NULL, &ce);
    if (!s->ctx)
        return rt_fail(err, RT_ERROR_BACKEND, "OpenCL context on '%s': %s", s->dev.name,
                       rt_cl_error_name(ce));
    s->queue = clCreateCommandQueue(s->ctx, d, CL_QUEUE_PROFILING_ENABLE, &ce);
    if (!s->queue)
        return rt_fail(err, RT_ERROR_BACKEND, "OpenCL queue on '%s': %s", s->dev.name,
                       rt_cl_error_name(ce));
    s->plan = rt_cl_plan_math(&s->dev, s->math, s->flush);
    return RT_OK;
}

/* The denormal options of every program: the policy's. */
static const char *denormal_options(const cl_state *s) {
    return s->plan.flush ? "-cl-denorms-are-zero -DRT_FLUSH_DENORMALS " : "";
}

/* Whether the device flushes under -cl-denorms-are-zero: a device that keeps
 * denormals may (the option permits it, it does not demand it). A product
 * with a subnormal result and a subnormal input times 2^100 must both give
 * zero; the inputs come from a buffer, so nothing folds at compile time. */
static const char probe_source[] =
    "__kernel void rt_k_denorm_probe(__global const float *in, __global float *out) {\n"
    "    out[0] = in[0] * in[1];\n"
    "    out[1] = in[2] * in[3];\n"
    "}\n";

static rt_status probe_flush(cl_state *s, int *flushes, rt_error *err) {
    const char *src = probe_source;
    cl_device_id d = s->dev.device_id;
    cl_int ce;
    cl_program prog = clCreateProgramWithSource(s->ctx, 1, &src, NULL, &ce);
    cl_kernel k = NULL;
    cl_mem in = NULL, out = NULL;
    /* 2^-70 * 2^-70 = 2^-140 (subnormal); 2^-140 * 2^100 = 2^-40 (normal). */
    float vin[4] = {0x1p-70f, 0x1p-70f, 0x1p-140f, 0x1p100f}, vout[2] = {1.0f, 1.0f};
    if (prog) { /* quiet, as every build (cl_stderr.h); a probe's messages are not kept */
        rt_cl_stderr capture;
        rt_cl_stderr_begin(&capture);
        ce = clBuildProgram(prog, 1, &d, denormal_options(s), NULL, NULL);
        free(rt_cl_stderr_end(&capture));
    }
    if (prog && ce == CL_SUCCESS) k = clCreateKernel(prog, "rt_k_denorm_probe", &ce);
    if (k)
        in = clCreateBuffer(s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof vin, vin, &ce);
    if (in) out = clCreateBuffer(s->ctx, CL_MEM_WRITE_ONLY, sizeof vout, NULL, &ce);
    if (out) ce = clSetKernelArg(k, 0, sizeof in, &in);
    if (out && ce == CL_SUCCESS) ce = clSetKernelArg(k, 1, sizeof out, &out);
    size_t one = 1;
    if (out && ce == CL_SUCCESS)
        ce = clEnqueueNDRangeKernel(s->queue, k, 1, NULL, &one, NULL, 0, NULL, NULL);
    if (out && ce == CL_SUCCESS)
        ce = clEnqueueReadBuffer(s->queue, out, CL_TRUE, 0, sizeof vout, vout, 0, NULL, NULL);
    int ok = out && ce == CL_SUCCESS;
    if (out) clReleaseMemObject(out);
    if (in) clReleaseMemObject(in);
    if (k) clReleaseKernel(k);
    if (prog) clReleaseProgram(prog);
    if (!ok)
        return rt_fail(err, RT_ERROR_BACKEND, "denormal probe on '%s': %s", s->dev.name,
                       rt_cl_error_name(ce));
    *flushes = vout[0] == 0.0f && vout[1] == 0.0f;
    return RT_OK;
}

/* ---- the program -------------------------------------------------------- */

/* The -D switches for the scene: its header flags (secondary rays, single
 * identity instance, normals, per-triangle materials) and triangle test, so
 * the compiler drops what the scene does not use. */
static void scene_defines(const rt_flat *f, char *out, size_t size) {
    uint32_t flags = f->hdr.flags;
    uint32_t inst_set = (flags & RT_SCENE_SINGLE) ? RT_INST_IDENTITY : 0u;
    uint32_t inst_mask = RT_INST_IDENTITY | ((flags & RT_SCENE_NORMALS) ? RT_INST_NORMALS : 0u) |
                         (f->kd_node_count ? RT_INST_KD : 0u);
    snprintf(out, size,
             "-DRT_STATIC_FLAGS=%uu -DRT_STATIC_INST_SET=%uu -DRT_STATIC_INST_MASK=%uu "
             "-DRT_STATIC_TRI_METHOD=%uu",
             flags, inst_set, inst_mask, f->hdr.tri_method);
}

static rt_status warm_up(cl_state *s, int wave, rt_error *err);
static rt_status compile(cl_state *s, const rt_flat *f, const char *options, const char *defines,
                         int lanes, const rt_cl_cache *cache, char **log, rt_error *err);
static void keep_build_log(cl_state *s, const char *log, const char *printed);
static void append_log(rt_error *err, const char *log);

/* The packet kernel's lanes for this device: 16 (4x4 blocks) on CPU devices,
 * 0 (one ray per work-item) elsewhere (both trace BVH and kd-tree meshes). The renderer's tuning
 * (for tests and comparisons) runs the one-ray kernels on a CPU device too, or picks another block
 * (4: 2x2, 8: 4x2). */
static int packet_lanes(const cl_state *s) {
    if (!s->dev.cpu || s->tune.one_ray_kernels) return 0;
    int n = s->tune.packet_lanes;
    return n == 4 || n == 8 ? n : 16;
}

static rt_status build_program(cl_state *s, const rt_flat *f, double *compile_ms, rt_error *err) {
    char defines[192], options[768];
    scene_defines(f, defines, sizeof defines);
    const char *extra = s->device_options;
    int lanes = packet_lanes(s);
    char packet[64] = "";
    if (lanes) snprintf(packet, sizeof packet, " -DRT_PK_LANES=%d", lanes);
    if (s->test_skip)
        snprintf(packet + strlen(packet), sizeof packet - strlen(packet), " -DRT_TEST_SKIP=%u",
                 s->test_skip);
    /* The exact build: no mad or fast-relaxed maths (they change results);
     * the maths profile and denormal policy of the plan. Study variants
     * append their options (device_options) after ours. */
    const char *math = s->plan.portable     ? "-DRT_PORTABLE_MATH "
                       : s->dev.cr_div_sqrt ? "-cl-fp32-correctly-rounded-divide-sqrt "
                                            : "";
    snprintf(options, sizeof options, "%s%s%s%s%s%s", math, denormal_options(s), defines, packet,
             extra[0] ? " " : "", extra);
    if (s->program && strcmp(options, s->options) == 0) return RT_OK;
    if (s->k_camera) clReleaseKernel(s->k_camera);
    if (s->k_trace) clReleaseKernel(s->k_trace);
    if (s->k_shade) clReleaseKernel(s->k_shade);
    release_wave_kernels(s);
    if (s->program) clReleaseProgram(s->program);
    s->k_camera = s->k_trace = s->k_shade = NULL;
    s->program = NULL;
    double t0 = rt_now_ms();
    /* The kernel cache (cl_program_cache.h): a cached binary first, loaded
     * under the capture as every build; the caller hears of a build from
     * source before it starts, outside the capture. */
    const char *src[2] = {rt_cl_source_rt_single_ray, rt_cl_source_rt_ray_packet};
    rt_cl_cache *cache = malloc(sizeof *cache);
    if (!cache) return rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory");
    rt_cl_cache_open(cache, &s->dev, lanes ? 2 : 1, src, options);
    rt_cl_stderr capture;
    rt_cl_stderr_begin(&capture);
    s->program = rt_cl_cache_load(cache, s->ctx, s->dev.device_id, options);
    free(rt_cl_stderr_end(&capture));
    if (!s->program && s->on_compile)
        s->on_compile(s->on_compile_user, "opencl", s->dev.name, cache->dir[0] ? cache->dir : NULL);
    rt_cl_stderr_begin(&capture);
    char *log = NULL;
    rt_status st = compile(s, f, options, defines, lanes, cache, &log, err);
    char *printed = rt_cl_stderr_end(&capture);
    free(cache);
    keep_build_log(s, log, printed);
    if (st != RT_OK && s->build_log && s->build_log[0]) append_log(err, s->build_log);
    free(log);
    free(printed);
    *compile_ms += rt_now_ms() - t0;
    return st;
}

/* The program's build log, as a new string (NULL: none or no memory). */
static char *program_log(cl_program program, cl_device_id d) {
    size_t n = 0;
    if (clGetProgramBuildInfo(program, d, CL_PROGRAM_BUILD_LOG, 0, NULL, &n) != CL_SUCCESS)
        return NULL;
    char *log = malloc(n + 1);
    if (!log) return NULL;
    if (clGetProgramBuildInfo(program, d, CL_PROGRAM_BUILD_LOG, n, log, NULL) != CL_SUCCESS) n = 0;
    log[n] = '\0';
    return log;
}

/* s->build_log = the compiler's log, then the driver's stderr output, each
 * without surrounding blank lines; "" when both are empty. */
static void keep_build_log(cl_state *s, const char *log, const char *printed) {
    const char *parts[2] = {log ? log : "", printed ? printed : ""};
    size_t len[2];
    for (int i = 0; i < 2; i++) {
        while (*parts[i] == '\n' || *parts[i] == ' ') parts[i]++;
        len[i] = strlen(parts[i]);
        while (len[i] && (parts[i][len[i] - 1] == '\n' || parts[i][len[i] - 1] == ' ')) len[i]--;
    }
    free(s->build_log);
    s->build_log = malloc(len[0] + len[1] + 2);
    if (!s->build_log) return;
    memcpy(s->build_log, parts[0], len[0]);
    size_t n = len[0];
    if (len[0] && len[1]) s->build_log[n++] = '\n';
    memcpy(s->build_log + n, parts[1], len[1]);
    s->build_log[n + len[1]] = '\0';
}

/* Adds as much of the build log as fits to err's message. */
static void append_log(rt_error *err, const char *log) {
    if (!err) return;
    size_t used = strlen(err->message);
    if (used + 16 < sizeof err->message)
        snprintf(err->message + used, sizeof err->message - used, "; build log:\n%s", log);
}

static rt_status make_kernels(cl_state *s, const rt_flat *f, const char *options,
                              const char *defines, int lanes, rt_error *err);

/* Makes the kernels of s->program when it came from the cache, else builds
 * the program from source first, and warms them up (PoCL compiles each
 * kernel's code at its first launch); a program built from source is then
 * saved in the cache, with that code. A cached program that fails is
 * forgotten and built again from source. *log receives the compiler's log
 * (to free), on success and on failure. */
static rt_status compile(cl_state *s, const rt_flat *f, const char *options, const char *defines,
                         int lanes, const rt_cl_cache *cache, char **log, rt_error *err) {
    if (s->program) {
        *log = program_log(s->program, s->dev.device_id);
        if (make_kernels(s, f, options, defines, lanes, err) == RT_OK) return RT_OK;
        free(*log);
        *log = NULL;
        rt_cl_cache_forget(cache);
        if (s->k_camera) clReleaseKernel(s->k_camera);
        if (s->k_trace) clReleaseKernel(s->k_trace);
        if (s->k_shade) clReleaseKernel(s->k_shade);
        release_wave_kernels(s);
        clReleaseProgram(s->program);
        s->k_camera = s->k_trace = s->k_shade = NULL;
        s->program = NULL;
    }
    /* CPU devices get the packet kernel in the same program. */
    const char *src[2] = {rt_cl_source_rt_single_ray, rt_cl_source_rt_ray_packet};
    cl_int ce;
    s->program = clCreateProgramWithSource(s->ctx, lanes ? 2 : 1, src, NULL, &ce);
    if (!s->program)
        return rt_fail(err, RT_ERROR_BACKEND, "OpenCL program: %s", rt_cl_error_name(ce));
    cl_device_id d = s->dev.device_id;
    ce = clBuildProgram(s->program, 1, &d, options, NULL, NULL);
    *log = program_log(s->program, d);
    if (ce != CL_SUCCESS) {
        clReleaseProgram(s->program);
        s->program = NULL;
        return rt_fail(err, RT_ERROR_BACKEND,
                       "OpenCL kernel build failed on '%s' (%s; options: %s)", s->dev.name,
                       rt_cl_error_name(ce), options);
    }
    rt_status st = make_kernels(s, f, options, defines, lanes, err);
    if (st == RT_OK) rt_cl_cache_store(cache, s->program);
    return st;
}

/* The kernels of the built s->program, warmed up. */
static rt_status make_kernels(cl_state *s, const rt_flat *f, const char *options,
                              const char *defines, int lanes, rt_error *err) {
    cl_int ce = CL_SUCCESS;
    s->k_camera = clCreateKernel(s->program, "rt_k_camera", &ce);
    if (s->k_camera) s->k_trace = clCreateKernel(s->program, "rt_k_trace", &ce);
    if (s->k_trace) s->k_shade = clCreateKernel(s->program, "rt_k_shade", &ce);
    if (s->k_shade) s->k_wcam = clCreateKernel(s->program, "rt_k_wave_camera", &ce);
    if (s->k_wcam) s->k_wtrace = clCreateKernel(s->program, "rt_k_wave_trace", &ce);
    if (s->k_wtrace) s->k_wshade = clCreateKernel(s->program, "rt_k_wave_shade", &ce);
    if (s->k_wshade) s->k_wsum = clCreateKernel(s->program, "rt_k_wave_sum", &ce);
    if (s->k_wsum && lanes) s->k_packet = clCreateKernel(s->program, "rt_k_packet", &ce);
    if (s->k_packet) s->k_ptrace = clCreateKernel(s->program, "rt_k_packet_trace", &ce);
    if (!s->k_wsum || (lanes && !s->k_ptrace))
        return rt_fail(err, RT_ERROR_BACKEND, "OpenCL kernels: %s", rt_cl_error_name(ce));
    s->lanes = lanes;
    snprintf(s->options, sizeof s->options, "%s", options);
    snprintf(s->defines, sizeof s->defines, "%s", defines);
    return warm_up(s, (f->hdr.flags & RT_SCENE_SECONDARY) != 0, err);
}

/* ---- buffers and uploads ------------------------------------------------ */

static int out_of_memory(cl_int ce) {
    return ce == CL_MEM_OBJECT_ALLOCATION_FAILURE || ce == CL_OUT_OF_RESOURCES ||
           ce == CL_OUT_OF_HOST_MEMORY || ce == CL_INVALID_BUFFER_SIZE;
}

/* Makes buffer b hold at least bytes (never 0: empty arrays get a stub).
 * Returns 1 when it was (re)made, so its contents are gone. */
static rt_status ensure(cl_state *s, int b, size_t bytes, int *remade, rt_error *err) {
    if (bytes < 16) bytes = 16;
    *remade = 0;
    if (s->buf[b] && s->cap[b] >= bytes) return RT_OK;
    if (s->buf[b]) clReleaseMemObject(s->buf[b]);
    s->buf[b] = NULL;
    s->cap[b] = 0;
    if ((uint64_t)bytes > s->dev.max_alloc)
        return rt_fail(err, RT_ERROR_OUT_OF_MEMORY,
                       "out of device memory: buffer '%s' needs %zu bytes, more than the largest "
                       "allocation of '%s' (%llu bytes)",
                       rt_cl_buffer_what(b), bytes, s->dev.name,
                       (unsigned long long)s->dev.max_alloc);
    cl_int ce;
    s->buf[b] = clCreateBuffer(s->ctx, CL_MEM_READ_WRITE, bytes, NULL, &ce);
    if (!s->buf[b])
        return rt_fail(err, out_of_memory(ce) ? RT_ERROR_OUT_OF_MEMORY : RT_ERROR_BACKEND,
                       "%s: buffer '%s' of %zu bytes on '%s' (%s)",
                       out_of_memory(ce) ? "out of device memory" : "cannot allocate",
                       rt_cl_buffer_what(b), bytes, s->dev.name, rt_cl_error_name(ce));
    s->cap[b] = bytes;
    *remade = 1;
    return RT_OK;
}

static rt_status write_buf(cl_state *s, int b, size_t offset, const void *data, size_t bytes,
                           uint64_t *uploaded, rt_error *err) {
    if (!bytes) return RT_OK;
    cl_int ce =
        clEnqueueWriteBuffer(s->queue, s->buf[b], CL_FALSE, offset, bytes, data, 0, NULL, NULL);
    if (ce != CL_SUCCESS)
        return rt_fail(err, out_of_memory(ce) ? RT_ERROR_OUT_OF_MEMORY : RT_ERROR_BACKEND,
                       "%s: writing buffer '%s' (%zu bytes) on '%s' (%s)",
                       out_of_memory(ce) ? "out of device memory" : "upload failed",
                       rt_cl_buffer_what(b), bytes, s->dev.name, rt_cl_error_name(ce));
    *uploaded += bytes;
    return RT_OK;
}

/* One copy of an upload plan (upload_plan.h): array i is buffer i here. */
_Static_assert((int)RT_CL_BUF_HDR == (int)RT_UP_HDR && (int)RT_CL_BUF_LIGHTS == (int)RT_UP_LIGHTS &&
                   (int)RT_CL_BUF_KD_NODES == (int)RT_UP_KD_NODES,
               "the layout's buffers are the upload plan's arrays");
typedef struct cl_upload {
    cl_state *s;
    uint64_t *bytes;
    rt_error *err;
} cl_upload;

static rt_status cl_emit(void *user, const rt_upload_copy *c) {
    cl_upload *u = user;
    return write_buf(u->s, c->array, c->offset, c->src, c->bytes, u->bytes, u->err);
}

/* Brings the device's copy of the layout up to date (upload_plan.h: only
 * what changed) and waits for the writes. */
static rt_status upload_scene(cl_state *s, const rt_backend_layout *layout, uint64_t *bytes,
                              double *ms, rt_error *err) {
    double t0 = rt_now_ms();
    rt_upload_plan plan;
    if (rt_upload_plan_make(&s->memo, layout, s->cap, &plan) != RT_OK)
        return rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory");
    int remade[RT_UP_COUNT] = {0};
    rt_status st = RT_OK;
    for (int i = 0; plan.buffers && i < RT_UP_COUNT && st == RT_OK; i++)
        st = ensure(s, i, plan.bytes[i], &remade[i], err);
    cl_upload u = {s, bytes, err};
    if (st == RT_OK) st = rt_upload_plan_run(&plan, layout, remade, cl_emit, &u);
    if (st == RT_OK) {
        cl_int ce = clFinish(s->queue);
        if (ce != CL_SUCCESS)
            st = rt_fail(err, out_of_memory(ce) ? RT_ERROR_OUT_OF_MEMORY : RT_ERROR_BACKEND,
                         "upload to '%s' failed (%s)", s->dev.name, rt_cl_error_name(ce));
    }
    rt_upload_plan_finish(&plan, &s->memo, layout, st == RT_OK);
    *ms += rt_now_ms() - t0;
    return st;
}

/* ---- launches --------------------------------------------------------------- */

static rt_status set_arg(cl_kernel k, cl_uint i, size_t n, const void *v, rt_error *err) {
    cl_int ce = clSetKernelArg(k, i, n, v);
    if (ce != CL_SUCCESS)
        return rt_fail(err, RT_ERROR_BACKEND, "kernel argument %u: %s", i, rt_cl_error_name(ce));
    return RT_OK;
}

/* A kernel argument and the buffer (RT_CL_BUF_...) bound to it. */
typedef struct buf_arg {
    cl_uint arg;
    int buf;
} buf_arg;

/* Binds the buffers of args (n of them) to their arguments of k, in order;
 * the first failure stops it. */
static rt_status set_bufs(cl_state *s, cl_kernel k, const buf_arg *args, size_t n, rt_error *err) {
    rt_status st = RT_OK;
    for (size_t i = 0; i < n && st == RT_OK; i++)
        st = set_arg(k, args[i].arg, sizeof(cl_mem), &s->buf[args[i].buf], err);
    return st;
}
#define SET_BUFS(s, k, args, err) set_bufs(s, k, args, sizeof args / sizeof *args, err)

/* The scene arrays, the view arguments of every tracing kernel. */
static rt_status set_view(cl_state *s, cl_kernel k, rt_error *err) {
    for (int b = RT_CL_BUF_HDR; b <= RT_CL_BUF_KD_NODES; b++) {
        rt_status st = set_arg(k, (cl_uint)(RT_ARG_HDR + (b - RT_CL_BUF_HDR)), sizeof(cl_mem),
                               &s->buf[b], err);
        if (st != RT_OK) return st;
    }
    return RT_OK;
}

/* The work-group size for k: 64 work-items, a multiple of the kernel's
 * preferred multiple (8 on PoCL's pthread device, 32 on NVIDIA), within its
 * limit. Fixed per kernel: PoCL compiles a work-group function per local size
 * at its first use, so a size chosen per tile would cost compiles. */
static size_t local_size(cl_state *s, cl_kernel k) {
    size_t local = 64, wg = 0, mult = 0;
    cl_device_id d = s->dev.device_id;
    if (clGetKernelWorkGroupInfo(k, d, CL_KERNEL_PREFERRED_WORK_GROUP_SIZE_MULTIPLE, sizeof mult,
                                 &mult, NULL) == CL_SUCCESS &&
        mult > local && mult <= 256)
        local = mult;
    if (clGetKernelWorkGroupInfo(k, d, CL_KERNEL_WORK_GROUP_SIZE, sizeof wg, &wg, NULL) ==
            CL_SUCCESS &&
        wg > 0 && wg < local)
        local = wg;
    return local;
}

/* Enqueues k (the kernel RT_CL_DONE_<KERNEL> = kernel) over count items (the
 * global size rounded up to the work-group size; the kernels ignore items past
 * count) without waiting: the launches of a tile follow each other on the
 * in-order queue, and the host waits once per tile (see finish_launches). The
 * count is added to what the completion check expects. */
static rt_status enqueue(cl_state *s, cl_kernel k, int kernel, uint32_t count, cl_event *ev,
                         rt_error *err) {
    const char *name = rt_cl_kernel_name(kernel);
    size_t local = local_size(s, k);
    size_t global = ((size_t)count + local - 1) / local * local;
    if (global == 0) global = local;
    cl_int ce = clEnqueueNDRangeKernel(s->queue, k, 1, NULL, &global, &local, 0, NULL, ev);
    if (ce != CL_SUCCESS)
        return rt_fail(err, out_of_memory(ce) ? RT_ERROR_OUT_OF_MEMORY : RT_ERROR_BACKEND,
                       "kernel %s on '%s' (%u items): %s", name, s->dev.name, count,
                       rt_cl_error_name(ce));
    s->launched[kernel] += count;
    return RT_OK;
}

/* Waits for n launches, adds each one's profiled time to ms[i], returns the
 * longest in *longest, and releases the events. */
static rt_status finish_launches(cl_state *s, cl_event *ev, int n, double *ms, double *longest,
                                 rt_error *err) {
    cl_int ce = clWaitForEvents((cl_uint)n, ev);
    *longest = 0.0;
    for (int i = 0; i < n; i++) {
        cl_ulong start = 0, end = 0;
        if (ce == CL_SUCCESS &&
            clGetEventProfilingInfo(ev[i], CL_PROFILING_COMMAND_START, sizeof start, &start,
                                    NULL) == CL_SUCCESS &&
            clGetEventProfilingInfo(ev[i], CL_PROFILING_COMMAND_END, sizeof end, &end, NULL) ==
                CL_SUCCESS &&
            end >= start) {
            double t = (double)(end - start) * 1e-6;
            ms[i] += t;
            if (t > *longest) *longest = t;
        }
        clReleaseEvent(ev[i]);
    }
    if (ce != CL_SUCCESS)
        return rt_fail(err, out_of_memory(ce) ? RT_ERROR_OUT_OF_MEMORY : RT_ERROR_BACKEND,
                       "kernels on '%s': %s", s->dev.name, rt_cl_error_name(ce));
    return RT_OK;
}

/* Enqueues k over count items, waits, and adds its profiled time to *ms. */
static rt_status launch(cl_state *s, cl_kernel k, int kernel, uint32_t count, double *ms,
                        rt_error *err) {
    cl_event ev;
    rt_status st = enqueue(s, k, kernel, count, &ev, err);
    if (st != RT_OK) return st;
    double longest;
    return finish_launches(s, &ev, 1, ms, &longest, err);
}

/* One empty launch of each kernel (count 0, every item returns at once) with
 * stub buffers, right after the build: PoCL compiles (or loads from its cache)
 * the work-group function of a kernel at its first launch, which otherwise
 * lands in the first frame's time (about 1 s per kernel with a cold cache). */
static rt_status warm_up(cl_state *s, int wave, rt_error *err) {
    /* Not on Oclgrind, a simulator: it compiles at the build and interprets
     * every work-item of a launch, so the large empty grid below cost it
     * about 6 s per kernel (18 s of a 20 s 16x16 frame) and gained nothing. */
    if (strstr(s->dev.platform, "Oclgrind")) return RT_OK;
    cl_mem stub = clCreateBuffer(s->ctx, CL_MEM_READ_WRITE, 64, NULL, NULL);
    if (!stub) return rt_fail(err, RT_ERROR_BACKEND, "cannot allocate a stub buffer");
    cl_uint zero = 0;
    cl_int izero = 0;
    cl_kernel ks[7] = {s->k_camera, s->k_trace,  s->k_shade, s->k_wcam,
                       s->k_wtrace, s->k_wshade, s->k_wsum};
    cl_uint nargs[7] = {RT_K_CAMERA_ARGS, RT_K_TRACE_ARGS,  RT_K_SHADE_ARGS, RT_K_WCAM_ARGS,
                        RT_K_WTRACE_ARGS, RT_K_WSHADE_ARGS, RT_K_WSUM_ARGS};
    const char *names[7] = {"rt_k_camera",      "rt_k_trace",      "rt_k_shade",
                            "rt_k_wave_camera", "rt_k_wave_trace", "rt_k_wave_shade",
                            "rt_k_wave_sum"};
    int nk = wave ? 7 : 3; /* the wavefront kernels only where the scene has secondary rays */
    if (s->lanes) {
        /* Frames run rt_k_packet alone; ray queries rt_k_packet_trace
         * (closest hit) and rt_k_trace (any hit). */
        ks[0] = s->k_packet;
        nargs[0] = RT_K_PACKET_ARGS;
        names[0] = "rt_k_packet";
        ks[2] = s->k_ptrace;
        nargs[2] = RT_K_PTRACE_ARGS;
        names[2] = "rt_k_packet_trace";
        nk = 3;
    }
    rt_status st = RT_OK;
    for (int k = 0; k < nk && st == RT_OK; k++) {
        for (cl_uint a = 0; a < nargs[k]; a++) {
            /* Scalars are uint/int (4 bytes), the rest buffers. */
            cl_int ce = clSetKernelArg(ks[k], a, sizeof(cl_mem), &stub);
            if (ce != CL_SUCCESS) ce = clSetKernelArg(ks[k], a, sizeof zero, &zero);
            if (ce != CL_SUCCESS) ce = clSetKernelArg(ks[k], a, sizeof izero, &izero);
            if (ce != CL_SUCCESS) {
                st = rt_fail(err, RT_ERROR_BACKEND, "warm-up argument %u of %s: %s", a, names[k],
                             rt_cl_error_name(ce));
                break;
            }
        }
        /* PoCL specialises for grids up to some width ("smallgrid") and
         * builds another function for larger ones: warm up both. */
        size_t local = local_size(s, ks[k]);
        size_t globals[2] = {local, RT_CL_TILE_MAX};
        for (int g = 0; g < 2 && st == RT_OK; g++) {
            cl_int ce = clEnqueueNDRangeKernel(s->queue, ks[k], 1, NULL, &globals[g], &local, 0,
                                               NULL, NULL);
            if (ce == CL_SUCCESS) ce = clFinish(s->queue);
            if (ce != CL_SUCCESS)
                st = rt_fail(err, RT_ERROR_BACKEND, "warm-up of %s on '%s': %s", names[k],
                             s->dev.name, rt_cl_error_name(ce));
        }
    }
    clReleaseMemObject(stub);
    return st;
}

static rt_status read_buf(cl_state *s, int b, size_t bytes, void *dst, rt_error *err) {
    cl_int ce = clEnqueueReadBuffer(s->queue, s->buf[b], CL_TRUE, 0, bytes, dst, 0, NULL, NULL);
    if (ce != CL_SUCCESS)
        return rt_fail(err, RT_ERROR_BACKEND, "reading buffer '%s' (%zu bytes) from '%s': %s",
                       rt_cl_buffer_what(b), bytes, s->dev.name, rt_cl_error_name(ce));
    return RT_OK;
}

/* Per-ray buffers for tiles of up to 'tile' rays. */
static rt_status ensure_ray_buffers(cl_state *s, uint32_t tile, rt_error *err) {
    int remade;
    rt_status st = ensure(s, RT_CL_BUF_RAYS, sizeof(rt_ray) * tile, &remade, err);
    if (st == RT_OK) st = ensure(s, RT_CL_BUF_HITS, sizeof(rt_hit_d) * tile, &remade, err);
    if (st == RT_OK) st = ensure(s, RT_CL_BUF_COUNTERS, sizeof(rt_counters) * tile, &remade, err);
    /* A stub until a query with masks needs it whole (cl_trace). */
    if (st == RT_OK) st = ensure(s, RT_CL_BUF_MASKS, sizeof(cl_uint), &remade, err);
    if (st == RT_OK)
        st = ensure(s, RT_CL_BUF_DONE, sizeof(cl_uint) * RT_CL_DONE_COUNT, &remade, err);
    return st;
}

/* ---- the completion check ----------------------------------------------------
 *
 * Every kernel's work-item that reaches its end adds 1 to its kernel's counter
 * in the DONE buffer (RT_K_DONE in rt_kernel_args.h: one atomic per item).
 * done_begin clears the counters before a tile's launches (a fill on the
 * in-order queue) and done_check reads them after the last one (one read of
 * RT_CL_DONE_COUNT words per tile) and compares each with the items the
 * tile launched of that kernel (enqueue counts them). A device that cut a
 * launch short (a simulator that stopped at an error, a driver that dropped
 * work-groups) then fails the frame or the query instead of handing back an
 * image with holes. */

/* Binds the DONE buffer to argument arg (RT_K_<KERNEL>_DONE) of k. */
static rt_status bind_done(cl_state *s, cl_kernel k, cl_uint arg, rt_error *err) {
    return set_arg(k, arg, sizeof(cl_mem), &s->buf[RT_CL_BUF_DONE], err);
}

static rt_status zero_buf(cl_state *s, int b, size_t bytes, rt_error *err);

static rt_status done_begin(cl_state *s, rt_error *err) {
    memset(s->launched, 0, sizeof s->launched);
    return zero_buf(s, RT_CL_BUF_DONE, sizeof(cl_uint) * RT_CL_DONE_COUNT, err);
}

/* Fails unless every work-item launched since done_begin finished; what
 * names the work (e.g. "pixels 0..255"). */
static rt_status done_check(cl_state *s, const char *what, rt_error *err) {
    cl_uint done[RT_CL_DONE_COUNT];
    rt_status st = read_buf(s, RT_CL_BUF_DONE, sizeof done, done, err);
    for (int k = 0; k < RT_CL_DONE_COUNT && st == RT_OK; k++)
        if (done[k] != s->launched[k])
            st = rt_fail(err, RT_ERROR_BACKEND,
                         "opencl: kernel %s on '%s' finished %u of %u work-items (%s): the "
                         "device cut the launch short, so the result is incomplete and was not "
                         "used",
                         rt_cl_kernel_name(k), s->dev.name, (unsigned)done[k],
                         (unsigned)s->launched[k], what);
    return st;
}

/* The smallest tile: enough work-groups of 64 to keep every compute unit
 * busy (PoCL's pthread device runs whole work-groups on its threads; a GPU
 * needs many per compute unit). */
static uint32_t tile_min(const cl_state *s) {
    uint64_t m = (uint64_t)s->dev.compute_units * 64u * 16u;
    if (m < RT_CL_TILE_MIN) m = RT_CL_TILE_MIN;
    return m > RT_CL_TILE_MAX ? RT_CL_TILE_MAX : (uint32_t)m;
}

/* The next tile size from the longest launch of the last full tile: halve
 * above the target time, double below a quarter of it. Kept in the state, so
 * the next frame starts where this one ended. */
static uint32_t next_tile(const cl_state *s, uint32_t tile, double longest_ms) {
    if (longest_ms > RT_CL_TARGET_MS && tile / 2 >= tile_min(s)) return tile / 2;
    if (longest_ms < RT_CL_TARGET_MS / 4 && tile < RT_CL_TILE_MAX) return tile * 2;
    return tile < tile_min(s) ? tile_min(s) : tile;
}

/* Any failure of this backend reads "opencl: ..." for the caller. */
static rt_status named(rt_error *err, rt_status st) {
    return rt_error_prefix(err, st, "opencl: ");
}

static rt_status cl_prepare(void *state, const rt_backend_layout *layout, rt_render_stats *stats,
                            rt_error *err) {
    cl_state *s = state;
    rt_status st = RT_OK;
    if (!s->ctx) {
        st = open_device(s, err);
        if (st == RT_OK && s->plan.needs_probe) st = probe_flush(s, &s->probed_flush, err);
    }
    if (st == RT_OK) st = build_program(s, layout->flat, &stats->compile_ms, err);
    if (st == RT_OK) st = upload_scene(s, layout, &stats->upload_bytes, &stats->upload_ms, err);
    if (st != RT_OK) return named(err, st);
    snprintf(stats->device, sizeof stats->device, "%s", s->dev.name);
    snprintf(stats->specialisation, sizeof stats->specialisation, "%s", s->defines);
    snprintf(stats->device_options, sizeof stats->device_options, "%s", s->device_options);
    /* Extra options (the study's variants) void the device's promise. */
    stats->exact =
        s->plan.exact && (!s->plan.needs_probe || s->probed_flush) && !s->device_options[0];
    stats->math_profile = s->plan.portable ? "portable" : "native";
    stats->denormals = s->plan.flush ? "flush" : "preserve";
    return RT_OK;
}

/* One tile through rt_shade_hit's stack inside rt_k_shade: camera, closest
 * hit and shading (or an AOV), back to back on the in-order queue with one
 * wait at the end. *longest gets the longest launch (ms). */
static rt_status direct_tile(cl_state *s, cl_uint f, cl_uint n, rt_render_stats *stats,
                             double *longest, rt_error *err) {
    cl_kernel kc = s->k_camera, kt = s->k_trace, ks = s->k_shade;
    rt_status st = set_arg(kc, RT_K_CAMERA_FIRST, sizeof f, &f, err);
    if (st == RT_OK) st = set_arg(kc, RT_K_CAMERA_COUNT, sizeof n, &n, err);
    if (st == RT_OK) st = set_arg(kt, RT_K_TRACE_COUNT, sizeof n, &n, err);
    if (st == RT_OK) st = set_arg(ks, RT_K_SHADE_FIRST, sizeof f, &f, err);
    if (st == RT_OK) st = set_arg(ks, RT_K_SHADE_COUNT, sizeof n, &n, err);
    cl_event ev[3];
    int queued = 0;
    if (st == RT_OK) st = enqueue(s, kc, RT_CL_DONE_CAMERA, n, &ev[queued], err);
    if (st == RT_OK) st = enqueue(s, kt, RT_CL_DONE_TRACE, n, &ev[++queued], err);
    if (st == RT_OK) st = enqueue(s, ks, RT_CL_DONE_SHADE, n, &ev[++queued], err);
    if (st == RT_OK) queued++;
    *longest = 0.0;
    if (queued == 3) {
        st = finish_launches(s, ev, 3, stats->kernel_ms, longest, err);
    } else {
        clFinish(s->queue);
        for (int i = 0; i < queued; i++) clReleaseEvent(ev[i]);
    }
    if (st == RT_OK) stats->launches += 3;
    return st;
}

/* Blocks f .. f + n - 1 through rt_k_packet (camera, trace, shading and
 * shadow rays in one launch); its time counts as trace. */
static rt_status packet_tile(cl_state *s, cl_uint f, cl_uint n, rt_render_stats *stats,
                             double *longest, rt_error *err) {
    cl_kernel k = s->k_packet;
    rt_status st = set_arg(k, RT_K_PACKET_FIRST, sizeof f, &f, err);
    if (st == RT_OK) st = set_arg(k, RT_K_PACKET_COUNT, sizeof n, &n, err);
    double t = 0.0;
    if (st == RT_OK) st = launch(s, k, RT_CL_DONE_PACKET, n, &t, err);
    stats->kernel_ms[1] += t;
    *longest = t;
    if (st == RT_OK) stats->launches++;
    return st;
}

/* Launches k over count items, waits, adds the time to *ms and raises
 * *longest. */
static rt_status timed(cl_state *s, cl_kernel k, int kernel, uint32_t count, double *ms,
                       double *longest, rt_error *err) {
    double t = 0.0;
    rt_status st = launch(s, k, kernel, count, &t, err);
    *ms += t;
    if (t > *longest) *longest = t;
    return st;
}

static rt_status zero_buf(cl_state *s, int b, size_t bytes, rt_error *err) {
    cl_uint zero = 0;
    cl_int ce =
        clEnqueueFillBuffer(s->queue, s->buf[b], &zero, sizeof zero, 0, bytes, 0, NULL, NULL);
    if (ce != CL_SUCCESS)
        return rt_fail(err, RT_ERROR_BACKEND, "clearing buffer '%s' on '%s': %s",
                       rt_cl_buffer_what(b), s->dev.name, rt_cl_error_name(ce));
    return RT_OK;
}

/* One tile of an image with secondary rays as wavefront passes (see
 * kernels/rt_single_ray.cl): the primary rays' queue, then per level a trace and
 * a shade launch whose secondary rays make the next queue (its length read
 * back between the launches), until the queue is empty; then the per-pixel
 * sum in rt_shade_hit's order. *overflow is set (and the tile left
 * unfinished) when a level queues more than cap rays. */
static rt_status wave_tile(cl_state *s, cl_uint slots, cl_uint cap, cl_uint f, cl_uint n,
                           rt_render_stats *stats, double *longest, int *overflow, rt_error *err) {
    cl_kernel kc = s->k_wcam, kt = s->k_wtrace, ks = s->k_wshade;
    *longest = 0.0;
    *overflow = 0;
    rt_status st = zero_buf(s, RT_CL_BUF_COUNTERS, sizeof(rt_counters) * n, err);
    if (st == RT_OK) st = set_arg(kc, RT_K_WCAM_FIRST, sizeof f, &f, err);
    if (st == RT_OK) st = set_arg(kc, RT_K_WCAM_COUNT, sizeof n, &n, err);
    if (st == RT_OK)
        st = set_arg(kc, RT_K_WCAM_QUEUE, sizeof(cl_mem), &s->buf[RT_CL_BUF_QUEUE_A], err);
    if (st == RT_OK) st = timed(s, kc, RT_CL_DONE_WCAM, n, &stats->kernel_ms[0], longest, err);
    if (st == RT_OK) stats->launches++;
    cl_uint count = n;
    int in = RT_CL_BUF_QUEUE_A, out = RT_CL_BUF_QUEUE_B;
    while (st == RT_OK && count > 0) {
        st = set_arg(kt, RT_K_WTRACE_COUNT, sizeof count, &count, err);
        if (st == RT_OK) st = set_arg(kt, RT_K_WTRACE_QUEUE, sizeof(cl_mem), &s->buf[in], err);
        if (st == RT_OK) st = set_arg(ks, RT_K_WSHADE_COUNT, sizeof count, &count, err);
        if (st == RT_OK) st = set_arg(ks, RT_K_WSHADE_QUEUE, sizeof(cl_mem), &s->buf[in], err);
        if (st == RT_OK) st = set_arg(ks, RT_K_WSHADE_NEXT, sizeof(cl_mem), &s->buf[out], err);
        if (st == RT_OK)
            st = timed(s, kt, RT_CL_DONE_WTRACE, count, &stats->kernel_ms[1], longest, err);
        if (st == RT_OK) st = zero_buf(s, RT_CL_BUF_QUEUE_COUNT, sizeof(cl_uint), err);
        if (st == RT_OK)
            st = timed(s, ks, RT_CL_DONE_WSHADE, count, &stats->kernel_ms[2], longest, err);
        cl_uint next = 0;
        if (st == RT_OK) st = read_buf(s, RT_CL_BUF_QUEUE_COUNT, sizeof next, &next, err);
        if (st != RT_OK) return st;
        stats->launches += 2;
        if (next > cap) {
            *overflow = 1;
            return RT_OK;
        }
        count = next;
        int t = in;
        in = out;
        out = t;
    }
    cl_kernel ksum = s->k_wsum;
    if (st == RT_OK) st = set_arg(ksum, RT_K_WSUM_FIRST, sizeof f, &f, err);
    if (st == RT_OK) st = set_arg(ksum, RT_K_WSUM_COUNT, sizeof n, &n, err);
    if (st == RT_OK) st = timed(s, ksum, RT_CL_DONE_WSUM, n, &stats->kernel_ms[2], longest, err);
    if (st == RT_OK) stats->launches++;
    return st;
}

/* The wavefront's largest tile: a power of two whose records fit in
 * RT_CL_WAVE_RECORD_BYTES and the device's largest allocation. */
static uint32_t wave_tile_max(const cl_state *s, uint32_t slots) {
    uint64_t budget = RT_CL_WAVE_RECORD_BYTES;
    if (s->dev.max_alloc && s->dev.max_alloc < budget) budget = s->dev.max_alloc;
    uint64_t fit = budget / ((uint64_t)slots * sizeof(rt_wave_record));
    uint32_t t = RT_CL_TILE_MAX;
    while (t > 64 && t > fit) t /= 2;
    return t;
}

/* Buffers and fixed arguments of the wavefront kernels. */
static rt_status wave_setup(cl_state *s, cl_uint slots, uint32_t tile_max, cl_uint cap,
                            cl_int channels, rt_error *err) {
    /* A queue holds a tile's primary rays or up to cap secondary rays. */
    size_t entries = cap > tile_max ? cap : tile_max;
    int remade;
    rt_status st = ensure(s, RT_CL_BUF_QUEUE_A, sizeof(rt_wave_entry) * entries, &remade, err);
    if (st == RT_OK)
        st = ensure(s, RT_CL_BUF_QUEUE_B, sizeof(rt_wave_entry) * entries, &remade, err);
    if (st == RT_OK) st = ensure(s, RT_CL_BUF_WAVE_HITS, sizeof(rt_hit_d) * entries, &remade, err);
    if (st == RT_OK)
        st = ensure(s, RT_CL_BUF_RECORDS, sizeof(rt_wave_record) * (size_t)slots * tile_max,
                    &remade, err);
    if (st == RT_OK) st = ensure(s, RT_CL_BUF_QUEUE_COUNT, sizeof(cl_uint), &remade, err);
    if (st == RT_OK) st = set_view(s, s->k_wtrace, err);
    if (st == RT_OK) st = set_view(s, s->k_wshade, err);
    cl_kernel kc = s->k_wcam, kt = s->k_wtrace, ks = s->k_wshade, ksum = s->k_wsum;
    if (st == RT_OK) st = set_arg(kc, RT_K_WCAM_HDR, sizeof(cl_mem), &s->buf[RT_CL_BUF_HDR], err);
    static const buf_arg trace_bufs[] = {{RT_K_WTRACE_HITS, RT_CL_BUF_WAVE_HITS},
                                         {RT_K_WTRACE_COUNTERS, RT_CL_BUF_COUNTERS}};
    if (st == RT_OK) st = SET_BUFS(s, kt, trace_bufs, err);
    static const buf_arg shade_bufs[] = {{RT_K_WSHADE_HITS, RT_CL_BUF_WAVE_HITS},
                                         {RT_K_WSHADE_COUNTERS, RT_CL_BUF_COUNTERS},
                                         {RT_K_WSHADE_RECORDS, RT_CL_BUF_RECORDS}};
    if (st == RT_OK) st = SET_BUFS(s, ks, shade_bufs, err);
    cl_uint stride = tile_max; /* records are slot-major */
    if (st == RT_OK) st = set_arg(ks, RT_K_WSHADE_STRIDE, sizeof stride, &stride, err);
    if (st == RT_OK)
        st = set_arg(ks, RT_K_WSHADE_NEXT_COUNT, sizeof(cl_mem), &s->buf[RT_CL_BUF_QUEUE_COUNT],
                     err);
    if (st == RT_OK) st = set_arg(ks, RT_K_WSHADE_NEXT_CAP, sizeof cap, &cap, err);
    static const buf_arg sum_bufs[] = {{RT_K_WSUM_HDR, RT_CL_BUF_HDR},
                                       {RT_K_WSUM_RECORDS, RT_CL_BUF_RECORDS}};
    if (st == RT_OK) st = SET_BUFS(s, ksum, sum_bufs, err);
    if (st == RT_OK) st = set_arg(ksum, RT_K_WSUM_STRIDE, sizeof stride, &stride, err);
    if (st == RT_OK) st = set_arg(ksum, RT_K_WSUM_CHANNELS, sizeof channels, &channels, err);
    if (st == RT_OK) st = set_arg(ksum, RT_K_WSUM_FB, sizeof(cl_mem), &s->buf[RT_CL_BUF_FB], err);
    if (st == RT_OK) st = bind_done(s, kc, RT_K_WCAM_DONE, err);
    if (st == RT_OK) st = bind_done(s, kt, RT_K_WTRACE_DONE, err);
    if (st == RT_OK) st = bind_done(s, ks, RT_K_WSHADE_DONE, err);
    if (st == RT_OK) st = bind_done(s, ksum, RT_K_WSUM_DONE, err);
    return st;
}

static rt_status cl_render(void *state, const rt_backend_layout *layout,
                           const rt_backend_frame *frame, rt_render_stats *stats, rt_error *err) {
    cl_state *s = state;
    const rt_scene_header *h = &layout->flat->hdr;
    uint32_t pixels = (uint32_t)h->width * (uint32_t)h->height;
    size_t fb_bytes = sizeof(float) * (size_t)pixels * (size_t)frame->channels;
    int remade;
    rt_status st = ensure(s, RT_CL_BUF_FB, fb_bytes, &remade, err);
    /* No tile holds more than the frame's pixels: a small frame gets small
     * buffers (the buffers only grow). Oclgrind's race check pays for every
     * byte of a buffer at every launch. */
    if (st == RT_OK)
        st = ensure_ray_buffers(s, pixels < RT_CL_TILE_MAX ? pixels : RT_CL_TILE_MAX, err);
    if (st != RT_OK) return named(err, st);

    cl_int aov = (cl_int)frame->aov, channels = frame->channels, any = 0;
    st = set_view(s, s->k_trace, err);
    if (st == RT_OK) st = set_view(s, s->k_shade, err);
    cl_kernel kc = s->k_camera, kt = s->k_trace, ks = s->k_shade;
    static const buf_arg camera_bufs[] = {{RT_K_CAMERA_HDR, RT_CL_BUF_HDR},
                                          {RT_K_CAMERA_RAYS, RT_CL_BUF_RAYS}};
    if (st == RT_OK) st = SET_BUFS(s, kc, camera_bufs, err);
    if (st == RT_OK) st = set_arg(kt, RT_K_TRACE_ANY_HIT, sizeof any, &any, err);
    static const buf_arg trace_bufs[] = {{RT_K_TRACE_RAYS, RT_CL_BUF_RAYS},
                                         {RT_K_TRACE_HITS, RT_CL_BUF_HITS},
                                         {RT_K_TRACE_COUNTERS, RT_CL_BUF_COUNTERS},
                                         {RT_K_TRACE_MASKS, RT_CL_BUF_MASKS}};
    if (st == RT_OK) st = SET_BUFS(s, kt, trace_bufs, err);
    cl_uint unmasked = 0; /* rendering: every ray's mask is 0xffffffff */
    if (st == RT_OK) st = set_arg(kt, RT_K_TRACE_MASKED, sizeof unmasked, &unmasked, err);
    if (st == RT_OK) st = set_arg(ks, RT_K_SHADE_AOV, sizeof aov, &aov, err);
    if (st == RT_OK) st = set_arg(ks, RT_K_SHADE_CHANNELS, sizeof channels, &channels, err);
    static const buf_arg shade_bufs[] = {{RT_K_SHADE_RAYS, RT_CL_BUF_RAYS},
                                         {RT_K_SHADE_HITS, RT_CL_BUF_HITS},
                                         {RT_K_SHADE_COUNTERS, RT_CL_BUF_COUNTERS},
                                         {RT_K_SHADE_FB, RT_CL_BUF_FB}};
    if (st == RT_OK) st = SET_BUFS(s, ks, shade_bufs, err);
    if (st == RT_OK) st = bind_done(s, kc, RT_K_CAMERA_DONE, err);
    if (st == RT_OK) st = bind_done(s, kt, RT_K_TRACE_DONE, err);
    if (st == RT_OK) st = bind_done(s, ks, RT_K_SHADE_DONE, err);

    /* Images with reflection or refraction go through the wavefront; AOVs
     * (primary-ray values, or every ray's tests of a pixel) and scenes
     * without secondary rays through rt_k_shade. */
    int wave =
        aov == RT_AOV_NONE && (h->flags & RT_SCENE_SECONDARY) && !s->tune.no_wavefront && !s->lanes;
    cl_uint slots = (2u << h->max_depth) - 1u, cap = 0;
    uint32_t tmax = RT_CL_TILE_MAX;
    if (st == RT_OK && wave) {
        tmax = wave_tile_max(s, slots);
        cap = 2u * tmax;
        /* Tests shrink the queues to force the overflow path. */
        if (s->tune.wave_queue_cap > 0 && s->tune.wave_queue_cap < cap)
            cap = s->tune.wave_queue_cap;
        /* The records' stride and the queues for this frame's tiles, which
         * hold at most its pixels; a level queues at most slots rays per
         * pixel, so a cap above that overflows no more than that does. */
        uint32_t fit = pixels < tmax ? pixels : tmax;
        if ((uint64_t)cap > (uint64_t)slots * fit) cap = slots * fit;
        st = wave_setup(s, slots, fit, cap, channels, err);
        if (s->tile > tmax) s->tile = tmax;
    }
    if (st != RT_OK) return named(err, st);

    /* CPU devices: rt_k_packet over blocks of lanes pixels (tiles are then
     * ranges of blocks); elsewhere rt_k_camera/trace/shade or the wavefront
     * over ranges of pixels. */
    const uint32_t lanes = (uint32_t)s->lanes, bw = lanes == 4 ? 2u : 4u,
                   bh = lanes ? lanes / bw : 1u;
    const uint32_t units =
        lanes ? (((uint32_t)h->width + bw - 1u) / bw) * (((uint32_t)h->height + bh - 1u) / bh)
              : pixels;
    if (lanes) {
        snprintf(stats->kernels, sizeof stats->kernels, "packet %ux%u (rt_k_packet)", bw, bh);
        cl_kernel kp = s->k_packet;
        if (st == RT_OK) st = set_view(s, kp, err);
        if (st == RT_OK) st = set_arg(kp, RT_K_PACKET_AOV, sizeof aov, &aov, err);
        if (st == RT_OK) st = set_arg(kp, RT_K_PACKET_CHANNELS, sizeof channels, &channels, err);
        static const buf_arg packet_bufs[] = {{RT_K_PACKET_COUNTERS, RT_CL_BUF_COUNTERS},
                                              {RT_K_PACKET_FB, RT_CL_BUF_FB}};
        if (st == RT_OK) st = SET_BUFS(s, kp, packet_bufs, err);
        if (st == RT_OK) st = bind_done(s, kp, RT_K_PACKET_DONE, err);
        if (st != RT_OK) return named(err, st);
    } else {
        snprintf(stats->kernels, sizeof stats->kernels, "one ray per work-item%s",
                 wave ? " (wavefront)" : "");
    }

    rt_counters *counts = NULL;
    if (frame->want_counts) {
        counts = malloc(sizeof(rt_counters) * RT_CL_TILE_MAX);
        if (!counts) return rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "opencl: out of memory");
    }
    double t_render = rt_now_ms();
    for (uint32_t first = 0; first < units && st == RT_OK;) {
        /* The tile in units (pixels, or blocks of lanes pixels); one entry
         * of counters per unit. */
        uint32_t per = lanes ? (s->tile / lanes ? s->tile / lanes : 1u) : s->tile;
        cl_uint n = units - first < per ? units - first : per;
        cl_uint tile_px = lanes ? n * lanes : n;
        double longest = 0.0;
        int overflow = 0;
        st = done_begin(s, err);
        if (st != RT_OK) break;
        if (lanes) {
            st = packet_tile(s, first, n, stats, &longest, err);
        } else if (wave) {
            st = wave_tile(s, slots, cap, first, n, stats, &longest, &overflow, err);
            stats->wave_tiles++;
            if (overflow) stats->wave_fallbacks++;
        }
        /* A level that queued more rays than the queues hold: the tile again
         * with the stack in the kernel (the same bits). */
        if (st == RT_OK && (overflow || (!lanes && !wave)))
            st = direct_tile(s, first, n, stats, &longest, err);
        if (st == RT_OK) {
            char what[96];
            if (lanes)
                snprintf(what, sizeof what, "blocks %u..%u of %ux%u pixels", (unsigned)first,
                         (unsigned)(first + n - 1), (unsigned)bw, (unsigned)bh);
            else
                snprintf(what, sizeof what, "pixels %u..%u", (unsigned)first,
                         (unsigned)(first + n - 1));
            st = done_check(s, what, err);
        }
        if (st != RT_OK) break;
        if (tile_px > stats->tile_pixels) stats->tile_pixels = tile_px;
        if (counts) {
            double t0 = rt_now_ms();
            st = read_buf(s, RT_CL_BUF_COUNTERS, sizeof(rt_counters) * n, counts, err);
            stats->download_ms += rt_now_ms() - t0;
            for (cl_uint i = 0; i < n && st == RT_OK; i++) {
                stats->rays += counts[i].rays;
                stats->box_tests += counts[i].box_tests;
                stats->tri_tests += counts[i].tri_tests;
            }
        }
        first += n;
        /* Only a full tile says how long a tile takes. */
        if (n == per) s->tile = next_tile(s, s->tile, longest);
        if (wave && s->tile > tmax) s->tile = tmax;
        if (frame->progress) frame->progress(frame->progress_user, (double)first / units);
    }
    free(counts);
    if (st == RT_OK) {
        double t0 = rt_now_ms();
        st = read_buf(s, RT_CL_BUF_FB, fb_bytes, frame->pixels, err);
        stats->download_ms += rt_now_ms() - t0;
    }
    if (st != RT_OK) return named(err, st);
    /* Wall time of the launches and their read-backs: comparable with the
     * CPU backends' render_ms. */
    stats->render_ms = rt_now_ms() - t_render;
    stats->primary_rays = pixels;
    stats->threads = (int)s->dev.compute_units;
    return RT_OK;
}

static rt_status cl_trace(void *state, const rt_backend_layout *layout, const rt_ray *rays,
                          const uint32_t *masks, size_t count, rt_hit_d *hits, int any_hit,
                          rt_trace_path path, rt_trace_stats *stats, rt_error *err) {
    cl_state *s = state;
    (void)path;
    (void)stats;
    (void)layout; /* cl_prepare uploaded it */
    /* Tiles of at most count rays (as frames, small queries small buffers). */
    uint32_t most = count < RT_CL_TILE_MAX ? (uint32_t)count : RT_CL_TILE_MAX;
    rt_status st = ensure_ray_buffers(s, most, err);
    int remade;
    if (st == RT_OK && masks) st = ensure(s, RT_CL_BUF_MASKS, sizeof(cl_uint) * most, &remade, err);
    /* Closest hits on a CPU device: packets of consecutive rays
     * (rt_k_packet_trace, the same hits); any hit: rt_k_trace, so that the
     * hit reported is the oracle's first one, not only some hit. */
    int packet = st == RT_OK && s->lanes && !any_hit;
    cl_kernel k = s ? (packet ? s->k_ptrace : s->k_trace) : NULL;
    _Static_assert((int)RT_K_PTRACE_COUNT == (int)RT_K_TRACE_COUNT &&
                       (int)RT_K_PTRACE_HITS - (int)RT_K_PTRACE_RAYS ==
                           (int)RT_K_TRACE_HITS - (int)RT_K_TRACE_RAYS &&
                       (int)RT_K_PTRACE_COUNTERS - (int)RT_K_PTRACE_RAYS ==
                           (int)RT_K_TRACE_COUNTERS - (int)RT_K_TRACE_RAYS &&
                       (int)RT_K_PTRACE_MASKED - (int)RT_K_PTRACE_RAYS ==
                           (int)RT_K_TRACE_MASKED - (int)RT_K_TRACE_RAYS &&
                       (int)RT_K_PTRACE_MASKS - (int)RT_K_PTRACE_RAYS ==
                           (int)RT_K_TRACE_MASKS - (int)RT_K_TRACE_RAYS,
                   "rt_k_trace and rt_k_packet_trace take count, rays, hits, counters, masked, "
                   "masks alike");
    cl_uint a = packet ? RT_K_PTRACE_RAYS : RT_K_TRACE_RAYS; /* the rays argument */
    cl_int any = any_hit ? 1 : 0;
    if (st == RT_OK) st = set_view(s, k, err);
    if (st == RT_OK && !packet) st = set_arg(k, RT_K_TRACE_ANY_HIT, sizeof any, &any, err);
    if (st == RT_OK) st = set_arg(k, a, sizeof(cl_mem), &s->buf[RT_CL_BUF_RAYS], err);
    if (st == RT_OK) st = set_arg(k, a + 1, sizeof(cl_mem), &s->buf[RT_CL_BUF_HITS], err);
    if (st == RT_OK) st = set_arg(k, a + 2, sizeof(cl_mem), &s->buf[RT_CL_BUF_COUNTERS], err);
    cl_uint masked = masks != NULL;
    if (st == RT_OK) st = set_arg(k, a + 3, sizeof masked, &masked, err);
    if (st == RT_OK) st = set_arg(k, a + 4, sizeof(cl_mem), &s->buf[RT_CL_BUF_MASKS], err);
    _Static_assert((int)RT_K_PTRACE_DONE - (int)RT_K_PTRACE_RAYS ==
                       (int)RT_K_TRACE_DONE - (int)RT_K_TRACE_RAYS,
                   "rt_k_trace and rt_k_packet_trace take done alike");
    if (st == RT_OK) st = bind_done(s, k, a + 5, err);
    for (size_t first = 0; first < count && st == RT_OK;) {
        cl_uint n = (cl_uint)(count - first < s->tile ? count - first : s->tile);
        uint64_t ignored = 0;
        double ms = 0.0;
        st = write_buf(s, RT_CL_BUF_RAYS, 0, rays + first, sizeof(rt_ray) * n, &ignored, err);
        if (st == RT_OK && masks)
            st =
                write_buf(s, RT_CL_BUF_MASKS, 0, masks + first, sizeof(cl_uint) * n, &ignored, err);
        if (st == RT_OK) st = set_arg(k, RT_K_TRACE_COUNT, sizeof n, &n, err);
        if (st == RT_OK) st = done_begin(s, err);
        if (st == RT_OK)
            st = launch(s, k, packet ? RT_CL_DONE_PTRACE : RT_CL_DONE_TRACE,
                        packet ? (n + (cl_uint)s->lanes - 1) / (cl_uint)s->lanes : n, &ms, err);
        if (st == RT_OK) {
            char what[64];
            snprintf(what, sizeof what, "rays %zu..%zu", first, first + n - 1);
            st = done_check(s, what, err);
        }
        if (st == RT_OK) {
            cl_int ce = clEnqueueReadBuffer(s->queue, s->buf[RT_CL_BUF_HITS], CL_TRUE, 0,
                                            sizeof(rt_hit_d) * n, hits + first, 0, NULL, NULL);
            if (ce != CL_SUCCESS)
                st = rt_fail(err, RT_ERROR_BACKEND, "reading hits: %s", rt_cl_error_name(ce));
        }
        first += n;
        if (n == s->tile) s->tile = next_tile(s, s->tile, ms);
    }
    if (st != RT_OK) return named(err, st);
    return RT_OK;
}

static const char *cl_build_log(void *state) {
    const cl_state *s = state;
    return s->build_log ? s->build_log : "";
}

static int cl_available(rt_error *why) {
    rt_cl_device_info *devs;
    int count;
    if (rt_cl_devices(&devs, &count, why) != RT_OK) return 0;
    free(devs);
    return 1;
}

const rt_backend_ops rt_backend_opencl = {"opencl",   cl_available, cl_create,
                                          cl_prepare, cl_render,    cl_trace,
                                          cl_destroy, cl_build_log, NULL};
