/* SPDX-License-Identifier: Apache-2.0 */
/* rt_vk_resume.glsl - state that outlives the driver's loop budget: an item
 * that would need more loop iterations than llvmpipe and lavapipe run in one
 * shader invocation (65535 for all loops together, rt_vk_main.comp) saves
 * its whole state to its slot of the state buffer before it could reach the
 * budget, and a further dispatch loads it and goes on, as often as needed.
 *
 * The count: rt_vk_ticks (rt_vk_ticks.glsl), every loop iteration the
 * invocation ran, plus RT_VK_UNIT per checkpoint for the last test of each
 * loop (which the driver counts, the increment does not). The checkpoints
 * (rt_vk_checkpoint) come before each unit of work: a triangle of a leaf, a
 * node of a mesh's BVH or kd-tree, a node or an instance of the object BVH,
 * a step of rt_vk_main.comp's shading loop, a light of its scan for the
 * next shadow ray. A unit runs a bounded number of loop iterations (a
 * triangle test and its acceptance: its fixed loops and at most three soft
 * divisions of 25; a kd step: its pop loop, at most RT_KD_STACK; an
 * instance: its ray's six divisions; a shading step: rt_shade_begin or
 * rt_shade_end, one light's Phong terms, whose specular power loop runs the
 * material's shininess; a light: its direction and shadow ray), a few
 * hundred, far below the margin. One has no bound of its own: a shininess
 * beyond about 30,000 would outrun the margin, and the canary would report
 * the item, as before.
 *
 * The limit, RT_VK_TICK_LIMIT = 32768, half the budget: an item suspends
 * at the first checkpoint past it, so the driver has counted at most
 * 32768 + one unit + the saving (the stacks: at most 12 shading entries, 64
 * object-BVH entries and 64 kd cells) when it stops, well under 65535.
 * That holds because suspending is allowed only to an item alone in its
 * work group (pc.stride = RT_VK_LOCAL, one invocation per work group and so
 * per SIMD group): the budget is shared by the invocations of a SIMD group,
 * and the other invocations of the group return before any loop, so every
 * iteration the driver counts is this item's own. In the first dispatch of a
 * tile (pc.stride = 1) items share it and never suspend: one the shared
 * budget cut is marked by the canary and traced again alone (vk_backend.c).
 * A cut the count did not foresee is still the canary's (items[i] = 1),
 * never a wrong result.
 *
 * Progress: a resumed item runs at least the unit it stopped before (the
 * first checkpoint it meets after loading never suspends: rt_vk_worked),
 * so every dispatch moves it on, and a ray that needs many iterations costs
 * dispatches, not an error.
 *
 * Exactness: the state is stored as bits (floatBitsToUint), and a resumed
 * item recomputes only what the same operations give again (a ray's
 * prepared values, its object-space copy): the arithmetic and its order are
 * those of an item that never stopped, so the hits, images and counters are
 * the oracle's.
 *
 * The slot of an item: RT_VK_STATE_WORDS words at rt_vk_slot, regions
 * ST_MAIN (rt_vk_main.comp's shading state), ST_TOP (rt_trace: the best
 * hit, the object BVH's position and stack), ST_MESH (a mesh's BVH or kd
 * position and stack) and ST_LEAF (the next triangle of a leaf). Each level
 * saves its own region as the suspension unwinds (innermost first) and
 * loads it as the resumed item walks back down (outermost first);
 * rt_vk_resuming is true until the level that stopped has loaded its
 * position. */
/* Included by rt_vk_hit.glsl after the hit and counter structs. */
#ifndef RT_VK_RESUME_GLSL
#define RT_VK_RESUME_GLSL

#define RT_STACK_SIZE 64

/* ---- traversal stacks ------------------------------------------------------
 * In workgroup-shared memory, not in per-invocation arrays: a driver keeps a
 * private array indexed at run time in scratch memory or as a chain of
 * selects (lavapipe traced 100 times slower so). Entry k of invocation l is
 * at k * RT_VK_LOCAL + l (consecutive invocations in consecutive words;
 * RT_VK_LOCAL, the work group size, is kernels/rt_interface.def's). The
 * object BVH's stack is entries 0 .. RT_STACK_SIZE - 1, a mesh BVH's the
 * next RT_STACK_SIZE. */
shared uint rt_vk_stack[2 * RT_STACK_SIZE * RT_VK_LOCAL];
#define STACK_AT(level, k)                                                                         \
    rt_vk_stack[(uint(level) * uint(RT_STACK_SIZE) + uint(k)) * RT_VK_LOCAL +                      \
                gl_LocalInvocationIndex]

/* The per-dispatch buffers (rt_vk_io.glsl's), declared here so that the
 * traversal can reach the state buffer. */
RT_VK_IO_BUFFERS

#define RT_VK_TICK_LIMIT 32768u
#define RT_VK_UNIT       64u

#define ST_MAIN 0u
#define ST_TOP  256u
#define ST_MESH 336u
#define ST_LEAF 536u

/* The count past which the item suspends: RT_VK_TICK_LIMIT for an item alone
 * in its work group (pc.stride > 1), else never. A number rather than a
 * flag: a condition the loops do not change would let the compiler copy
 * each loop once per value (loop unswitching), which made lavapipe's
 * compile many times slower. */
uint rt_vk_limit = 0xffffffffu;
bool rt_vk_worked = false;    /* a checkpoint passed since this dispatch began */
bool rt_vk_resuming = false;  /* the level that stopped has not loaded its position yet */
bool rt_vk_suspended = false; /* saving: every level saves its region and returns */
uint rt_vk_slot = 0u;         /* the first word of this item's slot */

/* A checkpoint before a unit of work: true when the item must suspend here
 * (the caller saves its position and returns); counts RT_VK_UNIT. Passive
 * while the item is resuming (the position to go on at is deeper down). */
bool rt_vk_checkpoint() {
    /* The pipeline of a tile's first pass never suspends: with SC_RESUME a
     * constant 0 the driver drops the count and every save and load. */
    if (SC_RESUME == 0u) return false;
    rt_vk_ticks += RT_VK_UNIT;
    if (rt_vk_resuming) return false;
    if (rt_vk_ticks > rt_vk_limit && rt_vk_worked) {
        rt_vk_suspended = true;
        return true;
    }
    rt_vk_worked = true;
    return false;
}

/* Word w of the slot, as bits. */
void st_put(inout uint w, uint v) {
    slots[rt_vk_slot + w] = v;
    w++;
}
uint st_get(inout uint w) {
    uint v = slots[rt_vk_slot + w];
    w++;
    return v;
}
void st_putf(inout uint w, float v) {
    st_put(w, floatBitsToUint(v));
}
float st_getf(inout uint w) {
    return uintBitsToFloat(st_get(w));
}
void st_put3(inout uint w, float v[3]) {
    for (int k = 0; k < 3; k++, RT_VK_TICK) st_putf(w, v[k]);
}
void st_get3(inout uint w, out float v[3]) {
    for (int k = 0; k < 3; k++, RT_VK_TICK) v[k] = st_getf(w);
}

void st_put_ray(inout uint w, rt_ray r) {
    st_put3(w, r.org);
    st_put3(w, r.dir);
    st_putf(w, r.tmin);
    st_putf(w, r.tmax);
}
void st_get_ray(inout uint w, out rt_ray r) {
    st_get3(w, r.org);
    st_get3(w, r.dir);
    r.tmin = st_getf(w);
    r.tmax = st_getf(w);
}

void st_put_hit(inout uint w, rt_hit_d h) {
    st_putf(w, h.t);
    st_putf(w, h.u);
    st_putf(w, h.v);
    st_put(w, h.prim);
    st_put(w, h.inst);
    st_put(w, h.entry);
}
void st_get_hit(inout uint w, out rt_hit_d h) {
    h.t = st_getf(w);
    h.u = st_getf(w);
    h.v = st_getf(w);
    h.prim = st_get(w);
    h.inst = st_get(w);
    h.entry = st_get(w);
}

/* A BVH's position (node, stack depth, where in the node) and its stack
 * (level 0 the object BVH's, 1 a mesh's) at word w. */
void st_put_bvh(uint w, int level, uint node, int sp, uint at) {
    st_put(w, node);
    st_put(w, uint(sp));
    st_put(w, at);
    for (int k = 0; k < sp; k++, RT_VK_TICK) st_put(w, STACK_AT(level, k));
}
void st_get_bvh(uint w, int level, out uint node, out int sp, out uint at) {
    node = st_get(w);
    sp = int(st_get(w));
    at = st_get(w);
    for (int k = 0; k < sp; k++, RT_VK_TICK) STACK_AT(level, k) = st_get(w);
}

#endif
