/* single_wide.c - the layout's binary BVHs collapsed into 4- or 8-wide
 * nodes with triangle blocks (single_wide.h).
 *
 * Each wide node takes a binary inner node's two children and opens the
 * child of largest surface area while it has fewer than W children and some
 * child is an inner node (the usual collapse, as cpu_ref/packet_wide.c does
 * for packets); opened inner nodes disappear and their children's boxes move
 * up. A subtree whose entries are one run of at most RT_SW_LEAF_MERGE * W
 * triangles becomes one leaf, and every leaf's entries are copied into
 * blocks of W triangles in the leaf's entry order. */
#include "single_wide.h"

#include <stdlib.h>
#include <string.h>

typedef struct builder {
    int w;
    uint32_t *nodes, node_count, node_cap;
    uint32_t *blocks, block_count, block_cap;
    const rt_flat *flat;
    const rt_node *bin;
    uint32_t *sub_first, *sub_count; /* per binary node: its entries when one run (else
                                        sub_count UINT32_MAX) */
    int top;                         /* building the object BVH (leaves are instance ids) */
} builder;

typedef struct work {
    uint32_t bin, wide;
} work;

static void put_f(uint32_t *words, size_t i, float x) {
    memcpy(&words[i], &x, sizeof x);
}

/* Grows an array of 'words'-word items, 64-byte aligned, to hold one more. */
static int grow(uint32_t **arr, uint32_t count, uint32_t *cap, uint32_t words) {
    if (count < *cap) return 1;
    uint32_t c = *cap ? 2 * *cap : 64;
    size_t bytes = sizeof(uint32_t) * (size_t)words * c;
    bytes = (bytes + 63) / 64 * 64;
    uint32_t *n = aligned_alloc(64, bytes);
    if (!n) return 0;
    if (count) memcpy(n, *arr, sizeof(uint32_t) * (size_t)words * count);
    free(*arr);
    *arr = n;
    *cap = c;
    return 1;
}

/* A node with no children; UINT32_MAX when out of memory. */
static uint32_t new_node(builder *b) {
    const uint32_t words = rt_sw_node_words(b->w);
    if (!grow(&b->nodes, b->node_count, &b->node_cap, words)) return UINT32_MAX;
    uint32_t *n = b->nodes + (size_t)words * b->node_count;
    for (int c = 0; c < b->w; c++) {
        for (int k = 0; k < 3; k++) {
            put_f(n, (size_t)k * b->w + c, RT_INF);
            put_f(n, (size_t)(3 + k) * b->w + c, -RT_INF);
        }
        n[6 * b->w + c] = RT_SW_EMPTY;
        n[7 * b->w + c] = 0;
    }
    return b->node_count++;
}

/* The entries first .. first + count - 1 as blocks; returns the first block,
 * UINT32_MAX when out of memory. */
static uint32_t add_blocks(builder *b, uint32_t first, uint32_t count) {
    const uint32_t words = rt_sw_block_words(b->w), start = b->block_count;
    for (uint32_t at = 0; at < count; at += (uint32_t)b->w) {
        if (!grow(&b->blocks, b->block_count, &b->block_cap, words)) return UINT32_MAX;
        uint32_t *blk = b->blocks + (size_t)words * b->block_count++;
        for (int l = 0; l < b->w; l++) {
            const int real = at + (uint32_t)l < count;
            const uint32_t e = first + (real ? at + (uint32_t)l : count - 1);
            const rt_tri *t = &b->flat->tris[e];
            for (int k = 0; k < 3; k++) {
                put_f(blk, (size_t)k * b->w + l, t->v0[k]);
                put_f(blk, (size_t)(3 + k) * b->w + l, t->v1[k]);
                put_f(blk, (size_t)(6 + k) * b->w + l, t->v2[k]);
            }
            blk[9 * b->w + l] = real ? e : RT_SW_EMPTY;
        }
    }
    return start;
}

static float half_area(const rt_node *n) {
    float d[3];
    for (int k = 0; k < 3; k++) d[k] = n->bmax[k] - n->bmin[k];
    return d[0] * d[1] + d[1] * d[2] + d[2] * d[0];
}

/* Fills slot c of wide node w with binary node x: a leaf (or a small
 * subtree) becomes a leaf, an inner node a wide node of its own, queued. */
static int set_child(builder *b, uint32_t w, int c, uint32_t x, work *stack, uint32_t *sp) {
    const rt_node *src = &b->bin[x];
    const int is_leaf = (src->b & RT_NODE_LEAF_FLAG) != 0;
    uint32_t ref, info;
    if (b->top && is_leaf) {
        ref = src->a;
        info = src->b;
    } else if (!b->top && (is_leaf || b->sub_count[x] <= (uint32_t)(RT_SW_LEAF_MERGE * b->w))) {
        const uint32_t first = is_leaf ? src->a : b->sub_first[x];
        const uint32_t count = is_leaf ? src->b & RT_NODE_COUNT_MASK : b->sub_count[x];
        ref = add_blocks(b, first, count);
        if (ref == UINT32_MAX) return 0;
        info = ((count + (uint32_t)b->w - 1) / (uint32_t)b->w) | RT_NODE_LEAF_FLAG;
    } else {
        ref = new_node(b);
        if (ref == UINT32_MAX) return 0;
        info = 0;
        stack[(*sp)++] = (work){x, ref};
    }
    uint32_t *n = b->nodes + (size_t)rt_sw_node_words(b->w) * w;
    for (int k = 0; k < 3; k++) {
        put_f(n, (size_t)k * b->w + c, src->bmin[k]);
        put_f(n, (size_t)(3 + k) * b->w + c, src->bmax[k]);
    }
    n[6 * b->w + c] = ref;
    n[7 * b->w + c] = info;
    return 1;
}

/* sub_first and sub_count of every binary node below root: a pre-order
 * list, then children before parents. list and stack hold the tree. */
static void subtree_ranges(builder *b, uint32_t root, uint32_t *list, uint32_t *stack) {
    uint32_t n = 0, sp = 0;
    stack[sp++] = root;
    while (sp > 0) {
        uint32_t x = stack[--sp];
        list[n++] = x;
        if (!(b->bin[x].b & RT_NODE_LEAF_FLAG)) {
            stack[sp++] = b->bin[x].a;
            stack[sp++] = b->bin[x].b;
        }
    }
    while (n > 0) {
        const uint32_t x = list[--n];
        const rt_node *nd = &b->bin[x];
        if (nd->b & RT_NODE_LEAF_FLAG) {
            b->sub_first[x] = nd->a;
            b->sub_count[x] = nd->b & RT_NODE_COUNT_MASK;
            continue;
        }
        uint32_t fl = b->sub_first[nd->a], cl = b->sub_count[nd->a];
        uint32_t fr = b->sub_first[nd->b], cr = b->sub_count[nd->b];
        b->sub_count[x] = UINT32_MAX;
        if (cl == UINT32_MAX || cr == UINT32_MAX) continue;
        if (cl == 0 || cr == 0 || fl + cl == fr) {
            b->sub_first[x] = cl ? fl : fr;
            b->sub_count[x] = cl + cr;
        }
    }
}

/* The tree below binary root 'root' behind an entry node: returns the entry
 * node, UINT32_MAX when out of memory. */
static uint32_t build_tree(builder *b, uint32_t root, work *stack) {
    uint32_t sp = 0, entry = new_node(b);
    if (entry == UINT32_MAX || !set_child(b, entry, 0, root, stack, &sp)) return UINT32_MAX;
    while (sp > 0) {
        work wk = stack[--sp];
        uint32_t kids[8] = {b->bin[wk.bin].a, b->bin[wk.bin].b};
        int n = 2;
        while (n < b->w) {
            int open = -1;
            float best = -1.0f;
            for (int i = 0; i < n; i++) {
                const rt_node *x = &b->bin[kids[i]];
                if (x->b & RT_NODE_LEAF_FLAG) continue;
                if (!b->top && b->sub_count[kids[i]] <= (uint32_t)(RT_SW_LEAF_MERGE * b->w))
                    continue; /* becomes a leaf whole */
                float a = half_area(x);
                if (open < 0 || a > best) open = i, best = a;
            }
            if (open < 0) break;
            uint32_t x = kids[open];
            for (int i = n; i > open + 1; i--) kids[i] = kids[i - 1];
            kids[open] = b->bin[x].a;
            kids[open + 1] = b->bin[x].b;
            n++;
        }
        for (int i = 0; i < n; i++)
            if (!set_child(b, wk.wide, i, kids[i], stack, &sp)) return UINT32_MAX;
    }
    return entry;
}

rt_status rt_sw_build(const rt_flat *flat, int width, rt_sw_bvh *out) {
    memset(out, 0, sizeof *out);
    out->top = RT_SW_EMPTY;
    if (width != 4 && width != 8) return RT_ERROR_INVALID_ARGUMENT;
    const size_t n = flat->node_count ? flat->node_count : 1;
    const uint32_t insts = flat->hdr.instance_count;
    builder b;
    memset(&b, 0, sizeof b);
    b.w = width;
    b.flat = flat;
    b.bin = flat->nodes;
    b.sub_first = malloc(sizeof(uint32_t) * n);
    b.sub_count = malloc(sizeof(uint32_t) * n);
    /* Each wide node absorbs at least one binary inner node. */
    work *stack = malloc(sizeof(work) * n);
    uint32_t *entry_of = malloc(sizeof(uint32_t) * n), *list = malloc(sizeof(uint32_t) * n);
    uint32_t *order = malloc(sizeof(uint32_t) * n);
    out->inst_root = malloc(sizeof(uint32_t) * (insts ? insts : 1));
    int ok = 0;
    if (!b.sub_first || !b.sub_count || !stack || !entry_of || !list || !order || !out->inst_root)
        goto done;
    for (uint32_t i = 0; i < flat->node_count; i++) entry_of[i] = RT_SW_EMPTY;
    for (uint32_t i = 0; i <= insts; i++) {
        const int top = i == insts; /* the object BVH last */
        if (top && (!insts || (flat->hdr.flags & RT_SCENE_SINGLE))) break;
        const uint32_t root = top ? flat->hdr.top_root : flat->instances[i].root;
        b.top = top;
        if (entry_of[root] == RT_SW_EMPTY) {
            subtree_ranges(&b, root, list, order);
            entry_of[root] = build_tree(&b, root, stack);
        }
        if (entry_of[root] == UINT32_MAX) goto done;
        if (top)
            out->top = entry_of[root];
        else
            out->inst_root[i] = entry_of[root];
    }
    ok = 1;
done:
    free(b.sub_first);
    free(b.sub_count);
    free(stack);
    free(entry_of);
    free(list);
    free(order);
    if (!ok) {
        free(b.nodes);
        free(b.blocks);
        free(out->inst_root);
        memset(out, 0, sizeof *out);
        return RT_ERROR_OUT_OF_MEMORY;
    }
    out->width = width;
    out->inst_count = insts;
    out->nodes = b.nodes;
    out->node_count = b.node_count;
    out->blocks = b.blocks;
    out->block_count = b.block_count;
    return RT_OK;
}

void rt_sw_free(rt_sw_bvh *bvh) {
    if (!bvh) return;
    free(bvh->nodes);
    free(bvh->blocks);
    free(bvh->inst_root);
    memset(bvh, 0, sizeof *bvh);
}
