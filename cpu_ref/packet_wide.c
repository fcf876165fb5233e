/* packet_wide.c - the layout's binary BVHs collapsed into four-wide nodes
 * (packet_wide.h).
 *
 * Each wide node takes a binary inner node's two children and opens the
 * child of largest surface area while it has fewer than four children and
 * some child is an inner node (the usual collapse, e.g. Wald et al. 2008's
 * multi-branching BVHs); opened inner nodes disappear, their children's
 * boxes move up into the wide node, and every leaf stays the layout's leaf. */
#include "packet_wide.h"

#include <stdlib.h>
#include <string.h>

typedef struct builder {
    rt_pk_node *nodes;
    uint32_t *src; /* per node: RT_PK_WIDTH binary node indices */
    uint32_t count, cap;
    const rt_node *bin;  /* the layout's binary nodes */
    uint32_t *sub_first; /* per binary node: the first entry below it ... */
    uint32_t *sub_count; /* ... and how many, when they are contiguous (else 0) */
} builder;

/* Subtrees of at most this many triangles become one leaf: a packet tests a
 * few triangles at the cost of a box, and every box test saved is a node
 * load saved. */
enum { LEAF_MERGE = RT_PK_LEAF_MERGE };

/* A new node with no children; UINT32_MAX when out of memory. */
static uint32_t new_node(builder *b) {
    if (b->count == b->cap) {
        /* Aligned to cache lines: a node is then exactly two of them. */
        uint32_t cap = b->cap ? 2 * b->cap : 64;
        rt_pk_node *n = aligned_alloc(64, sizeof(rt_pk_node) * cap);
        uint32_t *src = realloc(b->src, sizeof(uint32_t) * RT_PK_WIDTH * cap);
        if (!n || !src) {
            free(n);
            if (src) b->src = src;
            return UINT32_MAX;
        }
        b->src = src;
        if (b->count) memcpy(n, b->nodes, sizeof(rt_pk_node) * b->count);
        free(b->nodes);
        b->nodes = n;
        b->cap = cap;
    }
    for (int c = 0; c < RT_PK_WIDTH; c++) b->src[RT_PK_WIDTH * b->count + c] = RT_PK_NO_CHILD;
    rt_pk_node *n = &b->nodes[b->count];
    for (int c = 0; c < RT_PK_WIDTH; c++) {
        for (int k = 0; k < 3; k++) {
            n->bmin[k][c] = RT_INF;
            n->bmax[k][c] = -RT_INF;
        }
        n->ref[c] = RT_PK_NO_CHILD;
        n->count[c] = 0;
    }
    return b->count++;
}

static float half_area(const rt_node *n) {
    float d[3];
    for (int k = 0; k < 3; k++) d[k] = n->bmax[k] - n->bmin[k];
    return d[0] * d[1] + d[1] * d[2] + d[2] * d[0];
}

typedef struct work {
    uint32_t bin;  /* a binary inner node ... */
    uint32_t wide; /* ... whose children fill this wide node */
} work;

/* Fills wide node w's slot c with binary node x: a leaf is copied, an inner
 * node gets a wide node of its own, queued on the work stack. */
static int set_child(builder *b, uint32_t w, int c, uint32_t x, work *stack, uint32_t *sp) {
    const rt_node *src = &b->bin[x];
    uint32_t ref = src->a, count = src->b;
    if (!(src->b & RT_NODE_LEAF_FLAG) && b->sub_count[x] <= LEAF_MERGE) {
        ref = b->sub_first[x];
        count = b->sub_count[x] | RT_NODE_LEAF_FLAG;
    } else if (!(src->b & RT_NODE_LEAF_FLAG)) {
        ref = new_node(b);
        if (ref == UINT32_MAX) return 0;
        count = 0;
        stack[(*sp)++] = (work){x, ref};
    }
    rt_pk_node *n = &b->nodes[w];
    for (int k = 0; k < 3; k++) {
        n->bmin[k][c] = src->bmin[k];
        n->bmax[k][c] = src->bmax[k];
    }
    n->ref[c] = ref;
    n->count[c] = count;
    b->src[RT_PK_WIDTH * w + c] = x;
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
        work w = stack[--sp];
        uint32_t kids[RT_PK_WIDTH] = {b->bin[w.bin].a, b->bin[w.bin].b};
        int n = 2;
        while (n < RT_PK_WIDTH) {
            int open = -1;
            float best = -1.0f;
            for (int i = 0; i < n; i++) {
                const rt_node *x = &b->bin[kids[i]];
                if (x->b & RT_NODE_LEAF_FLAG) continue;
                float a = half_area(x);
                if (open < 0 || a > best) open = i, best = a;
            }
            if (open < 0) break;
            /* Replace the opened node by its two children, in order. */
            uint32_t x = kids[open];
            for (int i = n; i > open + 1; i--) kids[i] = kids[i - 1];
            kids[open] = b->bin[x].a;
            kids[open + 1] = b->bin[x].b;
            n++;
        }
        for (int i = 0; i < n; i++)
            if (!set_child(b, w.wide, i, kids[i], stack, &sp)) return UINT32_MAX;
    }
    return entry;
}

rt_status rt_pk_wide_build(const rt_flat *flat, rt_pk_wide *out) {
    memset(out, 0, sizeof *out);
    out->top = RT_PK_NO_CHILD;
    const size_t n = flat->node_count ? flat->node_count : 1;
    int ok = 0;
    uint32_t insts = flat->hdr.instance_count;
    builder b = {
        NULL, NULL, 0, 0, flat->nodes, malloc(sizeof(uint32_t) * n), malloc(sizeof(uint32_t) * n)};
    /* Each wide node absorbs at least one binary inner node, so the work
     * stack never holds more entries than the layout has nodes. */
    work *stack = malloc(sizeof(work) * n);
    uint32_t *entry_of = malloc(sizeof(uint32_t) * n), *list = malloc(sizeof(uint32_t) * n);
    uint32_t *order = malloc(sizeof(uint32_t) * n);
    out->inst_root = malloc(sizeof(uint32_t) * (insts ? insts : 1));
    if (!b.sub_first || !b.sub_count || !stack || !entry_of || !list || !order || !out->inst_root)
        goto oom;
    for (uint32_t i = 0; i < flat->node_count; i++) entry_of[i] = RT_PK_NO_CHILD;
    for (uint32_t i = 0; i <= insts; i++) {
        int top = i == insts; /* the object BVH last */
        if (top && (!insts || (flat->hdr.flags & RT_SCENE_SINGLE))) break;
        uint32_t root = top ? flat->hdr.top_root : flat->instances[i].root;
        if (top) out->top_first = b.count;
        if (entry_of[root] == RT_PK_NO_CHILD) {
            subtree_ranges(&b, root, list, order);
            entry_of[root] = build_tree(&b, root, stack);
        }
        if (entry_of[root] == UINT32_MAX) goto oom;
        if (top)
            out->top = entry_of[root];
        else
            out->inst_root[i] = entry_of[root];
    }
    if (out->top == RT_PK_NO_CHILD) out->top_first = b.count;
    out->inst_count = insts;
    out->nodes = b.nodes;
    out->src = b.src;
    out->node_count = b.count;
    b.nodes = NULL;
    b.src = NULL;
    ok = 1;
oom:
    free(b.sub_first);
    free(b.sub_count);
    free(stack);
    free(entry_of);
    free(list);
    free(order);
    if (ok) return RT_OK;
    free(b.nodes);
    free(b.src);
    free(out->inst_root);
    memset(out, 0, sizeof *out);
    return RT_ERROR_OUT_OF_MEMORY;
}

rt_status rt_pk_wide_refit(const rt_flat *flat, rt_pk_wide *w) {
    /* The mesh trees: every child slot's box from its binary node. */
    for (uint32_t i = 0; i < w->top_first; i++)
        for (int c = 0; c < RT_PK_WIDTH; c++) {
            uint32_t x = w->src[RT_PK_WIDTH * i + c];
            if (x == RT_PK_NO_CHILD) continue;
            for (int k = 0; k < 3; k++) {
                w->nodes[i].bmin[k][c] = flat->nodes[x].bmin[k];
                w->nodes[i].bmax[k][c] = flat->nodes[x].bmax[k];
            }
        }
    if (w->top == RT_PK_NO_CHILD) return RT_OK;
    /* The object BVH, built anew after the mesh trees. */
    const size_t n = flat->node_count ? flat->node_count : 1;
    builder b = {w->nodes,
                 w->src,
                 w->top_first,
                 w->node_count,
                 flat->nodes,
                 malloc(sizeof(uint32_t) * n),
                 malloc(sizeof(uint32_t) * n)};
    work *stack = malloc(sizeof(work) * n);
    uint32_t *list = malloc(sizeof(uint32_t) * n), *order = malloc(sizeof(uint32_t) * n);
    uint32_t top = UINT32_MAX;
    if (b.sub_first && b.sub_count && stack && list && order) {
        subtree_ranges(&b, flat->hdr.top_root, list, order);
        top = build_tree(&b, flat->hdr.top_root, stack);
    }
    /* build_tree may have grown the arrays. */
    w->nodes = b.nodes;
    w->src = b.src;
    w->node_count = b.count;
    free(b.sub_first);
    free(b.sub_count);
    free(stack);
    free(list);
    free(order);
    if (top == UINT32_MAX) return RT_ERROR_OUT_OF_MEMORY;
    w->top = top;
    return RT_OK;
}

void rt_pk_wide_free(rt_pk_wide *wide) {
    if (!wide) return;
    free(wide->nodes);
    free(wide->src);
    free(wide->inst_root);
    memset(wide, 0, sizeof *wide);
}
