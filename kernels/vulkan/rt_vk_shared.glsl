/* rt_vk_shared.glsl - the GLSL mirror of kernels/rt_layout.h, rt_shared.h
 * and rt_shade.h for the Vulkan backend (host/vulkan/), in the portable
 * maths profile: division and square root from rt_vk_soft_math.glsl, the
 * watertight test's zero edge functions re-checked with the exact
 * difference of products, no double.
 *
 * A hand-written mirror (docs/ARCHITECTURE.md says why it is not generated):
 * every function has the C function's name, operands and order of
 * operations; the scene view is the storage buffers below instead of
 * pointers, a node or triangle is passed by index, out and inout parameters
 * replace pointers. The shader build marks every float operation
 * NoContraction (host/vulkan/spv_precise.c) and test_vulkan_spirv checks it;
 * test_vulkan_oracle holds the results to the CPU oracle's bits.
 *
 * Feature switches are specialization constants (host/vulkan/vk_backend.c
 * sets them from the scene, as OpenCL's -D switches). */
#ifndef RT_VK_SHARED_GLSL
#define RT_VK_SHARED_GLSL

#include "rt_vk_soft_math.glsl"

layout(constant_id = 0) const uint SC_FLAGS = 0u;         /* RT_STATIC_FLAGS */
layout(constant_id = 1) const uint SC_INST_SET = 0u;      /* RT_STATIC_INST_SET */
layout(constant_id = 2) const uint SC_INST_MASK = 3u;     /* RT_STATIC_INST_MASK */
layout(constant_id = 3) const uint SC_TRI_METHOD = 0u;    /* RT_STATIC_TRI_METHOD */
layout(constant_id = 4) const uint SC_DENORM_FLUSH = 0u;  /* 1: the _ftz soft maths */

#define RT_SCENE_FLAGS()  SC_FLAGS
#define RT_INST_FLAGS(f)  (((f) | SC_INST_SET) & SC_INST_MASK)
#define RT_TRI_METHOD()   SC_TRI_METHOD

#define RT_NO_HIT          0xffffffffu
#define RT_NO_MATERIAL     0xffffffffu
#define RT_NODE_LEAF_FLAG  0x80000000u
#define RT_NODE_COUNT_MASK 0x7fffffffu
#define RT_INST_IDENTITY   1u
#define RT_INST_NORMALS    2u
#define RT_TRI_WATERTIGHT  0u
#define RT_TRI_MOLLER      1u
#define RT_TRI_PLUECKER    2u
#define RT_TRI_BADOUEL     3u
#define RT_SCENE_SECONDARY 1u
#define RT_SCENE_SINGLE    2u
#define RT_SCENE_NORMALS   4u
#define RT_SCENE_TRI_MATS  8u
#define RT_STACK_SIZE      64
#define RT_SHADE_STACK     12
#define RT_BOX_FAR_SCALE     1.000000476837158203125
#define RT_BOX_FAR_SCALE_NEG 0.999999523162841796875
#define RT_BOX_T_MARGIN      0.015625
#define RT_SHADOW_TMAX       0.999999940395355224609375
#define RT_INF               uintBitsToFloat(0x7f800000u)

/* ---- the layout (rt_layout.h; std430 puts these at C's offsets) ---------- */

struct rt_node {
    float bmin[3];
    float bmax[3];
    uint a;
    uint b;
};
struct rt_tri {
    float v0[3];
    float v1[3];
    float v2[3];
};
struct rt_instance {
    float world_to_object[12];
    float object_to_world[12];
    uint root;
    uint material;
    uint flags;
    uint mesh;
    uint tri_first;
    uint tri_count;
    float bmin[3];
    float bmax[3];
};
struct rt_material_d {
    float color[3];
    float ambient;
    float diffuse;
    float specular;
    int shininess;
    float reflectivity;
    float transparency;
    float ior;
};
struct rt_light_d {
    float position[3];
    float color[3];
};
struct rt_scene_header {
    uint flags;
    uint top_root;
    uint instance_count;
    uint light_count;
    uint material_count;
    uint tri_method;
    uint max_depth;
    int width;
    int height;
    float min_weight;
    float ambient[3];
    float background[3];
    float cam_pos[3];
    float cam_forward[3];
    float cam_right[3];
    float cam_up[3];
};
struct rt_ray {
    float org[3];
    float dir[3];
    float tmin;
    float tmax;
};
struct rt_ray_pre {
    float inv[3];
    int sign[3];
    int kx, ky, kz;
    float sx, sy, sz;
    float inst_lo;
};
struct rt_hit_d {
    float t, u, v;
    uint prim;
    uint inst;
    uint entry;
};
struct rt_counters {
    uint box_tests;
    uint tri_tests;
    uint rays;
};

/* The scene view: bindings 0..9 in rt_scene_view's order. */
layout(std430, set = 0, binding = 0) readonly buffer B_hdr { rt_scene_header hdr; };
layout(std430, set = 0, binding = 1) readonly buffer B_nodes { rt_node nodes[]; };
layout(std430, set = 0, binding = 2) readonly buffer B_tris { rt_tri tris[]; };
layout(std430, set = 0, binding = 3) readonly buffer B_tri_ids { uint tri_ids[]; };
layout(std430, set = 0, binding = 4) readonly buffer B_normals { float tri_normals[]; };
layout(std430, set = 0, binding = 5) readonly buffer B_tri_mats { uint tri_mats[]; };
layout(std430, set = 0, binding = 6) readonly buffer B_inst { rt_instance instances[]; };
layout(std430, set = 0, binding = 7) readonly buffer B_inst_ids { uint inst_ids[]; };
layout(std430, set = 0, binding = 8) readonly buffer B_mats { rt_material_d materials[]; };
layout(std430, set = 0, binding = 9) readonly buffer B_lights { rt_light_d lights[]; };

/* ---- traversal stacks ------------------------------------------------------
 * In workgroup-shared memory, not in per-invocation arrays: a driver keeps a
 * private array indexed at run time in scratch memory or as a chain of
 * selects (lavapipe traced 100 times slower so). Entry k of invocation l is
 * at k * RT_VK_LOCAL + l (consecutive invocations in consecutive words). The
 * object BVH's stack is entries 0 .. RT_STACK_SIZE - 1, a mesh BVH's the
 * next RT_STACK_SIZE. */
#define RT_VK_LOCAL 64u
shared uint rt_vk_stack[2 * RT_STACK_SIZE * RT_VK_LOCAL];
#define STACK_AT(level, k) rt_vk_stack[(uint(level) * uint(RT_STACK_SIZE) + uint(k)) * RT_VK_LOCAL + gl_LocalInvocationIndex]

/* ---- the portable profile's division and square root -------------------- */

float RT_DIV(float a, float b) {
    return uintBitsToFloat(
        rt_sm_div_bits_(floatBitsToUint(a), floatBitsToUint(b), SC_DENORM_FLUSH != 0u));
}
float RT_SQRT(float x) {
    return uintBitsToFloat(rt_sm_sqrt_bits_(floatBitsToUint(x), SC_DENORM_FLUSH != 0u));
}
float RT_DOP(float a, float b, float c, float d) {
    return uintBitsToFloat(rt_sm_dop_bits_(floatBitsToUint(a), floatBitsToUint(b),
                                           floatBitsToUint(c), floatBitsToUint(d),
                                           SC_DENORM_FLUSH != 0u));
}
/* fabs as a bit operation (as C's fabsf: the sign bit cleared, NaN kept). */
float RT_FABS(float x) {
    return uintBitsToFloat(floatBitsToUint(x) & 0x7fffffffu);
}

/* ---- small vector helpers ----------------------------------------------- */

/* a[k] for k in 0..2, by selects: a local array indexed at run time stays in
 * memory (scratch) in many drivers, and with it every access to the array,
 * which made lavapipe trace several times slower. */
float rt_pick3(float a[3], int k) {
    return k == 0 ? a[0] : (k == 1 ? a[1] : a[2]);
}

float rt_dot3(float a[3], float b[3]) {
    return (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2];
}

void rt_cross3(float a[3], float b[3], out float o[3]) {
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

void rt_normalize3(inout float v[3]) {
    float len = RT_SQRT(rt_dot3(v, v));
    if (len > 0.0) {
        [[dont_unroll]] for (int i = 0; i < 3; i++) v[i] = RT_DIV(v[i], len);
    }
}

/* ---- rays ----------------------------------------------------------------- */

void rt_ray_prepare(rt_ray r, out rt_ray_pre p) {
    float ax = RT_FABS(r.dir[0]), ay = RT_FABS(r.dir[1]), az = RT_FABS(r.dir[2]);
    int kz = 0;
    if (ay > ax) kz = 1;
    if (az > (kz == 1 ? ay : ax)) kz = 2;
    int kx = kz + 1 == 3 ? 0 : kz + 1;
    int ky = kx + 1 == 3 ? 0 : kx + 1;
    float dkz = rt_pick3(r.dir, kz);
    if (dkz < 0.0) {
        int tmp = kx;
        kx = ky;
        ky = tmp;
    }
    p.kx = kx;
    p.ky = ky;
    p.kz = kz;
    /* The six divisions of the C function, in one loop: one inlined copy of
     * the soft division instead of six. */
    float num[6] = float[6](1.0, 1.0, 1.0, rt_pick3(r.dir, kx), rt_pick3(r.dir, ky), 1.0);
    float den[6] = float[6](r.dir[0], r.dir[1], r.dir[2], dkz, dkz, dkz);
    float q[6];
    [[dont_unroll]] for (int i = 0; i < 6; i++) q[i] = RT_DIV(num[i], den[i]);
    for (int i = 0; i < 3; i++) {
        p.inv[i] = q[i];
        p.sign[i] = p.inv[i] < 0.0 ? 1 : 0;
    }
    p.sx = q[3];
    p.sy = q[4];
    p.sz = q[5];
    p.inst_lo = -RT_INF;
}

float rt_camera_sx(int px) {
    return RT_DIV(2.0 * (float(px) + 0.5), float(hdr.width)) - 1.0;
}
float rt_camera_sy(int py) {
    return 1.0 - RT_DIV(2.0 * (float(py) + 0.5), float(hdr.height));
}
void rt_camera_ray(int px, int py, out rt_ray r) {
    float sx = rt_camera_sx(px), sy = rt_camera_sy(py);
    for (int i = 0; i < 3; i++) {
        r.org[i] = hdr.cam_pos[i];
        r.dir[i] = (hdr.cam_forward[i] + sx * hdr.cam_right[i]) + sy * hdr.cam_up[i];
    }
    r.tmin = 0.0;
    r.tmax = RT_INF;
}

void rt_offset_point(float p[3], float n[3], float sign, out float o[3]) {
    for (int i = 0; i < 3; i++) {
        float ni = sign * n[i];
        int of = int(256.0 * ni);
        float pi = intBitsToFloat(floatBitsToInt(p[i]) + (p[i] < 0.0 ? -of : of));
        o[i] = RT_FABS(p[i]) < 0.03125 ? p[i] + 0.0000152587890625 * ni : pi;
    }
}

/* ---- ray/box -------------------------------------------------------------- */

bool rt_box_test(uint node, rt_ray r, rt_ray_pre p, float tmin, float tmax, out float tnear) {
    float lo = tmin, hi = RT_INF;
    for (int i = 0; i < 3; i++) {
        float a = p.sign[i] != 0 ? nodes[node].bmax[i] : nodes[node].bmin[i];
        float b = p.sign[i] != 0 ? nodes[node].bmin[i] : nodes[node].bmax[i];
        float t0 = (a - r.org[i]) * p.inv[i];
        float t1 = (b - r.org[i]) * p.inv[i];
        lo = t0 > lo ? t0 : lo;
        hi = t1 < hi ? t1 : hi;
    }
    hi = hi * (hi < 0.0 ? RT_BOX_FAR_SCALE_NEG : RT_BOX_FAR_SCALE);
    hi = tmax < hi ? tmax : hi;
    tnear = lo;
    return lo <= hi;
}

/* ---- ray/triangle tests --------------------------------------------------- */

void rt_edge_recheck(float Ax, float Ay, float Bx, float By, float Cx, float Cy, out float U,
                     out float V, out float W) {
    U = RT_DOP(Cx, By, Cy, Bx);
    V = RT_DOP(Ax, Cy, Ay, Cx);
    W = RT_DOP(Bx, Ay, By, Ax);
}

bool rt_tri_watertight(uint e, rt_ray r, rt_ray_pre p, float tmin, float tmax, out float t,
                       out float u, out float v) {
    float A[3], B[3], C[3];
    for (int i = 0; i < 3; i++) {
        A[i] = tris[e].v0[i] - r.org[i];
        B[i] = tris[e].v1[i] - r.org[i];
        C[i] = tris[e].v2[i] - r.org[i];
    }
    int kx = p.kx, ky = p.ky, kz = p.kz;
    float Akx = rt_pick3(A, kx), Aky = rt_pick3(A, ky), Akz = rt_pick3(A, kz);
    float Bkx = rt_pick3(B, kx), Bky = rt_pick3(B, ky), Bkz = rt_pick3(B, kz);
    float Ckx = rt_pick3(C, kx), Cky = rt_pick3(C, ky), Ckz = rt_pick3(C, kz);
    float Ax = Akx - p.sx * Akz, Ay = Aky - p.sy * Akz;
    float Bx = Bkx - p.sx * Bkz, By = Bky - p.sy * Bkz;
    float Cx = Ckx - p.sx * Ckz, Cy = Cky - p.sy * Ckz;
    float U = Cx * By - Cy * Bx;
    float V = Ax * Cy - Ay * Cx;
    float W = Bx * Ay - By * Ax;
    if (U == 0.0 || V == 0.0 || W == 0.0) rt_edge_recheck(Ax, Ay, Bx, By, Cx, Cy, U, V, W);
    t = 0.0;
    u = 0.0;
    v = 0.0;
    if ((U < 0.0 || V < 0.0 || W < 0.0) && (U > 0.0 || V > 0.0 || W > 0.0)) return false;
    float det = (U + V) + W;
    if (det == 0.0) return false;
    float Az = p.sz * Akz, Bz = p.sz * Bkz, Cz = p.sz * Ckz;
    float T = (U * Az + V * Bz) + W * Cz;
    float tt = RT_DIV(T, det);
    if (!(tt >= tmin && tt <= tmax)) return false;
    t = tt;
    u = RT_DIV(V, det);
    v = RT_DIV(W, det);
    return true;
}

bool rt_tri_moller(uint e, rt_ray r, float tmin, float tmax, out float t, out float u,
                   out float v) {
    float e1[3], e2[3], s[3], pv[3], q[3];
    for (int i = 0; i < 3; i++) {
        e1[i] = tris[e].v1[i] - tris[e].v0[i];
        e2[i] = tris[e].v2[i] - tris[e].v0[i];
        s[i] = r.org[i] - tris[e].v0[i];
    }
    t = 0.0;
    u = 0.0;
    v = 0.0;
    rt_cross3(r.dir, e2, pv);
    float det = rt_dot3(e1, pv);
    if (det == 0.0) return false;
    float inv = RT_DIV(1.0, det);
    float uu = rt_dot3(s, pv) * inv;
    if (!(uu >= 0.0 && uu <= 1.0)) return false;
    rt_cross3(s, e1, q);
    float vv = rt_dot3(r.dir, q) * inv;
    if (!(vv >= 0.0 && uu + vv <= 1.0)) return false;
    float tt = rt_dot3(e2, q) * inv;
    if (!(tt >= tmin && tt <= tmax)) return false;
    t = tt;
    u = uu;
    v = vv;
    return true;
}

bool rt_tri_pluecker(uint e, rt_ray r, float tmin, float tmax, out float t, out float u,
                     out float v) {
    float a[3], b[3], c[3], bc[3], ca[3], ab[3];
    for (int i = 0; i < 3; i++) {
        a[i] = tris[e].v0[i] - r.org[i];
        b[i] = tris[e].v1[i] - r.org[i];
        c[i] = tris[e].v2[i] - r.org[i];
    }
    t = 0.0;
    u = 0.0;
    v = 0.0;
    rt_cross3(b, c, bc);
    rt_cross3(c, a, ca);
    rt_cross3(a, b, ab);
    float U = rt_dot3(r.dir, bc), V = rt_dot3(r.dir, ca), W = rt_dot3(r.dir, ab);
    if ((U < 0.0 || V < 0.0 || W < 0.0) && (U > 0.0 || V > 0.0 || W > 0.0)) return false;
    float det = (U + V) + W;
    if (det == 0.0) return false;
    float tt = RT_DIV(rt_dot3(a, bc), det);
    if (!(tt >= tmin && tt <= tmax)) return false;
    t = tt;
    u = RT_DIV(V, det);
    v = RT_DIV(W, det);
    return true;
}

bool rt_tri_badouel(uint e, rt_ray r, float tmin, float tmax, out float t, out float u,
                    out float v) {
    float e1[3], e2[3], n[3], a[3];
    for (int i = 0; i < 3; i++) {
        e1[i] = tris[e].v1[i] - tris[e].v0[i];
        e2[i] = tris[e].v2[i] - tris[e].v0[i];
        a[i] = tris[e].v0[i] - r.org[i];
    }
    t = 0.0;
    u = 0.0;
    v = 0.0;
    rt_cross3(e1, e2, n);
    float nd = rt_dot3(n, r.dir);
    if (nd == 0.0) return false;
    float tt = RT_DIV(rt_dot3(n, a), nd);
    if (!(tt >= tmin && tt <= tmax)) return false;
    float nx = RT_FABS(n[0]), ny = RT_FABS(n[1]), nz = RT_FABS(n[2]);
    int k = 0;
    if (ny > nx) k = 1;
    if (nz > (k == 1 ? ny : nx)) k = 2;
    int i1 = k == 0 ? 1 : 0, i2 = k == 2 ? 1 : 2;
    float e1i1 = rt_pick3(e1, i1), e1i2 = rt_pick3(e1, i2);
    float e2i1 = rt_pick3(e2, i1), e2i2 = rt_pick3(e2, i2);
    float p1 = (rt_pick3(r.org, i1) + tt * rt_pick3(r.dir, i1)) - tris[e].v0[i1];
    float p2 = (rt_pick3(r.org, i2) + tt * rt_pick3(r.dir, i2)) - tris[e].v0[i2];
    float det = e1i1 * e2i2 - e1i2 * e2i1;
    float uu = RT_DIV(p1 * e2i2 - p2 * e2i1, det);
    float vv = RT_DIV(e1i1 * p2 - e1i2 * p1, det);
    if (!(uu >= 0.0 && vv >= 0.0 && uu + vv <= 1.0)) return false;
    t = tt;
    u = uu;
    v = vv;
    return true;
}

bool rt_tri_test(uint method, uint e, rt_ray r, rt_ray_pre p, float tmin, float tmax,
                 out float t, out float u, out float v) {
    if (method == RT_TRI_MOLLER) return rt_tri_moller(e, r, tmin, tmax, t, u, v);
    if (method == RT_TRI_PLUECKER) return rt_tri_pluecker(e, r, tmin, tmax, t, u, v);
    if (method == RT_TRI_BADOUEL) return rt_tri_badouel(e, r, tmin, tmax, t, u, v);
    return rt_tri_watertight(e, r, p, tmin, tmax, t, u, v);
}

/* ---- traversal ------------------------------------------------------------ */

bool rt_hit_before(float t, uint inst, uint prim, rt_hit_d best) {
    if (t != best.t) return t < best.t;
    if (inst != best.inst) return inst < best.inst;
    return prim < best.prim;
}

void rt_hit_init(out rt_hit_d h, rt_ray r) {
    h.t = r.tmax;
    h.u = 0.0;
    h.v = 0.0;
    h.prim = RT_NO_HIT;
    h.inst = RT_NO_HIT;
    h.entry = RT_NO_HIT;
}

float rt_box_lo(float tmin) {
    return tmin - RT_FABS(tmin) * RT_BOX_T_MARGIN;
}
float rt_box_hi(float tmax) {
    return tmax + RT_FABS(tmax) * RT_BOX_T_MARGIN;
}

/* ---- hit acceptance (rt_shared.h says why) ---- */

void rt_slab(float a, float b, float org, float inv, inout float lo, inout float hi) {
    float t0 = (a - org) * inv;
    float t1 = (b - org) * inv;
    lo = t0 > lo ? t0 : lo;
    hi = t1 < hi ? t1 : hi;
}

bool rt_slab_end(float lo, float hi, float tmax, out float tnear) {
    hi = hi * (hi < 0.0 ? RT_BOX_FAR_SCALE_NEG : RT_BOX_FAR_SCALE);
    hi = tmax < hi ? tmax : hi;
    tnear = lo;
    return lo <= hi;
}

bool rt_inst_enter(uint inst, rt_ray r, rt_ray_pre p, out float inst_lo) {
    float lo = rt_box_lo(r.tmin), hi = RT_INF;
    for (int i = 0; i < 3; i++) {
        float mn = instances[inst].bmin[i], mx = instances[inst].bmax[i];
        rt_slab(p.sign[i] != 0 ? mx : mn, p.sign[i] != 0 ? mn : mx, r.org[i], p.inv[i], lo, hi);
    }
    return rt_slab_end(lo, hi, RT_INF, inst_lo);
}

float rt_min3(float a, float b, float c) {
    float m = a < b ? a : b;
    return c < m ? c : m;
}
float rt_max3(float a, float b, float c) {
    float m = a > b ? a : b;
    return c > m ? c : m;
}

bool rt_hit_accepted(uint e, rt_ray r, rt_ray_pre p, float t) {
    float hi_t = rt_box_hi(t);
    if (hi_t < p.inst_lo) return false;
    float lo = rt_box_lo(r.tmin), hi = RT_INF, tn;
    for (int i = 0; i < 3; i++) {
        float mn = rt_min3(tris[e].v0[i], tris[e].v1[i], tris[e].v2[i]);
        float mx = rt_max3(tris[e].v0[i], tris[e].v1[i], tris[e].v2[i]);
        rt_slab(p.sign[i] != 0 ? mx : mn, p.sign[i] != 0 ? mn : mx, r.org[i], p.inv[i], lo, hi);
    }
    return rt_slab_end(lo, hi, hi_t, tn);
}

bool rt_leaf_test(uint first, uint count, uint inst, rt_ray r, rt_ray_pre p, bool any_hit,
                  inout rt_hit_d best, inout rt_counters c) {
    uint method = RT_TRI_METHOD();
    for (uint e = first; e < first + count; e++) {
        float t, u, v;
        c.tri_tests++;
        if (!rt_tri_test(method, e, r, p, r.tmin, best.t, t, u, v)) continue;
        if (!rt_hit_accepted(e, r, p, t)) continue;
        uint prim = tri_ids[e];
        if (any_hit || rt_hit_before(t, inst, prim, best)) {
            best.t = t;
            best.u = u;
            best.v = v;
            best.prim = prim;
            best.inst = inst;
            best.entry = e;
            if (any_hit) return true;
        }
    }
    return false;
}

/* rt_descend without the stack (GLSL has no pointer to it): returns 0 when
 * the caller must pop, 1 to go on at *next, 2 to go on at *next after
 * pushing *push. The same tests and choices as the C function. */
int rt_descend(uint node, rt_ray r, rt_ray_pre p, rt_hit_d best, inout rt_counters c,
               out uint next, out uint push) {
    float t0, t1, lo = rt_box_lo(r.tmin), hi = rt_box_hi(best.t);
    uint na = nodes[node].a, nb = nodes[node].b;
    c.box_tests += 2u;
    bool h0 = rt_box_test(na, r, p, lo, hi, t0);
    bool h1 = rt_box_test(nb, r, p, lo, hi, t1);
    next = 0u;
    push = 0u;
    if (h0 && h1) {
        bool right_first = t1 < t0;
        push = right_first ? na : nb;
        next = right_first ? nb : na;
        return 2;
    } else if (h0) {
        next = na;
        return 1;
    } else if (h1) {
        next = nb;
        return 1;
    }
    return 0;
}

bool rt_trace_mesh(uint root, uint inst, rt_ray r, rt_ray_pre p, bool any_hit,
                   inout rt_hit_d best, inout rt_counters c) {
    int sp = 0;
    float tn;
    c.box_tests++;
    if (!rt_box_test(root, r, p, rt_box_lo(r.tmin), rt_box_hi(best.t), tn)) return false;
    uint node = root;
    for (;;) {
        uint nb = nodes[node].b;
        if ((nb & RT_NODE_LEAF_FLAG) != 0u) {
            if (rt_leaf_test(nodes[node].a, nb & RT_NODE_COUNT_MASK, inst, r, p, any_hit, best, c))
                return true;
            if (sp == 0) return false;
            node = STACK_AT(1, --sp);
            continue;
        }
        uint next, push;
        int d = rt_descend(node, r, p, best, c, next, push);
        if (d == 0) {
            if (sp == 0) return false;
            node = STACK_AT(1, --sp);
        } else {
            if (d == 2) STACK_AT(1, sp++) = push;
            node = next;
        }
    }
    return false;
}

#include "rt_vk_kd.glsl" /* kd-tree meshes: rt_kd_trace_mesh */

void rt_ray_to_object(uint inst, rt_ray r, out rt_ray o) {
    for (int i = 0; i < 3; i++) {
        float m0 = instances[inst].world_to_object[4 * i];
        float m1 = instances[inst].world_to_object[4 * i + 1];
        float m2 = instances[inst].world_to_object[4 * i + 2];
        float m3 = instances[inst].world_to_object[4 * i + 3];
        o.org[i] = ((m0 * r.org[0] + m1 * r.org[1]) + m2 * r.org[2]) + m3;
        o.dir[i] = (m0 * r.dir[0] + m1 * r.dir[1]) + m2 * r.dir[2];
    }
    o.tmin = r.tmin;
    o.tmax = r.tmax;
}

/* One call of rt_trace_mesh (and of rt_kd_trace_mesh) for both cases of the
 * C function (the ray transformed or not): one inlined copy of each
 * traversal. */
bool rt_trace_instance(uint inst, rt_ray r, rt_ray_pre p, bool any_hit, inout rt_hit_d best,
                       inout rt_counters c) {
    uint root = instances[inst].root;
    float inst_lo = -RT_INF;
    if ((RT_SCENE_FLAGS() & RT_SCENE_SINGLE) == 0u && !rt_inst_enter(inst, r, p, inst_lo))
        return false;
    rt_ray o = r;
    rt_ray_pre op = p;
    if ((RT_INST_FLAGS(instances[inst].flags) & RT_INST_IDENTITY) == 0u) {
        rt_ray_to_object(inst, r, o);
        rt_ray_prepare(o, op);
    }
    op.inst_lo = inst_lo;
    if ((RT_INST_FLAGS(instances[inst].flags) & RT_INST_KD) != 0u)
        return rt_kd_trace_mesh(root, inst, o, op, any_hit, best, c);
    return rt_trace_mesh(root, inst, o, op, any_hit, best, c);
}

bool rt_trace(rt_ray r, bool any_hit, out rt_hit_d best, inout rt_counters c) {
    rt_ray_pre p;
    rt_ray_prepare(r, p);
    rt_hit_init(best, r);
    c.rays++;
    if (hdr.instance_count == 0u) return false;
    if ((RT_SCENE_FLAGS() & RT_SCENE_SINGLE) != 0u) {
        rt_trace_instance(0u, r, p, any_hit, best, c);
        return best.prim != RT_NO_HIT;
    }
    int sp = 0;
    float tn;
    uint node = hdr.top_root;
    c.box_tests++;
    if (!rt_box_test(node, r, p, rt_box_lo(r.tmin), rt_box_hi(best.t), tn)) return false;
    for (;;) {
        uint nb = nodes[node].b;
        if ((nb & RT_NODE_LEAF_FLAG) != 0u) {
            uint count = nb & RT_NODE_COUNT_MASK, na = nodes[node].a;
            for (uint e = na; e < na + count; e++)
                if (rt_trace_instance(inst_ids[e], r, p, any_hit, best, c)) return true;
            if (sp == 0) break;
            node = STACK_AT(0, --sp);
            continue;
        }
        uint next, push;
        int d = rt_descend(node, r, p, best, c, next, push);
        if (d == 0) {
            if (sp == 0) break;
            node = STACK_AT(0, --sp);
        } else {
            if (d == 2) STACK_AT(0, sp++) = push;
            node = next;
        }
    }
    return best.prim != RT_NO_HIT;
}

/* ---- shading (rt_shade.h) ------------------------------------------------- */

struct rt_surface {
    float p[3];
    float ng[3];
    float ns[3];
    int front;
    uint material;
};

void rt_normal_to_world(uint inst, float n[3], out float o[3]) {
    for (int i = 0; i < 3; i++)
        o[i] = (instances[inst].world_to_object[i] * n[0] +
                instances[inst].world_to_object[4 + i] * n[1]) +
               instances[inst].world_to_object[8 + i] * n[2];
}

void rt_point_to_world(uint inst, float p[3], out float o[3]) {
    for (int i = 0; i < 3; i++)
        o[i] = ((instances[inst].object_to_world[4 * i] * p[0] +
                 instances[inst].object_to_world[4 * i + 1] * p[1]) +
                instances[inst].object_to_world[4 * i + 2] * p[2]) +
               instances[inst].object_to_world[4 * i + 3];
}

/* The hit point from the barycentrics in object space, then transformed
 * (Waechter and Binder 2019), as the C function. */
void rt_surface_at(rt_ray r, rt_hit_d h, out rt_surface sf) {
    uint e = h.entry, inst = h.inst;
    bool identity = (RT_INST_FLAGS(instances[inst].flags) & RT_INST_IDENTITY) != 0u;
    float e1[3], e2[3], n[3], ns[3], po[3];
    float b0 = (1.0 - h.u) - h.v;
    for (int k = 0; k < 3; k++) {
        e1[k] = tris[e].v1[k] - tris[e].v0[k];
        e2[k] = tris[e].v2[k] - tris[e].v0[k];
        po[k] = (b0 * tris[e].v0[k] + h.u * tris[e].v1[k]) + h.v * tris[e].v2[k];
    }
    if (identity) {
        for (int k = 0; k < 3; k++) sf.p[k] = po[k];
    } else {
        rt_point_to_world(inst, po, sf.p);
    }
    rt_cross3(e1, e2, n);
    if (identity) {
        for (int k = 0; k < 3; k++) sf.ng[k] = n[k];
    } else {
        rt_normal_to_world(inst, n, sf.ng);
    }
    rt_normalize3(sf.ng);
    for (int k = 0; k < 3; k++) sf.ns[k] = sf.ng[k];
    if ((RT_INST_FLAGS(instances[inst].flags) & RT_INST_NORMALS) != 0u) {
        uint vn = 9u * e;
        float w = (1.0 - h.u) - h.v;
        for (int k = 0; k < 3; k++)
            n[k] = (w * tri_normals[vn + uint(k)] + h.u * tri_normals[vn + 3u + uint(k)]) +
                   h.v * tri_normals[vn + 6u + uint(k)];
        if (identity) {
            for (int k = 0; k < 3; k++) ns[k] = n[k];
        } else {
            rt_normal_to_world(inst, n, ns);
        }
        rt_normalize3(ns);
        if (rt_dot3(ns, ns) > 0.0)
            for (int k = 0; k < 3; k++) sf.ns[k] = ns[k];
    }
    sf.front = rt_dot3(sf.ns, r.dir) < 0.0 ? 1 : 0;
    if (rt_dot3(sf.ng, r.dir) > 0.0)
        for (int k = 0; k < 3; k++) sf.ng[k] = -sf.ng[k];
    if (sf.front == 0)
        for (int k = 0; k < 3; k++) sf.ns[k] = -sf.ns[k];
    sf.material = instances[inst].material;
    if ((RT_SCENE_FLAGS() & RT_SCENE_TRI_MATS) != 0u && tri_mats[e] != RT_NO_MATERIAL)
        sf.material = tri_mats[e];
}

void rt_phong_ambient(rt_surface sf, out float o[3]) {
    uint m = sf.material;
    for (int k = 0; k < 3; k++)
        o[k] = (materials[m].ambient * materials[m].color[k]) * hdr.ambient[k];
}

bool rt_phong_light(rt_surface sf, uint li, out rt_ray sr, out float Ln[3], out float ndl) {
    float L[3];
    for (int k = 0; k < 3; k++) L[k] = lights[li].position[k] - sf.p[k];
    float dist = RT_SQRT(rt_dot3(L, L));
    ndl = 0.0;
    if (!(dist > 0.0)) return false;
    for (int k = 0; k < 3; k++) Ln[k] = RT_DIV(L[k], dist);
    ndl = rt_dot3(sf.ns, Ln);
    if (!(ndl > 0.0)) return false;
    rt_offset_point(sf.p, sf.ng, rt_dot3(sf.ng, L) >= 0.0 ? 1.0 : -1.0, sr.org);
    for (int k = 0; k < 3; k++) sr.dir[k] = lights[li].position[k] - sr.org[k];
    sr.tmin = 0.0;
    sr.tmax = RT_SHADOW_TMAX;
    return true;
}

void rt_phong_add(rt_surface sf, uint li, float Ln[3], float ndl, float dn[3], inout float o[3]) {
    uint m = sf.material;
    for (int k = 0; k < 3; k++)
        o[k] = o[k] + ((materials[m].diffuse * materials[m].color[k]) * lights[li].color[k]) * ndl;
    if (materials[m].specular > 0.0) {
        float R[3];
        for (int k = 0; k < 3; k++) R[k] = (2.0 * ndl) * sf.ns[k] - Ln[k];
        float rv = -rt_dot3(R, dn);
        if (rv > 0.0) {
            float pw = 1.0;
            for (int i = 0; i < materials[m].shininess; i++) pw = pw * rv;
            for (int k = 0; k < 3; k++)
                o[k] = o[k] + (materials[m].specular * lights[li].color[k]) * pw;
        }
    }
}

struct rt_shade_entry {
    rt_ray ray;
    float w[3];
    uint depth;
};

bool rt_weight_counts(float w[3], float min_weight) {
    return w[0] >= min_weight || w[1] >= min_weight || w[2] >= min_weight;
}

struct rt_shade_node {
    rt_surface sf;
    float dn[3];
    float lit[3];
    float lw;
};

bool rt_shade_begin(rt_shade_entry e, rt_hit_d h, out rt_shade_node nd) {
    nd.lw = 0.0;
    if (h.prim == RT_NO_HIT) return false;
    rt_surface_at(e.ray, h, nd.sf);
    uint m = nd.sf.material;
    for (int k = 0; k < 3; k++) nd.dn[k] = e.ray.dir[k];
    rt_normalize3(nd.dn);
    nd.lw = (1.0 - materials[m].reflectivity) - materials[m].transparency;
    if (!(nd.lw > 0.0)) return false;
    rt_phong_ambient(nd.sf, nd.lit);
    return true;
}

void rt_shade_end(rt_shade_entry e, rt_hit_d h, rt_shade_node nd, out float term[3],
                  out bool has_term, out rt_shade_entry child[2], out int children) {
    has_term = false;
    children = 0;
    term[0] = 0.0;
    term[1] = 0.0;
    term[2] = 0.0;
    if (h.prim == RT_NO_HIT) {
        for (int k = 0; k < 3; k++) term[k] = e.w[k] * hdr.background[k];
        has_term = true;
        return;
    }
    uint m = nd.sf.material;
    if (nd.lw > 0.0) {
        for (int k = 0; k < 3; k++) term[k] = (e.w[k] * nd.lw) * nd.lit[k];
        has_term = true;
    }
    if ((RT_SCENE_FLAGS() & RT_SCENE_SECONDARY) == 0u || e.depth >= hdr.max_depth) return;
    float refl = materials[m].reflectivity;
    float cosi = -rt_dot3(nd.dn, nd.sf.ns);
    if (materials[m].transparency > 0.0) {
        float ior = materials[m].ior;
        float eta = nd.sf.front != 0 ? RT_DIV(1.0, ior) : ior;
        float k2 = 1.0 - (eta * eta) * (1.0 - cosi * cosi);
        if (k2 < 0.0) {
            refl = refl + materials[m].transparency;
        } else {
            rt_shade_entry t;
            float a = eta * cosi - RT_SQRT(k2);
            for (int k = 0; k < 3; k++) {
                t.ray.dir[k] = eta * nd.dn[k] + a * nd.sf.ns[k];
                t.w[k] = e.w[k] * materials[m].transparency;
            }
            rt_offset_point(nd.sf.p, nd.sf.ng, -1.0, t.ray.org);
            t.ray.tmin = 0.0;
            t.ray.tmax = RT_INF;
            t.depth = e.depth + 1u;
            if (rt_weight_counts(t.w, hdr.min_weight)) child[children++] = t;
        }
    }
    if (refl > 0.0) {
        rt_shade_entry t;
        for (int k = 0; k < 3; k++) {
            t.ray.dir[k] = nd.dn[k] + (2.0 * cosi) * nd.sf.ns[k];
            t.w[k] = e.w[k] * refl;
        }
        rt_offset_point(nd.sf.p, nd.sf.ng, 1.0, t.ray.org);
        t.ray.tmin = 0.0;
        t.ray.tmax = RT_INF;
        t.depth = e.depth + 1u;
        if (rt_weight_counts(t.w, hdr.min_weight)) child[children++] = t;
    }
}

#endif
