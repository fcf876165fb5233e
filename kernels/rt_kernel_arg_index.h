/* rt_kernel_arg_index.h - the position of every argument of every OpenCL
 * kernel (kernels/rt_single_ray.cl, kernels/rt_ray_packet.cl), named once for the
 * host (host/opencl/cl_backend.c sets arguments by these names) and held to
 * the kernels' signatures by a test (tests/test_opencl_kernel_args.c asks the
 * built program for each argument's name). Valid C and OpenCL C.
 *
 * Tracing kernels start with the eleven arrays of the scene view (RT_VIEW_ARGS
 * in rt_kernel_args.h), in the order of rt_scene_view. */
#ifndef RT_KERNEL_ARG_INDEX_H
#define RT_KERNEL_ARG_INDEX_H

/* The scene view, arguments 0..10 of every tracing kernel. */
enum {
    RT_ARG_HDR,
    RT_ARG_NODES,
    RT_ARG_TRIS,
    RT_ARG_TRI_IDS,
    RT_ARG_TRI_NORMALS,
    RT_ARG_TRI_MATS,
    RT_ARG_INSTANCES,
    RT_ARG_INST_IDS,
    RT_ARG_MATERIALS,
    RT_ARG_LIGHTS,
    RT_ARG_KD_NODES,
    RT_ARG_VIEW_COUNT
};

/* rt_k_camera(hdr, first, count, rays) */
enum { RT_K_CAMERA_HDR, RT_K_CAMERA_FIRST, RT_K_CAMERA_COUNT, RT_K_CAMERA_RAYS, RT_K_CAMERA_ARGS };

/* rt_k_trace(view, count, any_hit, rays, hits, counters) */
enum {
    RT_K_TRACE_COUNT = RT_ARG_VIEW_COUNT,
    RT_K_TRACE_ANY_HIT,
    RT_K_TRACE_RAYS,
    RT_K_TRACE_HITS,
    RT_K_TRACE_COUNTERS,
    RT_K_TRACE_ARGS
};

/* rt_k_shade(view, first, count, aov, channels, rays, hits, counters, fb) */
enum {
    RT_K_SHADE_FIRST = RT_ARG_VIEW_COUNT,
    RT_K_SHADE_COUNT,
    RT_K_SHADE_AOV,
    RT_K_SHADE_CHANNELS,
    RT_K_SHADE_RAYS,
    RT_K_SHADE_HITS,
    RT_K_SHADE_COUNTERS,
    RT_K_SHADE_FB,
    RT_K_SHADE_ARGS
};

/* rt_k_wave_camera(hdr, first, count, queue) */
enum { RT_K_WCAM_HDR, RT_K_WCAM_FIRST, RT_K_WCAM_COUNT, RT_K_WCAM_QUEUE, RT_K_WCAM_ARGS };

/* rt_k_wave_trace(view, count, queue, hits, counters) */
enum {
    RT_K_WTRACE_COUNT = RT_ARG_VIEW_COUNT,
    RT_K_WTRACE_QUEUE,
    RT_K_WTRACE_HITS,
    RT_K_WTRACE_COUNTERS,
    RT_K_WTRACE_ARGS
};

/* rt_k_wave_shade(view, count, queue, hits, counters, records, stride, next,
 * next_count, next_cap) */
enum {
    RT_K_WSHADE_COUNT = RT_ARG_VIEW_COUNT,
    RT_K_WSHADE_QUEUE,
    RT_K_WSHADE_HITS,
    RT_K_WSHADE_COUNTERS,
    RT_K_WSHADE_RECORDS,
    RT_K_WSHADE_STRIDE,
    RT_K_WSHADE_NEXT,
    RT_K_WSHADE_NEXT_COUNT,
    RT_K_WSHADE_NEXT_CAP,
    RT_K_WSHADE_ARGS
};

/* rt_k_wave_sum(first, count, hdr, records, stride, channels, fb) */
enum {
    RT_K_WSUM_FIRST,
    RT_K_WSUM_COUNT,
    RT_K_WSUM_HDR,
    RT_K_WSUM_RECORDS,
    RT_K_WSUM_STRIDE,
    RT_K_WSUM_CHANNELS,
    RT_K_WSUM_FB,
    RT_K_WSUM_ARGS
};

/* rt_k_packet(view, first, count, aov, channels, counters, fb) */
enum {
    RT_K_PACKET_FIRST = RT_ARG_VIEW_COUNT,
    RT_K_PACKET_COUNT,
    RT_K_PACKET_AOV,
    RT_K_PACKET_CHANNELS,
    RT_K_PACKET_COUNTERS,
    RT_K_PACKET_FB,
    RT_K_PACKET_ARGS
};

/* rt_k_packet_trace(view, count, rays, hits, counters) */
enum {
    RT_K_PTRACE_COUNT = RT_ARG_VIEW_COUNT,
    RT_K_PTRACE_RAYS,
    RT_K_PTRACE_HITS,
    RT_K_PTRACE_COUNTERS,
    RT_K_PTRACE_ARGS
};

#ifdef RT_KERNEL_SIGNATURES
/* The argument names of each kernel in signature order, for the test that
 * holds the enums above to the .cl files (defined there only). */
typedef struct rt_kernel_signature {
    const char *kernel;
    int view;              /* 1: the view arguments come first */
    int args;              /* the argument count (the *_ARGS enum) */
    const char *names[20]; /* after the view's */
} rt_kernel_signature;

static const char *const rt_kernel_view_names[RT_ARG_VIEW_COUNT] = {
    "hdr",       "nodes",    "tris",      "tri_ids", "tri_normals", "tri_mats",
    "instances", "inst_ids", "materials", "lights",  "kd_nodes"};

static const rt_kernel_signature rt_kernel_signatures[] = {
    {"rt_k_camera", 0, RT_K_CAMERA_ARGS, {"hdr", "first", "count", "rays"}},
    {"rt_k_trace", 1, RT_K_TRACE_ARGS, {"count", "any_hit", "rays", "hits", "counters"}},
    {"rt_k_shade",
     1,
     RT_K_SHADE_ARGS,
     {"first", "count", "aov", "channels", "rays", "hits", "counters", "fb"}},
    {"rt_k_wave_camera", 0, RT_K_WCAM_ARGS, {"hdr", "first", "count", "queue"}},
    {"rt_k_wave_trace", 1, RT_K_WTRACE_ARGS, {"count", "queue", "hits", "counters"}},
    {"rt_k_wave_shade",
     1,
     RT_K_WSHADE_ARGS,
     {"count", "queue", "hits", "counters", "records", "stride", "next", "next_count", "next_cap"}},
    {"rt_k_wave_sum",
     0,
     RT_K_WSUM_ARGS,
     {"first", "count", "hdr", "records", "stride", "channels", "fb"}},
    {"rt_k_packet", 1, RT_K_PACKET_ARGS, {"first", "count", "aov", "channels", "counters", "fb"}},
    {"rt_k_packet_trace", 1, RT_K_PTRACE_ARGS, {"count", "rays", "hits", "counters"}},
};
#endif

#endif /* RT_KERNEL_ARG_INDEX_H */
