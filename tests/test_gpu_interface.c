/* SPDX-License-Identifier: Apache-2.0 */
/* test_gpu_interface.c - every field of every struct the host and the GPU
 * code exchange is where the device reads or writes it, on OpenCL and on
 * Vulkan. The host fills each input buffer (and the push constants) with
 * distinct words, tag(buffer, word index); a probe on the device
 * (kernels/rt_interface_test.cl, kernels/vulkan/rt_vk_interface_test.comp)
 * goes through the rows of kernels/rt_interface_fields.def, numbering their
 * words n = 0, 1, ...: it copies each input field to items[n] and writes
 * RT_PROBE_TAG + n into each output field. The host then checks each word
 * against offsetof() on the C side: items[n] must be the tag of the word at
 * the field's C offset (in element 1 of an array, so the element's size
 * counts too), and the output buffers must hold RT_PROBE_TAG + n at it. The
 * rows of a struct must fill its size, so a field missing from the list
 * fails too. Each backend without a device says "skipped" and why; the test
 * is skipped (77) when neither has one. */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rt_interface.h"
#include "rt_shade.h" /* rt_wave_entry, rt_wave_record */

#define RT_PROBE_TAG 0x40000000u

/* The backends pass rt_aov (rt.h) to the devices as it is: every AOV code
 * of the table must be its value there. */
#include "rt_interface_rows.h"
#undef RT_AOV
#define RT_AOV(NAME, code)                                                                         \
    _Static_assert((int)AOV_##NAME == (int)RT_AOV_##NAME, "AOV " #NAME " is rt_aov's");
#include "rt_interface.def"
#include "rt_interface_rows.h"

/* The probes' buffers. */
enum {
    PB_hdr,
    PB_nodes,
    PB_tris,
    PB_instances,
    PB_materials,
    PB_lights,
    PB_kd_nodes,
    PB_rays,
    PB_hits,
    PB_counters,
    PB_pc,
    PB_queue,
    PB_records,
    PB_COUNT
};
static const char *const pb_names[PB_COUNT] = {
    "hdr",  "nodes", "tris",     "instances", "materials", "lights", "kd_nodes",
    "rays", "hits",  "counters", "pc",        "queue",     "records"};

/* The word the host writes at index w of buffer b: a normal float, distinct
 * for every buffer and word. */
static uint32_t tag(int b, size_t w) {
    return RT_PROBE_TAG | ((uint32_t)b << 16) | (uint32_t)w;
}

/* One row of rt_interface_fields.def as the host sees it. */
typedef struct probe_row {
    int buffer;    /* PB_* */
    int out;       /* 1: the device writes the field */
    size_t offset; /* offsetof(struct, field) */
    int count;     /* words */
    size_t size;   /* sizeof(struct) */
    const char *name;
} probe_row;

#define RT_DIR_IN  0
#define RT_DIR_OUT 1
#define RT_FIELD(dir, buf, type, field, kind)                                                      \
    {PB_##buf, RT_DIR_##dir, offsetof(type, field), 1, sizeof(type), #type "." #field},
#define RT_FIELDS(dir, buf, type, field, count, kind)                                              \
    {PB_##buf, RT_DIR_##dir, offsetof(type, field), count, sizeof(type), #type "." #field},

#ifdef RT_HAVE_VULKAN
#define RT_VK_ONLY(rows) rows
#define RT_CL_ONLY(rows)
static const probe_row vk_rows[] = {
#include "rt_interface_fields.def"
};
#undef RT_VK_ONLY
#undef RT_CL_ONLY
#endif
#ifdef RT_HAVE_OPENCL
#define RT_VK_ONLY(rows)
#define RT_CL_ONLY(rows) rows
static const probe_row cl_rows[] = {
#include "rt_interface_fields.def"
};
#endif
#define ROWS(a) (sizeof a / sizeof a[0])

/* The buffers of one probe run: bytes, contents, and the words written. */
typedef struct probe_buffers {
    size_t bytes[PB_COUNT];
    uint32_t *data[PB_COUNT];
    size_t items;    /* words of items[] */
    uint32_t *found; /* items[] after the run */
} probe_buffers;

/* Elements of a buffer's struct the probe's buffers hold: two (the probe
 * reads element 1), one for the header and the push constants. */
static int elements(int b) {
    return b == PB_hdr || b == PB_pc ? 1 : 2;
}

/* Sizes every buffer from its rows, checks that the rows of each struct
 * fill it, and fills the inputs with tags (outputs with zeros). */
static void probe_setup(const probe_row *rows, size_t n, probe_buffers *p) {
    memset(p, 0, sizeof *p);
    size_t words[PB_COUNT] = {0}, size[PB_COUNT] = {0};
    for (size_t i = 0; i < n; i++) {
        words[rows[i].buffer] += (size_t)rows[i].count;
        size[rows[i].buffer] = rows[i].size;
        p->items += (size_t)rows[i].count;
    }
    for (int b = 0; b < PB_COUNT; b++) {
        if (!size[b]) continue;
        CHECK_MSG(words[b] * 4 == size[b],
                  "%s: rt_interface_fields.def lists %zu words of its struct, sizeof is %zu bytes",
                  pb_names[b], words[b], size[b]);
        p->bytes[b] = size[b] * (size_t)elements(b);
        p->data[b] = calloc(p->bytes[b] / 4, 4);
        int out = 0;
        for (size_t i = 0; i < n; i++)
            if (rows[i].buffer == b) out = rows[i].out;
        for (size_t w = 0; !out && w < p->bytes[b] / 4; w++) p->data[b][w] = tag(b, w);
    }
    p->found = calloc(p->items ? p->items : 1, 4);
}

/* Checks a run's results against the C offsets; what names the backend. */
static void probe_check(const char *what, const probe_row *rows, size_t n, const probe_buffers *p) {
    size_t word = 0;
    int bad = 0;
    for (size_t i = 0; i < n; i++) {
        const probe_row *r = &rows[i];
        size_t base = (elements(r->buffer) - 1) * (r->size / 4) + r->offset / 4;
        for (int k = 0; k < r->count; k++, word++) {
            uint32_t got, want;
            if (r->out) {
                got = p->data[r->buffer][base + (size_t)k];
                want = RT_PROBE_TAG + (uint32_t)word;
            } else {
                got = p->found[word];
                want = tag(r->buffer, base + (size_t)k);
            }
            if (got == want || bad++ >= 20) continue;
            char field[96];
            if (r->count > 1)
                snprintf(field, sizeof field, "%s[%d]", r->name, k);
            else
                snprintf(field, sizeof field, "%s", r->name);
            if (r->out)
                CHECK_MSG(0,
                          "%s: %s (%s, C offset %zu) holds 0x%08x, the device's write was 0x%08x",
                          what, field, pb_names[r->buffer], r->offset + 4 * (size_t)k, got, want);
            else
                CHECK_MSG(0,
                          "%s: %s (%s, C offset %zu): the device read 0x%08x, the host's word "
                          "there is 0x%08x",
                          what, field, pb_names[r->buffer], r->offset + 4 * (size_t)k, got, want);
        }
    }
    CHECK_MSG(bad == 0, "%s: %d of %zu words misplaced", what, bad, p->items);
    if (bad == 0) printf("%s: %zu words of %zu fields where C puts them\n", what, p->items, n);
}

static void probe_free(probe_buffers *p) {
    for (int b = 0; b < PB_COUNT; b++) free(p->data[b]);
    free(p->found);
}

/* ---- Vulkan -------------------------------------------------------------- */

#ifdef RT_HAVE_VULKAN
#include "vulkan/vk_backend.h"
#include "vulkan/vk_device.h"

/* 1 when it ran, 0 when skipped. */
static int run_vulkan(void) {
    rt_vk_device_info *devs;
    int count;
    rt_error err;
    if (rt_vk_devices(&devs, &count, &err) != RT_OK) {
        printf("vulkan: skipped: %s\n", err.message);
        return 0;
    }
    free(devs);
    probe_buffers p;
    probe_setup(vk_rows, ROWS(vk_rows), &p);
    static const int binding[PB_COUNT] = {[PB_hdr] = RT_VK_BUF_HDR,
                                          [PB_nodes] = RT_VK_BUF_NODES,
                                          [PB_tris] = RT_VK_BUF_TRIS,
                                          [PB_instances] = RT_VK_BUF_INSTANCES,
                                          [PB_materials] = RT_VK_BUF_MATERIALS,
                                          [PB_lights] = RT_VK_BUF_LIGHTS,
                                          [PB_kd_nodes] = RT_VK_BUF_KD_NODES,
                                          [PB_rays] = RT_VK_BUF_RAYS,
                                          [PB_hits] = RT_VK_BUF_HITS,
                                          [PB_counters] = RT_VK_BUF_COUNTERS,
                                          [PB_pc] = -1,
                                          [PB_queue] = -1,
                                          [PB_records] = -1};
    const void *in[RT_VK_BUF_COUNT] = {0};
    void *out[RT_VK_BUF_COUNT] = {0};
    size_t bytes[RT_VK_BUF_COUNT] = {0};
    for (int b = 0; b < PB_COUNT; b++) {
        if (binding[b] < 0 || !p.bytes[b]) continue;
        in[binding[b]] = p.data[b];
        out[binding[b]] = p.data[b];
        bytes[binding[b]] = p.bytes[b];
    }
    in[RT_VK_BUF_ITEMS] = p.found;
    out[RT_VK_BUF_ITEMS] = p.found;
    bytes[RT_VK_BUF_ITEMS] = 4 * p.items;
    rt_vk_push push;
    CHECK(p.bytes[PB_pc] == sizeof push);
    memcpy(&push, p.data[PB_pc], sizeof push);
    rt_status st = rt_vk_interface_probe(NULL, in, out, bytes, &push, &err);
    CHECK_MSG(st == RT_OK, "vulkan: the probe failed: %s", err.message);
    if (st == RT_OK) probe_check("vulkan", vk_rows, ROWS(vk_rows), &p);
    probe_free(&p);
    return 1;
}
#else
static int run_vulkan(void) {
    printf("vulkan: skipped: this build has no Vulkan backend\n");
    return 0;
}
#endif

/* ---- OpenCL -------------------------------------------------------------- */

#ifdef RT_HAVE_OPENCL
#include <CL/cl.h>

#include "opencl/cl_device.h"

/* The probe's own arguments after the view's. */
enum { ARG_RAYS = RT_ARG_VIEW_COUNT, ARG_HITS, ARG_COUNTERS, ARG_QUEUE, ARG_RECORDS, ARG_ITEMS };

static char *read_text(const char *path) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *s = n >= 0 ? malloc((size_t)n + 1) : NULL;
    if (s && fread(s, 1, (size_t)n, f) != (size_t)n) {
        free(s);
        s = NULL;
    }
    if (s) s[n] = 0;
    fclose(f);
    return s;
}

static int run_opencl(void) {
    rt_cl_device_info *devs;
    int count;
    rt_error err;
    if (rt_cl_devices(&devs, &count, &err) != RT_OK) {
        printf("opencl: skipped: %s\n", err.message);
        return 0;
    }
    int pick = rt_cl_select(devs, count, NULL, &err);
    if (pick < 0) {
        printf("opencl: skipped: %s\n", err.message);
        free(devs);
        return 0;
    }
    const char *root = getenv("RT_SOURCE_DIR");
    char path[4096], options[4200];
    snprintf(path, sizeof path, "%s/kernels/rt_interface_test.cl", root ? root : ".");
    snprintf(options, sizeof options, "-I %s/kernels", root ? root : ".");
    char *src = read_text(path);
    CHECK_MSG(src != NULL, "cannot read %s (RT_SOURCE_DIR is the source tree)", path);
    cl_device_id d = devs[pick].device_id;
    cl_context_properties props[] = {CL_CONTEXT_PLATFORM,
                                     (cl_context_properties)devs[pick].platform_id, 0};
    free(devs);
    if (!src) return 1;
    cl_int ce;
    cl_context ctx = clCreateContext(props, 1, &d, NULL, NULL, &ce);
    CHECK(ctx != NULL);
    cl_command_queue q = ctx ? clCreateCommandQueue(ctx, d, 0, &ce) : NULL;
    const char *srcs[1] = {src};
    cl_program prog = ctx ? clCreateProgramWithSource(ctx, 1, srcs, NULL, &ce) : NULL;
    ce = prog ? clBuildProgram(prog, 1, &d, options, NULL, NULL) : CL_INVALID_PROGRAM;
    if (ce != CL_SUCCESS && prog) {
        char log[4096] = "";
        clGetProgramBuildInfo(prog, d, CL_PROGRAM_BUILD_LOG, sizeof log - 1, log, NULL);
        CHECK_MSG(0, "opencl: building %s: %d\n%s", path, (int)ce, log);
    }
    cl_kernel k = ce == CL_SUCCESS ? clCreateKernel(prog, "rt_k_interface_test", &ce) : NULL;
    CHECK(q != NULL && k != NULL);
    probe_buffers p;
    probe_setup(cl_rows, ROWS(cl_rows), &p);
    /* The view's arrays by their kernel arguments; those the probe does not
     * read get a stub. */
    int view_buffer[RT_ARG_VIEW_COUNT];
    for (int a = 0; a < RT_ARG_VIEW_COUNT; a++) view_buffer[a] = -1;
    view_buffer[RT_ARG_HDR] = PB_hdr;
    view_buffer[RT_ARG_NODES] = PB_nodes;
    view_buffer[RT_ARG_TRIS] = PB_tris;
    view_buffer[RT_ARG_INSTANCES] = PB_instances;
    view_buffer[RT_ARG_MATERIALS] = PB_materials;
    view_buffer[RT_ARG_LIGHTS] = PB_lights;
    view_buffer[RT_ARG_KD_NODES] = PB_kd_nodes;
    cl_mem mem[PB_COUNT] = {0}, stub = NULL, items = NULL;
    uint32_t zero[4] = {0};
    if (k) {
        stub =
            clCreateBuffer(ctx, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, sizeof zero, zero, &ce);
        items = clCreateBuffer(ctx, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, 4 * p.items, p.found,
                               &ce);
        for (int b = 0; b < PB_COUNT; b++)
            if (p.bytes[b])
                mem[b] = clCreateBuffer(ctx, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, p.bytes[b],
                                        p.data[b], &ce);
        for (int a = 0; a < RT_ARG_VIEW_COUNT; a++) {
            cl_mem m = view_buffer[a] >= 0 ? mem[view_buffer[a]] : stub;
            clSetKernelArg(k, (cl_uint)a, sizeof m, &m);
        }
        clSetKernelArg(k, ARG_RAYS, sizeof(cl_mem), &mem[PB_rays]);
        clSetKernelArg(k, ARG_HITS, sizeof(cl_mem), &mem[PB_hits]);
        clSetKernelArg(k, ARG_COUNTERS, sizeof(cl_mem), &mem[PB_counters]);
        clSetKernelArg(k, ARG_QUEUE, sizeof(cl_mem), &mem[PB_queue]);
        clSetKernelArg(k, ARG_RECORDS, sizeof(cl_mem), &mem[PB_records]);
        clSetKernelArg(k, ARG_ITEMS, sizeof(cl_mem), &items);
        size_t global = 1;
        ce = clEnqueueNDRangeKernel(q, k, 1, NULL, &global, NULL, 0, NULL, NULL);
        CHECK_MSG(ce == CL_SUCCESS, "opencl: running the probe: %d", (int)ce);
        if (ce == CL_SUCCESS)
            ce = clEnqueueReadBuffer(q, items, CL_TRUE, 0, 4 * p.items, p.found, 0, NULL, NULL);
        for (int b = 0; b < PB_COUNT && ce == CL_SUCCESS; b++)
            if (mem[b])
                ce = clEnqueueReadBuffer(q, mem[b], CL_TRUE, 0, p.bytes[b], p.data[b], 0, NULL,
                                         NULL);
        CHECK_MSG(ce == CL_SUCCESS, "opencl: reading the probe's results: %d", (int)ce);
        if (ce == CL_SUCCESS) probe_check("opencl", cl_rows, ROWS(cl_rows), &p);
    }
    for (int b = 0; b < PB_COUNT; b++)
        if (mem[b]) clReleaseMemObject(mem[b]);
    if (stub) clReleaseMemObject(stub);
    if (items) clReleaseMemObject(items);
    if (k) clReleaseKernel(k);
    if (prog) clReleaseProgram(prog);
    if (q) clReleaseCommandQueue(q);
    if (ctx) clReleaseContext(ctx);
    probe_free(&p);
    free(src);
    return 1;
}
#else
static int run_opencl(void) {
    printf("opencl: skipped: this build has no OpenCL backend\n");
    return 0;
}
#endif

int main(void) {
    int ran = run_opencl();
    ran += run_vulkan();
    if (!ran) test_skip("no OpenCL or Vulkan device");
    return TEST_END();
}
