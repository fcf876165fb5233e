/* SPDX-License-Identifier: Apache-2.0 */
/* wide_bvh.c - the layout's binary BVHs collapsed into 4- or 8-wide nodes
 * (wide_bvh.h), for both CPU tracers.
 *
 * Each wide node takes a binary inner node's two children and opens the
 * child of largest surface area while it has fewer than 'width' children
 * and some child may be opened (the usual collapse, e.g. Wald et al. 2008's
 * multi-branching BVHs); opened inner nodes disappear and their children's
 * boxes move up into the wide node. A subtree whose entries are one run of
 * at most leaf_entries becomes one leaf; every other leaf is the layout's
 * leaf. With blocks, a mesh leaf's entries are copied into blocks of
 * 'width' triangles in the leaf's entry order. */
#include "wide_bvh.h"

#include <stdlib.h>
#include <string.h>

typedef struct builder {
    rt_wide_shape shape;
    uint32_t node_words, block_words;
    uint32_t *nodes, node_count, node_cap;
    uint32_t *src; /* per node: 'width' binary node indices */
    uint32_t *blocks, block_count, block_cap;
    const rt_flat *flat;
    const rt_node *bin;
    uint32_t *sub_first, *sub_count; /* per binary node: its entries when one run (else
                                        sub_count UINT32_MAX) */
    int top;                         /* building the object BVH (entries are instance ids) */
} builder;

typedef struct work {
    uint32_t bin;  /* a binary inner node ... */
    uint32_t wide; /* ... whose children fill this wide node */
} work;

static void put_f(uint32_t *words, size_t i, float x) {
    memcpy(&words[i], &x, sizeof x);
}

/* Grows an array of 'words'-word items, 64-byte aligned, to hold one more
 * (and, for nodes, their src entries). 0 when out of memory. */
static int grow(uint32_t **arr, uint32_t count, uint32_t *cap, uint32_t words, uint32_t **src,
                uint32_t src_words) {
    if (count < *cap) return 1;
    uint32_t c = *cap ? 2 * *cap : 64;
    size_t bytes = sizeof(uint32_t) * (size_t)words * c;
    bytes = (bytes + 63) / 64 * 64;
    uint32_t *n = aligned_alloc(64, bytes);
    if (!n) return 0;
    if (src) {
        uint32_t *s = realloc(*src, sizeof(uint32_t) * (size_t)src_words * c);
        if (!s) {
            free(n);
            return 0;
        }
        *src = s;
    }
    if (count) memcpy(n, *arr, sizeof(uint32_t) * (size_t)words * count);
    free(*arr);
    *arr = n;
    *cap = c;
    return 1;
}

/* A node with no children; UINT32_MAX when out of memory. */
static uint32_t new_node(builder *b) {
    const int w = b->shape.width;
    if (!grow(&b->nodes, b->node_count, &b->node_cap, b->node_words, &b->src, (uint32_t)w))
        return UINT32_MAX;
    uint32_t *n = b->nodes + (size_t)b->node_words * b->node_count;
    for (int c = 0; c < w; c++) {
        for (int k = 0; k < 3; k++) {
            put_f(n, (size_t)k * w + c, RT_INF);
            put_f(n, (size_t)(3 + k) * w + c, -RT_INF);
        }
        n[6 * w + c] = RT_WIDE_EMPTY;
        n[7 * w + c] = 0;
        b->src[(size_t)w * b->node_count + c] = RT_WIDE_EMPTY;
    }
    return b->node_count++;
}

/* Lane l of block blk: the layout's triangle e. */
static void put_tri(const builder *b, uint32_t *blk, int l, uint32_t e) {
    const int w = b->shape.width;
    const rt_tri *t = &b->flat->tris[e];
    for (int k = 0; k < 3; k++) {
        put_f(blk, (size_t)k * w + l, t->v0[k]);
        put_f(blk, (size_t)(3 + k) * w + l, t->v1[k]);
        put_f(blk, (size_t)(6 + k) * w + l, t->v2[k]);
    }
}

/* The entries first .. first + count - 1 as blocks; returns the first block,
 * UINT32_MAX when out of memory. */
static uint32_t add_blocks(builder *b, uint32_t first, uint32_t count) {
    const uint32_t w = (uint32_t)b->shape.width, start = b->block_count;
    for (uint32_t at = 0; at < count; at += w) {
        if (!grow(&b->blocks, b->block_count, &b->block_cap, b->block_words, NULL, 0))
            return UINT32_MAX;
        uint32_t *blk = b->blocks + (size_t)b->block_words * b->block_count++;
        for (uint32_t l = 0; l < w; l++) {
            const int real = at + l < count;
            const uint32_t e = first + (real ? at + l : count - 1);
            put_tri(b, blk, (int)l, e);
            blk[9 * w + l] = real ? e : RT_WIDE_EMPTY;
        }
    }
    return start;
}

static float half_area(const rt_node *n) {
    float d[3];
    for (int k = 0; k < 3; k++) d[k] = n->bmax[k] - n->bmin[k];
    return d[0] * d[1] + d[1] * d[2] + d[2] * d[0];
}

/* Whether binary inner node x becomes one leaf of the wide tree. */
static int merges(const builder *b, uint32_t x) {
    return (!b->top || b->shape.merge_top) && b->sub_count[x] <= b->shape.leaf_entries;
}

/* Fills slot c of wide node w with binary node x: a leaf (or a subtree that
 * merges) becomes a leaf, an inner node a wide node of its own, queued on
 * the work stack. 0 when out of memory. */
static int set_child(builder *b, uint32_t w, int c, uint32_t x, work *stack, uint32_t *sp) {
    const rt_node *src = &b->bin[x];
    const int is_leaf = (src->b & RT_NODE_LEAF_FLAG) != 0;
    uint32_t ref, info;
    if (!is_leaf && !merges(b, x)) {
        ref = new_node(b);
        if (ref == UINT32_MAX) return 0;
        info = 0;
        stack[(*sp)++] = (work){x, ref};
    } else if (b->top || !b->shape.blocks) {
        ref = is_leaf ? src->a : b->sub_first[x];
        info = is_leaf ? src->b : b->sub_count[x] | RT_NODE_LEAF_FLAG;
    } else {
        const uint32_t first = is_leaf ? src->a : b->sub_first[x];
        const uint32_t count = is_leaf ? src->b & RT_NODE_COUNT_MASK : b->sub_count[x];
        const uint32_t width = (uint32_t)b->shape.width;
        ref = add_blocks(b, first, count);
        if (ref == UINT32_MAX) return 0;
        info = ((count + width - 1) / width) | RT_NODE_LEAF_FLAG;
    }
    const int wd = b->shape.width;
    uint32_t *n = b->nodes + (size_t)b->node_words * w;
    for (int k = 0; k < 3; k++) {
        put_f(n, (size_t)k * wd + c, src->bmin[k]);
        put_f(n, (size_t)(3 + k) * wd + c, src->bmax[k]);
    }
    n[6 * wd + c] = ref;
    n[7 * wd + c] = info;
    b->src[(size_t)wd * w + c] = x;
    return 1;
}

/* sub_first and sub_count of every binary node below 'root' (UINT32_MAX
 * count where its entries are not one run): a pre-order list, then children
 * before parents. list and stack have room for the tree's nodes. */
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
 * node, UINT32_MAX when out of memory. stack has room for the tree's wide
 * nodes. */
static uint32_t build_tree(builder *b, uint32_t root, work *stack) {
    uint32_t sp = 0, entry = new_node(b);
    if (entry == UINT32_MAX || !set_child(b, entry, 0, root, stack, &sp)) return UINT32_MAX;
    while (sp > 0) {
        const work wk = stack[--sp];
        uint32_t kids[RT_WIDE_MAX] = {b->bin[wk.bin].a, b->bin[wk.bin].b};
        int n = 2;
        while (n < b->shape.width) {
            int open = -1;
            float best = -1.0f;
            for (int i = 0; i < n; i++) {
                const rt_node *x = &b->bin[kids[i]];
                if (x->b & RT_NODE_LEAF_FLAG) continue;
                if (b->shape.keep_leaf_subtrees && merges(b, kids[i])) continue;
                const float a = half_area(x);
                if (open < 0 || a > best) open = i, best = a;
            }
            if (open < 0) break;
            /* Replace the opened node by its two children, in order. */
            const uint32_t x = kids[open];
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

/* The scratch arrays of a build over flat's nodes; 0 when out of memory. */
typedef struct scratch {
    work *stack;
    uint32_t *list, *order;
} scratch;

static int scratch_alloc(builder *b, scratch *s) {
    const size_t n = b->flat->node_count ? b->flat->node_count : 1;
    b->sub_first = malloc(sizeof(uint32_t) * n);
    b->sub_count = malloc(sizeof(uint32_t) * n);
    /* Each wide node absorbs at least one binary inner node, so the work
     * stack never holds more entries than the layout has nodes. */
    s->stack = malloc(sizeof(work) * n);
    s->list = malloc(sizeof(uint32_t) * n);
    s->order = malloc(sizeof(uint32_t) * n);
    return b->sub_first && b->sub_count && s->stack && s->list && s->order;
}

static void scratch_free(builder *b, scratch *s) {
    free(b->sub_first);
    free(b->sub_count);
    free(s->stack);
    free(s->list);
    free(s->order);
}

static void builder_init(builder *b, const rt_flat *flat, const rt_wide_shape *shape) {
    memset(b, 0, sizeof *b);
    b->shape = *shape;
    b->node_words = RT_WIDE_NODE_WORDS(shape->width);
    b->block_words = RT_WIDE_BLOCK_WORDS(shape->width);
    b->flat = flat;
    b->bin = flat->nodes;
}

rt_status rt_wide_build(const rt_flat *flat, rt_wide_shape shape, rt_wide_bvh *out) {
    memset(out, 0, sizeof *out);
    out->top = RT_WIDE_EMPTY;
    if ((shape.width != 4 && shape.width != 8) || shape.leaf_entries == 0)
        return RT_ERROR_INVALID_ARGUMENT;
    const uint32_t insts = flat->hdr.instance_count;
    builder b;
    builder_init(&b, flat, &shape);
    scratch s;
    const int have_scratch = scratch_alloc(&b, &s);
    const size_t n = flat->node_count ? flat->node_count : 1;
    uint32_t *entry_of = malloc(sizeof(uint32_t) * n);
    out->inst_root = malloc(sizeof(uint32_t) * (insts ? insts : 1));
    int ok = 0;
    if (!have_scratch || !entry_of || !out->inst_root) goto done;
    for (uint32_t i = 0; i < flat->node_count; i++) entry_of[i] = RT_WIDE_EMPTY;
    for (uint32_t i = 0; i <= insts; i++) {
        const int top = i == insts; /* the object BVH last */
        if (top && (!insts || (flat->hdr.flags & RT_SCENE_SINGLE))) break;
        const uint32_t root = top ? flat->hdr.top_root : flat->instances[i].root;
        b.top = top;
        if (top) out->top_first = b.node_count;
        if (entry_of[root] == RT_WIDE_EMPTY) {
            subtree_ranges(&b, root, s.list, s.order);
            entry_of[root] = build_tree(&b, root, s.stack);
        }
        if (entry_of[root] == UINT32_MAX) goto done;
        if (top)
            out->top = entry_of[root];
        else
            out->inst_root[i] = entry_of[root];
    }
    if (out->top == RT_WIDE_EMPTY) out->top_first = b.node_count;
    ok = 1;
done:
    scratch_free(&b, &s);
    free(entry_of);
    if (!ok) {
        free(b.nodes);
        free(b.src);
        free(b.blocks);
        free(out->inst_root);
        memset(out, 0, sizeof *out);
        return RT_ERROR_OUT_OF_MEMORY;
    }
    out->shape = shape;
    out->inst_count = insts;
    out->nodes = b.nodes;
    out->node_count = b.node_count;
    out->src = b.src;
    out->blocks = b.blocks;
    out->block_count = b.block_count;
    return RT_OK;
}

rt_status rt_wide_refit(const rt_flat *flat, rt_wide_bvh *w) {
    const int wd = w->shape.width;
    const uint32_t node_words = RT_WIDE_NODE_WORDS(wd), block_words = RT_WIDE_BLOCK_WORDS(wd);
    /* The mesh trees: every child slot's box from its binary node. */
    for (uint32_t i = 0; i < w->top_first; i++) {
        uint32_t *n = w->nodes + (size_t)node_words * i;
        for (int c = 0; c < wd; c++) {
            const uint32_t x = w->src[(size_t)wd * i + c];
            if (x == RT_WIDE_EMPTY) continue;
            for (int k = 0; k < 3; k++) {
                put_f(n, (size_t)k * wd + c, flat->nodes[x].bmin[k]);
                put_f(n, (size_t)(3 + k) * wd + c, flat->nodes[x].bmax[k]);
            }
        }
    }
    builder b;
    builder_init(&b, flat, &w->shape);
    /* The blocks: each lane's triangle again (an empty lane repeats the
     * block's last real lane, as add_blocks wrote it). */
    for (uint32_t j = 0; j < w->block_count; j++) {
        uint32_t *blk = w->blocks + (size_t)block_words * j;
        uint32_t e = blk[9 * wd];
        for (int l = 0; l < wd; l++) {
            if (blk[9 * wd + l] != RT_WIDE_EMPTY) e = blk[9 * wd + l];
            put_tri(&b, blk, l, e);
        }
    }
    if (w->top == RT_WIDE_EMPTY) return RT_OK;
    /* The object BVH, built anew after the mesh trees. */
    b.nodes = w->nodes;
    b.src = w->src;
    b.node_count = w->top_first;
    b.node_cap = w->node_count;
    b.top = 1;
    scratch s;
    uint32_t top = UINT32_MAX;
    if (scratch_alloc(&b, &s)) {
        subtree_ranges(&b, flat->hdr.top_root, s.list, s.order);
        top = build_tree(&b, flat->hdr.top_root, s.stack);
    }
    scratch_free(&b, &s);
    /* build_tree may have grown the arrays. */
    w->nodes = b.nodes;
    w->src = b.src;
    w->node_count = b.node_count;
    if (top == UINT32_MAX) return RT_ERROR_OUT_OF_MEMORY;
    w->top = top;
    return RT_OK;
}

void rt_wide_free(rt_wide_bvh *wide) {
    if (!wide) return;
    free(wide->nodes);
    free(wide->src);
    free(wide->blocks);
    free(wide->inst_root);
    memset(wide, 0, sizeof *wide);
}
