/* SPDX-License-Identifier: Apache-2.0 */
/* test_soft_math_opencl.c - kernels/rt_soft_math.h compiled as OpenCL C gives
 * the bits of the C build, and stays free of what a portable device may lack.
 *
 * 1. On an OpenCL device (a CPU device preferred: PoCL), a kernel runs the
 *    six _bits functions and the three float ones on the special values, all
 *    their pairs, 10^5 random operand sets (tests/soft_math_cases.h); every
 *    result equals the C build's, bit for bit (NaNs included: the same code).
 * 2. The header's code (comments removed) has no division operator, no
 *    sqrt / fma / mad / native_ / half_ functions, no double and no 64-bit
 *    integer types.
 * 3. Where clang is installed ($RT_CLANG, else clang on the PATH), the header
 *    compiled as OpenCL C 1.2 for 32-bit SPIR at -O0 (the IR follows the
 *    source) has no floating-point instruction but fadd, fsub and fmul (the
 *    correctly rounded ones the fast paths use), none of them with a
 *    fast-math flag (so no fdiv, no fma, no contraction, no comparison or
 *    conversion), no double, and calls nothing but clz and its own
 *    functions.
 * Exits 77 (skipped) only when the build has no OpenCL or there is no
 * device; part 3 reports when clang is missing and is then not run. */
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rt_soft_math.h"
#include "soft_math_cases.h"

#ifdef RT_HAVE_OPENCL
#include <CL/cl.h>

#define N_OUT 9 /* results per operand set */

static const char *kernel_src =
    "#include \"rt_soft_math.h\"\n"
    "__kernel void sm_run(__global const uint *in, __global uint *out, uint n) {\n"
    "    uint i = (uint)get_global_id(0);\n"
    "    if (i >= n) return;\n"
    "    uint a = in[4 * i], b = in[4 * i + 1], c = in[4 * i + 2], d = in[4 * i + 3];\n"
    "    __global uint *o = out + 9 * i;\n"
    "    o[0] = rt_soft_div_bits(a, b);\n"
    "    o[1] = rt_soft_div_ftz_bits(a, b);\n"
    "    o[2] = rt_soft_sqrt_bits(a);\n"
    "    o[3] = rt_soft_sqrt_ftz_bits(a);\n"
    "    o[4] = rt_soft_diff_of_products_bits(a, b, c, d);\n"
    "    o[5] = rt_soft_diff_of_products_ftz_bits(a, b, c, d);\n"
    "    o[6] = as_uint(rt_soft_div(as_float(a), as_float(b)));\n"
    "    o[7] = as_uint(rt_soft_sqrt(as_float(a)));\n"
    "    o[8] = as_uint(rt_soft_diff_of_products(as_float(a), as_float(b), as_float(c),\n"
    "                                            as_float(d)));\n"
    "}\n";

static void c_results(const uint32_t *q, uint32_t *o) {
    o[0] = rt_soft_div_bits(q[0], q[1]);
    o[1] = rt_soft_div_ftz_bits(q[0], q[1]);
    o[2] = rt_soft_sqrt_bits(q[0]);
    o[3] = rt_soft_sqrt_ftz_bits(q[0]);
    o[4] = rt_soft_diff_of_products_bits(q[0], q[1], q[2], q[3]);
    o[5] = rt_soft_diff_of_products_ftz_bits(q[0], q[1], q[2], q[3]);
    o[6] = o[0];
    o[7] = o[2];
    o[8] = o[4];
}

/* Picks a device (CPU first); 0 when there is none. */
static int pick_device(cl_device_id *dev, char *name, size_t name_size) {
    cl_platform_id plats[16];
    cl_uint np = 0;
    if (clGetPlatformIDs(16, plats, &np) != CL_SUCCESS || np == 0) return 0;
    const cl_device_type types[2] = {CL_DEVICE_TYPE_CPU, CL_DEVICE_TYPE_ALL};
    for (int t = 0; t < 2; t++) {
        for (cl_uint p = 0; p < np && p < 16; p++) {
            cl_uint nd = 0;
            if (clGetDeviceIDs(plats[p], types[t], 1, dev, &nd) == CL_SUCCESS && nd > 0) {
                clGetDeviceInfo(*dev, CL_DEVICE_NAME, name_size, name, NULL);
                return 1;
            }
        }
    }
    return 0;
}

/* Part 1: the device against the C build. */
static void check_device(void) {
    cl_device_id dev;
    char name[256] = "";
    if (!pick_device(&dev, name, sizeof name)) test_skip("no OpenCL device");
    printf("device: %s\n", name);

    /* Operand sets: pairs of specials (c, d the pair reversed), random. */
    uint32_t sp[512];
    int ns = sm_specials(sp);
    size_t n = (size_t)ns * (size_t)ns + 100000;
    uint32_t *in = malloc(n * 4 * sizeof *in);
    uint32_t *out = malloc(n * N_OUT * sizeof *out);
    CHECK(in && out);
    if (!in || !out) return;
    size_t k = 0;
    for (int i = 0; i < ns; i++) {
        for (int j = 0; j < ns; j++, k++) {
            uint32_t *q = in + 4 * k;
            q[0] = sp[i], q[1] = sp[j], q[2] = sp[(i * 7 + j) % ns], q[3] = sp[(j * 13 + i) % ns];
        }
    }
    uint64_t seed = 0x243f6a8885a308d3ull;
    for (; k < n; k++) {
        uint32_t *q = in + 4 * k;
        switch (k % 3) {
        case 0:
            sm_dop_quad(&seed, q);
            break;
        case 1:
            sm_div_pair(&seed, &q[0], &q[1]);
            q[2] = sm_operand(&seed), q[3] = sm_operand(&seed);
            break;
        default:
            for (int j = 0; j < 4; j++) q[j] = sm_rand(&seed);
        }
    }

    cl_int err;
    cl_context ctx = clCreateContext(NULL, 1, &dev, NULL, NULL, &err);
    CHECK_MSG(err == CL_SUCCESS, "clCreateContext: %d", (int)err);
    cl_command_queue queue = clCreateCommandQueue(ctx, dev, 0, &err);
    CHECK_MSG(err == CL_SUCCESS, "clCreateCommandQueue: %d", (int)err);
    cl_program prog = clCreateProgramWithSource(ctx, 1, &kernel_src, NULL, &err);
    char options[4200];
    snprintf(options, sizeof options, "-cl-std=CL1.2 -I %s", test_source_path("kernels"));
    err = clBuildProgram(prog, 1, &dev, options, NULL, NULL);
    if (err != CL_SUCCESS) {
        static char log[65536];
        clGetProgramBuildInfo(prog, dev, CL_PROGRAM_BUILD_LOG, sizeof log, log, NULL);
        CHECK_MSG(0, "clBuildProgram: %d\n%s", (int)err, log);
        return;
    }
    test_checks++;
    cl_kernel kern = clCreateKernel(prog, "sm_run", &err);
    CHECK_MSG(err == CL_SUCCESS, "clCreateKernel: %d", (int)err);
    cl_mem bin =
        clCreateBuffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, n * 4 * sizeof *in, in, &err);
    cl_mem bout = clCreateBuffer(ctx, CL_MEM_WRITE_ONLY, n * N_OUT * sizeof *out, NULL, &err);
    cl_uint nn = (cl_uint)n;
    clSetKernelArg(kern, 0, sizeof bin, &bin);
    clSetKernelArg(kern, 1, sizeof bout, &bout);
    clSetKernelArg(kern, 2, sizeof nn, &nn);
    size_t global = (n + 63) / 64 * 64;
    err = clEnqueueNDRangeKernel(queue, kern, 1, NULL, &global, NULL, 0, NULL, NULL);
    CHECK_MSG(err == CL_SUCCESS, "clEnqueueNDRangeKernel: %d", (int)err);
    err = clEnqueueReadBuffer(queue, bout, CL_TRUE, 0, n * N_OUT * sizeof *out, out, 0, NULL, NULL);
    CHECK_MSG(err == CL_SUCCESS, "clEnqueueReadBuffer: %d", (int)err);

    static const char *names[N_OUT] = {"div_bits",      "div_ftz_bits", "sqrt_bits",
                                       "sqrt_ftz_bits", "dop_bits",     "dop_ftz_bits",
                                       "div (float)",   "sqrt (float)", "dop (float)"};
    long bad = 0;
    for (size_t i = 0; i < n; i++) {
        uint32_t want[N_OUT];
        c_results(in + 4 * i, want);
        for (int j = 0; j < N_OUT; j++) {
            if (want[j] == out[N_OUT * i + j]) continue;
            if (bad++ < 8)
                fprintf(stderr, "%s(%08x %08x %08x %08x): C %08x OpenCL %08x\n", names[j],
                        (unsigned)in[4 * i], (unsigned)in[4 * i + 1], (unsigned)in[4 * i + 2],
                        (unsigned)in[4 * i + 3], (unsigned)want[j], (unsigned)out[N_OUT * i + j]);
        }
    }
    printf("OpenCL vs C: %zu operand sets x %d functions, %ld mismatches\n", n, N_OUT, bad);
    CHECK_MSG(bad == 0, "%ld results differ between OpenCL and C", bad);

    clReleaseMemObject(bin);
    clReleaseMemObject(bout);
    clReleaseKernel(kern);
    clReleaseProgram(prog);
    clReleaseCommandQueue(queue);
    clReleaseContext(ctx);
    free(in);
    free(out);
}

/* The whole file in a malloc'ed string, or NULL. */
static char *read_text(const char *path) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    size_t cap = 1 << 16, len = 0;
    char *s = malloc(cap);
    size_t got;
    while (s && (got = fread(s + len, 1, cap - len - 1, f)) > 0) {
        len += got;
        if (len + 1 == cap) {
            char *t = realloc(s, cap *= 2);
            if (!t) free(s);
            s = t;
        }
    }
    fclose(f);
    if (s) s[len] = '\0';
    return s;
}

/* Part 2: the source, comments blanked, token by token. */
static void check_source(void) {
    char *src = read_text(test_source_path("kernels/rt_soft_math.h"));
    CHECK_MSG(src != NULL, "cannot read kernels/rt_soft_math.h");
    if (!src) return;
    for (char *p = src; *p; p++) { /* blank comments (no string literals in the header) */
        if (p[0] == '/' && p[1] == '*') {
            char *e = strstr(p + 2, "*/");
            char *end = e ? e + 2 : p + strlen(p);
            memset(p, ' ', (size_t)(end - p));
            p = end - 1;
        } else if (p[0] == '/' && p[1] == '/') {
            while (*p && *p != '\n') *p++ = ' ';
            if (!*p) break;
        }
    }
    static const char *banned[] = {
        "double",      "long",         "ulong",      "size_t",      "int64_t",   "uint64_t",
        "__int128",    "sqrt",         "sqrtf",      "rsqrt",       "fma",       "fmaf",
        "mad",         "mad24",        "divide",     "native_sqrt", "half_sqrt", "native_divide",
        "half_divide", "native_recip", "half_recip", "cl_khr_fp64", "fdiv",      "fmod"};
    int found = 0;
    const char *slash = strchr(src, '/');
    CHECK_MSG(slash == NULL, "rt_soft_math.h has a '/' outside comments: ...%.40s", slash);
    for (const char *p = src; *p;) {
        if (isalpha((unsigned char)*p) || *p == '_') {
            const char *s = p;
            while (isalnum((unsigned char)*p) || *p == '_') p++;
            size_t len = (size_t)(p - s);
            for (size_t i = 0; i < sizeof banned / sizeof banned[0]; i++) {
                if (strlen(banned[i]) == len && !strncmp(s, banned[i], len)) {
                    CHECK_MSG(0, "rt_soft_math.h uses '%s'", banned[i]);
                    found++;
                }
            }
        } else {
            p++;
        }
    }
    printf("source scan: %d banned tokens, %s '/' outside comments\n", found, slash ? "a" : "no");
    free(src);
}

/* Part 3: the IR. */
static void check_ir(void) {
    const char *clang = getenv("RT_CLANG");
    if (!clang || !*clang) clang = "clang";
    char probe[512];
    snprintf(probe, sizeof probe, "%s --version >/dev/null 2>&1", clang);
    if (system(probe) != 0) {
        printf("IR check not run: no %s (set RT_CLANG to a clang with OpenCL C)\n", clang);
        return;
    }
    const char *cl =
        test_write_temp("sm_ir.cl", "#include \"rt_soft_math.h\"\n"
                                    "__kernel void sm_ir(__global uint *io) {\n"
                                    "    io[0] = rt_soft_div_bits(io[0], io[1]);\n"
                                    "    io[1] = rt_soft_div_ftz_bits(io[0], io[1]);\n"
                                    "    io[2] = rt_soft_sqrt_bits(io[2]);\n"
                                    "    io[3] = rt_soft_sqrt_ftz_bits(io[3]);\n"
                                    "    io[4] = rt_soft_diff_of_products_bits(io[0], io[1], "
                                    "io[2], io[3]);\n"
                                    "    io[5] = rt_soft_diff_of_products_ftz_bits(io[0], io[1], "
                                    "io[2], io[3]);\n"
                                    "    __global float *f = (__global float *)(io + 6);\n"
                                    "    f[0] = rt_soft_div(f[0], f[1]);\n"
                                    "    f[1] = rt_soft_sqrt(f[1]);\n"
                                    "    f[2] = rt_soft_div_ftz(f[2], f[3]);\n"
                                    "    f[3] = rt_soft_sqrt_ftz(f[3]);\n"
                                    "    f[4] = rt_soft_diff_of_products(f[0], f[1], f[2], f[3]);\n"
                                    "    f[5] = rt_soft_diff_of_products_ftz(f[0], f[1], f[2], "
                                    "f[3]);\n"
                                    "}\n");
    char cmd[8192];
    snprintf(cmd, sizeof cmd,
             "%s -x cl -cl-std=CL1.2 -Xclang -finclude-default-header -target spir -emit-llvm "
             "-S -O0 -I %s -o - %s 2>&1",
             clang, test_source_path("kernels"), cl);
    FILE *p = popen(cmd, "r");
    CHECK_MSG(p != NULL, "cannot run %s", cmd);
    if (!p) return;
    /* fadd, fsub and fmul are allowed, but not with a fast-math flag (it
     * stands between the opcode and the type: "fmul contract float"). */
    static const char *banned[] = {
        " fdiv ",     " frem ",    " fneg ",        " fcmp ",   " fpext ", " fptrunc ",
        " sitofp ",   " uitofp ",  " fptosi ",      " fptoui ", "double",  " contract ",
        " reassoc ",  " afn ",     " arcp ",        " fast ",   " nnan ",  " ninf ",
        "@llvm.sqrt", "@llvm.fma", "@llvm.fmuladd", "sqrt",     "divide"};
    const size_t callee_only = sizeof banned / sizeof banned[0] - 2; /* sqrt, divide */
    char line[4096];
    int lines = 0, bad = 0, defines = 0;
    while (fgets(line, sizeof line, p)) {
        lines++;
        if (!strncmp(line, "define ", 7)) defines++;
        int is_call = strstr(line, " call ") != NULL || !strncmp(line, "declare ", 8);
        for (size_t i = 0; i < sizeof banned / sizeof banned[0]; i++) {
            /* "sqrt" and "divide" are banned in callees, not in our own names. */
            if (i >= callee_only && !is_call) continue;
            const char *hit = strstr(line, banned[i]);
            if (i >= callee_only && hit && strstr(line, "@rt_")) continue;
            if (hit) {
                if (bad++ < 8) fprintf(stderr, "IR: '%s' in: %s", banned[i], line);
            }
        }
        if (is_call) { /* callees: clz, get_global_id and our own functions only */
            const char *at = strchr(line, '@');
            if (at && strncmp(at, "@rt_", 4) && strncmp(at, "@_Z3clzj", 8) &&
                strncmp(at, "@llvm.lifetime", 14) && strncmp(at, "@llvm.memcpy", 12)) {
                if (bad++ < 8) fprintf(stderr, "IR: unexpected call in: %s", line);
            }
        }
    }
    int rc = pclose(p);
    CHECK_MSG(rc == 0 && defines >= 12, "%s failed (exit %d, %d functions)", cmd, rc, defines);
    printf("IR check (%s, OpenCL C 1.2, spir, -O0): %d lines, %d functions, %d banned\n", clang,
           lines, defines, bad);
    CHECK_MSG(bad == 0, "the OpenCL IR of rt_soft_math.h has %d banned operations", bad);
}

int main(void) {
    check_source();
    check_ir();
    check_device();
    return TEST_END();
}
#else
int main(void) {
    test_skip("the build has no OpenCL");
}
#endif
