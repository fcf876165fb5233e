/* SPDX-License-Identifier: Apache-2.0 */
/* spv_precise.c - a build step of the Vulkan shaders: decorates every float
 * arithmetic instruction of a SPIR-V module NoContraction (GLSL's 'precise'),
 * so that no Vulkan implementation may fuse a multiply and an add, reorder a
 * sum or turn x / y into x * (1 / y). Writing 'precise' on every variable of
 * the GLSL would do the same by hand, with a missed one silently allowing
 * contraction; here nothing is missed by construction, and
 * tests/cli_vulkan_spirv.sh checks the shipped modules.
 *
 *   spv_precise IN.spv OUT.spv
 *
 * The decorations are appended to the module's annotation section (after its
 * last OpDecorate-like instruction). Exit status 1 with a message on a file
 * that is not SPIR-V. Only for the build (not linked into the library). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum {
    OP_TYPE_FLOAT = 22,
    OP_TYPE_VECTOR = 23,
    OP_TYPE_MATRIX = 24,
    OP_DECORATE = 71,
    DEC_NO_CONTRACTION = 42
};

/* Float arithmetic whose result rounds (or that a compiler could fuse with
 * one that does): FNegate, FAdd, FSub, FMul, FDiv, FRem, FMod,
 * VectorTimesScalar, MatrixTimesScalar, VectorTimesMatrix,
 * MatrixTimesVector, MatrixTimesMatrix, OuterProduct, Dot. */
static int float_arith(uint32_t op) {
    return op == 127 || op == 129 || op == 131 || op == 133 || op == 136 || op == 138 ||
           op == 141 || (op >= 142 && op <= 148);
}

/* Annotation instructions: Decorate, MemberDecorate, DecorationGroup,
 * GroupDecorate, GroupMemberDecorate, DecorateId, DecorateString,
 * MemberDecorateString. */
static int annotation(uint32_t op) {
    return (op >= 71 && op <= 75) || op == 332 || op == 5632 || op == 5633;
}

static uint32_t *read_all(const char *path, size_t *words) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    size_t cap = 1 << 16, n = 0;
    uint32_t *w = malloc(cap * 4);
    size_t got;
    while (w && (got = fread(w + n, 4, cap - n, f)) > 0) {
        n += got;
        if (n == cap) {
            uint32_t *m = realloc(w, (cap *= 2) * 4);
            if (!m) free(w);
            w = m;
        }
    }
    fclose(f);
    *words = n;
    return w;
}

int main(int argc, char **argv) {
    if (argc != 3) {
        fprintf(stderr, "usage: spv_precise IN.spv OUT.spv\n");
        return 2;
    }
    size_t n;
    uint32_t *w = read_all(argv[1], &n);
    if (!w || n < 5 || w[0] != 0x07230203u) {
        fprintf(stderr, "spv_precise: %s: not a SPIR-V module\n", argv[1]);
        return 1;
    }
    uint32_t bound = w[3];
    unsigned char *is_float = calloc(bound, 1), *decorated = calloc(bound, 1),
                  *wanted = calloc(bound, 1);
    if (!is_float || !decorated || !wanted) return 1;
    size_t insert_at = 0, first_type = 0;
    for (size_t i = 5; i < n;) {
        uint32_t op = w[i] & 0xffffu, len = w[i] >> 16;
        if (len == 0 || i + len > n) {
            fprintf(stderr, "spv_precise: %s: malformed instruction at word %zu\n", argv[1], i);
            return 1;
        }
        if (op == OP_TYPE_FLOAT && w[i + 1] < bound) is_float[w[i + 1]] = 1;
        if ((op == OP_TYPE_VECTOR || op == OP_TYPE_MATRIX) && w[i + 1] < bound &&
            w[i + 2] < bound && is_float[w[i + 2]])
            is_float[w[i + 1]] = 1;
        if (op == OP_DECORATE && len >= 3 && w[i + 2] == DEC_NO_CONTRACTION && w[i + 1] < bound)
            decorated[w[i + 1]] = 1;
        if (annotation(op)) insert_at = i + len;
        if (!first_type && op >= 19 && op <= 39) first_type = i;
        if (float_arith(op) && len >= 3 && w[i + 1] < bound && w[i + 2] < bound &&
            is_float[w[i + 1]])
            wanted[w[i + 2]] = 1;
        i += len;
    }
    if (!insert_at) insert_at = first_type;
    if (!insert_at) {
        fprintf(stderr, "spv_precise: %s: no annotation or type section\n", argv[1]);
        return 1;
    }
    FILE *out = fopen(argv[2], "wb");
    if (!out) {
        fprintf(stderr, "spv_precise: cannot write %s\n", argv[2]);
        return 1;
    }
    fwrite(w, 4, insert_at, out);
    unsigned added = 0;
    for (uint32_t id = 0; id < bound; id++) {
        if (!wanted[id] || decorated[id]) continue;
        uint32_t dec[3] = {(3u << 16) | OP_DECORATE, id, DEC_NO_CONTRACTION};
        fwrite(dec, 4, 3, out);
        added++;
    }
    fwrite(w + insert_at, 4, n - insert_at, out);
    if (fclose(out) != 0) {
        fprintf(stderr, "spv_precise: writing %s failed\n", argv[2]);
        return 1;
    }
    free(w);
    free(is_float);
    free(decorated);
    free(wanted);
    return 0;
}
