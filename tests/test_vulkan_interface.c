/* SPDX-License-Identifier: Apache-2.0 */
/* test_vulkan_interface.c - the Vulkan shaders as built declare the
 * interface of kernels/rt_interface.def, as test_opencl_kernel_args does for
 * the OpenCL kernels. Reads the embedded SPIR-V of every shipped module (no
 * device needed) and checks:
 * - every storage buffer is in descriptor set 0 at a binding of the table,
 *   and its block is the table's (B_<name>); the main shader has every
 *   buffer of the table, and the bindings are 0 .. RT_VK_BUF_COUNT - 1;
 * - the push-constant block has the table's members, named and in order,
 *   at the offsets of rt_vk_push (offsetof);
 * - every specialization constant is the table's: its constant_id, name
 *   (SC_<NAME>) and default;
 * - the work group size is RT_VK_LOCAL.
 * A buffer, push constant or specialization constant declared by hand in a
 * shader instead of through the table, or a table row the main shader lost,
 * fails here. Skipped without the Vulkan backend. */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"

#ifdef RT_HAVE_VULKAN
#include "rt_interface.h"
#include "vulkan/vk_backend.h"

enum {
    OP_NAME = 5,
    OP_MEMBER_NAME = 6,
    OP_EXECUTION_MODE = 16,
    OP_TYPE_POINTER = 32,
    OP_SPEC_CONSTANT = 50,
    OP_VARIABLE = 59,
    OP_DECORATE = 71,
    OP_MEMBER_DECORATE = 72,
    DEC_SPEC_ID = 1,
    DEC_BINDING = 33,
    DEC_DESCRIPTOR_SET = 34,
    DEC_OFFSET = 35,
    MODE_LOCAL_SIZE = 17,
    SC_UNIFORM = 2,
    SC_PUSH_CONSTANT = 9,
    SC_STORAGE_BUFFER = 12,
    MAX_MEMBERS = 64
};

/* What the test reads of a module, by result id (bound: the header's). */
typedef struct spv_id {
    const char *name;
    int binding, set, spec_id;
    uint32_t pointee; /* a pointer type's */
    int pointer_class;
    int is_var, var_class;
    uint32_t var_type;
    int is_spec;
    uint32_t spec_value;
} spv_id;

typedef struct spv_member {
    uint32_t type, index;
    const char *name;
    int offset;
} spv_member;

typedef struct spv_module {
    spv_id *id;
    uint32_t bound;
    spv_member member[4096];
    int members;
    int local_size;
} spv_module;

static spv_module mod;

/* The member record of (type, index), made on first use; NULL when full. */
static spv_member *member(uint32_t type, uint32_t index) {
    for (int i = 0; i < mod.members; i++)
        if (mod.member[i].type == type && mod.member[i].index == index) return &mod.member[i];
    if (mod.members == (int)(sizeof mod.member / sizeof mod.member[0])) return NULL;
    spv_member *m = &mod.member[mod.members++];
    m->type = type;
    m->index = index;
    m->name = NULL;
    m->offset = -1;
    return m;
}

static void read_module(const uint32_t *w, size_t bytes) {
    free(mod.id);
    memset(&mod, 0, sizeof mod);
    size_t n = bytes / 4;
    CHECK(n > 5 && w[0] == 0x07230203u);
    if (n <= 5) return;
    mod.bound = w[3];
    mod.id = calloc(mod.bound ? mod.bound : 1, sizeof *mod.id);
    for (uint32_t i = 0; i < mod.bound; i++)
        mod.id[i].binding = mod.id[i].set = mod.id[i].spec_id = -1;
    for (size_t i = 5; i < n;) {
        uint32_t op = w[i] & 0xffffu, len = w[i] >> 16;
        CHECK_MSG(len > 0 && i + len <= n, "malformed SPIR-V at word %zu", i);
        if (len == 0 || i + len > n) return;
        const uint32_t *a = w + i + 1; /* the operands */
        int ok = len >= 2 && a[0] < mod.bound;
        spv_id *d = ok ? &mod.id[a[0]] : NULL;
        spv_member *m;
        if (op == OP_NAME && ok) d->name = (const char *)(a + 1);
        if (op == OP_MEMBER_NAME && ok && len >= 4 && (m = member(a[0], a[1])))
            m->name = (const char *)(a + 2);
        if (op == OP_MEMBER_DECORATE && ok && len >= 5 && a[2] == DEC_OFFSET &&
            (m = member(a[0], a[1])))
            m->offset = (int)a[3];
        if (op == OP_DECORATE && ok && len >= 4) {
            if (a[1] == DEC_BINDING) d->binding = (int)a[2];
            if (a[1] == DEC_DESCRIPTOR_SET) d->set = (int)a[2];
            if (a[1] == DEC_SPEC_ID) d->spec_id = (int)a[2];
        }
        if (op == OP_TYPE_POINTER && ok && len >= 4) {
            d->pointer_class = (int)a[1];
            d->pointee = a[2];
        }
        if (op == OP_VARIABLE && len >= 4 && a[1] < mod.bound) {
            mod.id[a[1]].is_var = 1;
            mod.id[a[1]].var_type = a[0];
            mod.id[a[1]].var_class = (int)a[2];
        }
        if (op == OP_SPEC_CONSTANT && len >= 4 && a[1] < mod.bound) {
            mod.id[a[1]].is_spec = 1;
            mod.id[a[1]].spec_value = a[2];
        }
        if (op == OP_EXECUTION_MODE && len >= 4 && a[1] == MODE_LOCAL_SIZE)
            mod.local_size = (int)a[2];
        i += len;
    }
}

/* The table's buffers by binding: their block names. */
static const char *table_block[RT_VK_BUF_COUNT];

static void table_blocks(void) {
#include "rt_interface_rows.h"
#undef RT_VIEW_BUFFER
#undef RT_IO_BUFFER
#undef RT_VK_BUFFER
#define RT_VIEW_BUFFER(ID, name, type, form, binding, what) table_block[binding] = "B_" #name;
#define RT_IO_BUFFER(ID, name, type, access, binding, what) table_block[binding] = "B_" #name;
#define RT_VK_BUFFER(ID, name, type, binding, what)         table_block[binding] = "B_" #name;
#include "rt_interface.def"
#include "rt_interface_rows.h"
}

static void check_buffers(const char *module, int main_shader) {
    int seen[RT_VK_BUF_COUNT] = {0};
    for (uint32_t id = 0; id < mod.bound; id++) {
        const spv_id *v = &mod.id[id];
        if (!v->is_var || v->binding < 0) continue;
        int b = v->binding;
        CHECK_MSG(v->set == 0, "%s: binding %d is in set %d, the table's are in set 0", module, b,
                  v->set);
        CHECK_MSG(b < RT_VK_BUF_COUNT && table_block[b],
                  "%s: binding %d is not in kernels/rt_interface.def", module, b);
        if (b >= RT_VK_BUF_COUNT || !table_block[b]) continue;
        seen[b] = 1;
        uint32_t ptr = v->var_type;
        int cls = ptr < mod.bound ? mod.id[ptr].pointer_class : -1;
        CHECK_MSG(cls == SC_UNIFORM || cls == SC_STORAGE_BUFFER,
                  "%s: binding %d is not a storage buffer", module, b);
        uint32_t type = ptr < mod.bound ? mod.id[ptr].pointee : 0;
        const char *block = type < mod.bound ? mod.id[type].name : NULL;
        if (main_shader)
            CHECK_MSG(block && strcmp(block, table_block[b]) == 0,
                      "%s: binding %d holds block '%s', the table says '%s'", module, b,
                      block ? block : "(unnamed)", table_block[b]);
    }
    if (main_shader)
        for (int b = 0; b < RT_VK_BUF_COUNT; b++) {
            CHECK_MSG(table_block[b] != NULL, "the table's bindings skip %d (0 .. %d expected)", b,
                      RT_VK_BUF_COUNT - 1);
            CHECK_MSG(seen[b], "%s: no buffer at binding %d (%s)", module, b,
                      table_block[b] ? table_block[b] : "?");
        }
}

static void check_push(const char *module) {
    uint32_t block = 0;
    int vars = 0;
    for (uint32_t id = 0; id < mod.bound; id++)
        if (mod.id[id].is_var && mod.id[id].var_class == SC_PUSH_CONSTANT &&
            mod.id[id].var_type < mod.bound) {
            vars++;
            block = mod.id[mod.id[id].var_type].pointee;
        }
    CHECK_MSG(vars == 1, "%s: %d push-constant blocks, 1 expected", module, vars);
    if (vars != 1) return;
    uint32_t m = 0;
#include "rt_interface_rows.h"
#undef RT_PUSH
#define RT_PUSH(type, field)                                                                       \
    {                                                                                              \
        const spv_member *pm = member(block, m);                                                   \
        CHECK_MSG(pm && pm->name && strcmp(pm->name, #field) == 0,                                 \
                  "%s: push constant %u is '%s', the table says '%s'", module, m,                  \
                  pm && pm->name ? pm->name : "(none)", #field);                                   \
        CHECK_MSG(pm && pm->offset == (int)offsetof(rt_vk_push, field),                            \
                  "%s: push constant %s at offset %d, rt_vk_push has it at %zu", module, #field,   \
                  pm ? pm->offset : -1, offsetof(rt_vk_push, field));                              \
        m++;                                                                                       \
    }
#include "rt_interface.def"
#include "rt_interface_rows.h"
    const spv_member *extra = member(block, m);
    CHECK_MSG(extra && extra->name == NULL && extra->offset < 0,
              "%s: the push-constant block has more members than the table's %u", module, m);
}

static void check_spec(const char *module) {
    for (uint32_t id = 0; id < mod.bound; id++) {
        const spv_id *c = &mod.id[id];
        if (c->spec_id < 0) continue;
        const char *name = c->name ? c->name : "(unnamed)";
        int found = 0;
#include "rt_interface_rows.h"
#undef RT_SPEC
#define RT_SPEC(NAME, cid, value)                                                                  \
    if (c->spec_id == (cid)) {                                                                     \
        found = 1;                                                                                 \
        CHECK_MSG(strcmp(name, "SC_" #NAME) == 0, "%s: constant_id %d is %s, the table says %s",   \
                  module, (cid), name, "SC_" #NAME);                                               \
        CHECK_MSG(c->is_spec && c->spec_value == (uint32_t)(value),                                \
                  "%s: %s defaults to %u, the table says %u", module, name, c->spec_value,         \
                  (unsigned)(value));                                                              \
    }
#include "rt_interface.def"
#include "rt_interface_rows.h"
        CHECK_MSG(found, "%s: constant_id %d (%s) is not in the table", module, c->spec_id, name);
    }
}

/* The table's constant_ids are 0 .. RT_VK_SPEC_COUNT - 1, each once (the
 * backend's specialization map takes constant i from word i). */
static void check_spec_ids(void) {
    int seen[RT_VK_SPEC_COUNT] = {0};
#include "rt_interface_rows.h"
#undef RT_SPEC
#define RT_SPEC(NAME, cid, value)                                                                  \
    CHECK_MSG((cid) >= 0 && (cid) < RT_VK_SPEC_COUNT && !seen[(cid)]++,                            \
              "SC_" #NAME ": constant_id %d is not one of 0 .. %d, each once", (cid),              \
              RT_VK_SPEC_COUNT - 1);
#include "rt_interface.def"
#include "rt_interface_rows.h"
}

int main(void) {
    table_blocks();
    check_spec_ids();
    static const char *const modules[] = {"rt_vk_main", "rt_vk_soft_test", "rt_vk_interface_test"};
    for (size_t i = 0; i < sizeof modules / sizeof modules[0]; i++) {
        size_t bytes;
        const uint32_t *w = rt_vk_module(modules[i], &bytes);
        CHECK_MSG(w != NULL, "no embedded module %s", modules[i]);
        if (!w) continue;
        read_module(w, bytes);
        int main_shader = strcmp(modules[i], "rt_vk_main") == 0;
        check_buffers(modules[i], main_shader);
        check_push(modules[i]);
        check_spec(modules[i]);
        CHECK_MSG(mod.local_size == RT_VK_LOCAL, "%s: work groups of %d, the table says %d",
                  modules[i], mod.local_size, RT_VK_LOCAL);
    }
    free(mod.id);
    return TEST_END();
}
#else
int main(void) {
    test_skip("this build has no Vulkan backend (RT_VULKAN=OFF, or no loader or glslangValidator)");
}
#endif
