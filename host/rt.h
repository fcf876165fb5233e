/* SPDX-License-Identifier: Apache-2.0 */
/* rt.h - the public C API of the rtcl ray tracing library.
 *
 * The operations follow the library of Langr 2016 (section 3.2): meshes of
 * triangles, objects that reference one or more meshes (keyframes) with a
 * material and a rigid transform, point lights, a camera, and render.
 *
 * Two objects: the scene (rt_scene), pure data that names nothing of
 * rendering, and the renderer (rt_renderer, the thesis's RayTracerContext),
 * which the caller creates with a backend and owns: it keeps the BVHs, the
 * flattened layout, the worker threads and the device state between frames,
 * and renders or traces any scene given to it.
 *
 * Conventions
 * - Every function that can fail returns an rt_status and fills one error
 *   struct (rt_error) with context (file, line, column, reason where they
 *   apply): a scene keeps the last error of the calls that edit it
 *   (rt_scene_error), a renderer the last error of its calls
 *   (rt_renderer_error), and loaders fill the rt_error the caller passes.
 *   The library never prints.
 * - Ids are dense 0-based indices in creation order.
 * - Matrices are 4x4, row-major, acting on column vectors: p' = M p, so the
 *   translation is in elements 3, 7 and 11.
 */
#ifndef RTCL_RT_H
#define RTCL_RT_H

#include <stddef.h>
#include <stdint.h>

/* RTCL_VERSION_MAJOR, _MINOR, _PATCH, RTCL_VERSION_STRING: the version this
 * header belongs to (installed beside it, written by the build). */
#include "rtcl_version.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum rt_status {
    RT_OK = 0,
    RT_ERROR_INVALID_ARGUMENT, /* a bad id, a NaN, a null pointer */
    RT_ERROR_IO,               /* a file could not be opened or read */
    RT_ERROR_PARSE,            /* a file's content is malformed */
    RT_ERROR_OUT_OF_MEMORY,
    RT_ERROR_UNSUPPORTED, /* a backend or feature that this build or machine lacks */
    RT_ERROR_BACKEND      /* a device or driver failure */
} rt_status;

/* A short name for a status ("parse error", ...). */
const char *rt_status_string(rt_status status);

/* The version of the library that runs, "MAJOR.MINOR.PATCH": the same as
 * RTCL_VERSION_STRING where the header and the library came together. */
const char *rt_version(void);

/* An error with the place it came from. line and column are 1-based; 0 means
 * not applicable. message holds the whole text, "file:line:column: reason". */
typedef struct rt_error {
    rt_status status;
    int line;
    int column;
    char file[512];
    char message[1024];
} rt_error;

typedef struct rt_scene rt_scene;

typedef struct rt_material {
    float color[3];
    float ambient;      /* coefficient on the scene's ambient light */
    float diffuse;      /* Lambert coefficient */
    float specular;     /* Phong coefficient */
    int shininess;      /* Phong exponent, an integer >= 0 */
    float reflectivity; /* 0..1: share of the mirror direction */
    float transparency; /* 0..1: share of the refracted direction */
    float ior;          /* index of refraction (> 0) */
    /* Light the surface gives off (each component in 0..1e6), added to its
     * Phong sum whatever the lights: MTL Ke, glTF emissive. Loaders also
     * make point lights of emissive surfaces where a scene has no lights
     * (docs/SCENE_FORMAT.md, "Emission"). */
    float emission[3];
} rt_material;

/* White, diffuse, ambient 1, no specular, reflection or refraction, ior 1,
 * no emission. */
rt_material rt_material_default(void);

typedef struct rt_camera {
    float position[3];
    float look_at[3]; /* the point the camera looks at */
    float up[3];
    float hfov_degrees; /* horizontal field of view, 0 < hfov < 180 */
    int width;
    int height;
} rt_camera;

/* ---- scene lifetime ---------------------------------------------------- */

rt_status rt_scene_create(rt_scene **out);
void rt_scene_destroy(rt_scene *scene);

/* Loads the scene file at path into a new scene *out: a .json scene or a
 * bare .obj (which gets the default camera, light and material, see
 * docs/SCENE_FORMAT.md; a JSON scene without a camera gets the default
 * camera and light too). The camera's resolution is the file's (1024x576
 * for a bare OBJ). On failure *out is NULL and err (which may be NULL)
 * describes the first problem, naming the file; nothing is half-loaded. */
rt_status rt_scene_load(const char *path, rt_scene **out, rt_error *err);

/* What rt_scene_load_with may do differently. Zero-initialised (or
 * rt_scene_load_options_default): rt_scene_load's behaviour. */
typedef struct rt_scene_load_options {
    /* 1: a scene that gets the default view (a bare OBJ, a JSON scene
     * without a camera) gets no default light: its lights are the file's
     * alone (none for a bare OBJ), for callers that add their own with
     * rt_light_add. The default camera and ambient are still given. */
    int no_default_light;
} rt_scene_load_options;

/* All zero: as rt_scene_load. */
rt_scene_load_options rt_scene_load_options_default(void);

/* rt_scene_load with options (NULL: the defaults). */
rt_status rt_scene_load_with(const char *path, const rt_scene_load_options *options, rt_scene **out,
                             rt_error *err);

/* The last error's message, "" when none. */
const char *rt_scene_error(const rt_scene *scene);

/* What loading the scene went past without failing (a material name an MTL
 * file defines twice: the first definition is used), one notice per line,
 * each naming the file and line; "" when none. For the caller to show: the
 * library never prints. */
const char *rt_scene_notices(const rt_scene *scene);

/* How many meshes and objects the scene holds (ids are 0 .. count - 1; the
 * meshes include the blend meshes it made for morphing objects); 0 for a
 * NULL scene. */
uint32_t rt_scene_mesh_count(const rt_scene *scene);
uint32_t rt_scene_object_count(const rt_scene *scene);

/* ---- meshes ------------------------------------------------------------ */

rt_status rt_mesh_create(rt_scene *scene, uint32_t *mesh_id);

/* Appends vertex_count vertices (positions: 3 floats each; normals: 3 floats
 * each or NULL) and triangle_count triangles whose indices (3 each) are
 * relative to the vertices appended by this call. A mesh has normals for all
 * its vertices or for none. */
rt_status rt_mesh_add_triangles(rt_scene *scene, uint32_t mesh_id, const float *positions,
                                const float *normals, uint32_t vertex_count,
                                const uint32_t *indices, uint32_t triangle_count);

/* ---- materials, lights, ambient, background ----------------------------- */

rt_status rt_material_add(rt_scene *scene, const rt_material *material, uint32_t *material_id);
/* Adds a point light at position (finite) with color (each component in
 * 0..1e6) and gives its id in *light_id. */
rt_status rt_light_add(rt_scene *scene, const float position[3], const float color[3],
                       uint32_t *light_id);

/* Moves light light_id to position and gives it color (rt_light_add's
 * rules). The next frame shows it there; a renderer rewrites only the
 * layout's per-frame part (the light count is the same). */
rt_status rt_light_set(rt_scene *scene, uint32_t light_id, const float position[3],
                       const float color[3]);

/* Light light_id's position and color; RT_ERROR_INVALID_ARGUMENT when there
 * is no such light. */
rt_status rt_light_get(const rt_scene *scene, uint32_t light_id, float position[3], float color[3]);

/* Removes light light_id; the lights after it move down one id (light_id
 * + 1 becomes light_id, ...), so the scene is the one built without it. A
 * scene may have no light (then only ambient light and the background
 * show). */
rt_status rt_light_remove(rt_scene *scene, uint32_t light_id);

/* The ambient light's colour (each component in 0..1e6), scaled by each
 * material's ambient coefficient. */
rt_status rt_scene_set_ambient(rt_scene *scene, const float color[3]);
/* The colour of rays that hit nothing (each component in 0..1e6). */
rt_status rt_scene_set_background(rt_scene *scene, const float color[3]);

/* Exposure in stops, -64..64 (0 when never set): rt_render multiplies the
 * shaded image by 2^ev after shading, on the host, so the image is the same
 * on every backend; AOVs are not scaled. Changing it rebuilds nothing. */
rt_status rt_scene_set_exposure(rt_scene *scene, float ev);
float rt_scene_exposure(const rt_scene *scene);

/* ---- objects ----------------------------------------------------------- */

/* Creates an object with material material_id, the identity transform and
 * no mesh yet (rt_object_add_mesh), and gives its id in *object_id. */
rt_status rt_object_create(rt_scene *scene, uint32_t material_id, uint32_t *object_id);

/* Removes object object_id (its keyframes, queued transforms, animation
 * and transform keys); the objects after it move down one id, so the scene
 * renders as the scene built without it, on every backend, and a renderer
 * that drew it before keeps its meshes' BVHs (meshes are not removed; a
 * blend mesh the scene made for the object is emptied and keeps its id). */
rt_status rt_object_remove(rt_scene *scene, uint32_t object_id);

/* Adds a keyframe. The first mesh added is selected. */
rt_status rt_object_add_mesh(rt_scene *scene, uint32_t object_id, uint32_t mesh_id);

/* Selects keyframe 'keyframe' (0-based, in the order meshes were added). */
rt_status rt_object_select_mesh(rt_scene *scene, uint32_t object_id, uint32_t keyframe);

/* Queues a rigid transform: at the next rt_scene_commit (which rt_render
 * calls) the object's matrix becomes matrix * current. Transforms queued
 * between two frames compose in the order they were queued. */
rt_status rt_object_transform(rt_scene *scene, uint32_t object_id, const float matrix[16]);

/* Sets the object's ray mask (0xffffffff for a new object). A ray of mask m
 * (rt_trace_options.ray_masks) skips the object when (m & mask) == 0, on
 * every backend, at the instance level of the traversal: the hits are those
 * of the scene without the objects it skips, bit for bit. Rendering traces
 * every ray (camera, shadow, reflection, refraction) with mask 0xffffffff,
 * so an object of mask 0 is invisible in renders (and casts no shadow). The
 * change reaches the backends with the next layout (rt_render or
 * rt_trace_rays), as any scene edit does. RT_ERROR_INVALID_ARGUMENT for an
 * object id out of range. */
rt_status rt_object_set_mask(rt_scene *scene, uint32_t object_id, uint32_t mask);

/* Applies queued transforms now. */
rt_status rt_scene_commit(rt_scene *scene);

/* ---- camera ------------------------------------------------------------ */

rt_status rt_camera_set(rt_scene *scene, const rt_camera *camera);
rt_status rt_camera_get(const rt_scene *scene, rt_camera *camera);

/* Moves eye and look-at point together, in the camera's frame:
 * right, up and forward distances. */
rt_status rt_camera_move(rt_scene *scene, float right, float up, float forward);

/* Turns the view direction: yaw about the camera's up vector, then pitch
 * about its right vector, in degrees. */
rt_status rt_camera_rotate(rt_scene *scene, float yaw_degrees, float pitch_degrees);

/* ---- rendering --------------------------------------------------------- */

typedef enum rt_aov {
    RT_AOV_NONE = 0,
    RT_AOV_DEPTH,  /* t of the primary hit (inf on a miss) */
    RT_AOV_PRIMID, /* triangle index (in file order) of the primary hit, -1 on a miss */
    RT_AOV_INSTID, /* object index of the primary hit, -1 on a miss */
    RT_AOV_NORMAL, /* world-space shading normal, 0 on a miss */
    RT_AOV_BOX_TESTS,
    RT_AOV_TRI_TESTS
} rt_aov;

typedef struct rt_framebuffer {
    int width;
    int height;
    int channels;  /* 3 for colour and normals, 1 for the other AOVs */
    float *pixels; /* row-major, top row first; the caller frees with free() */
} rt_framebuffer;

/* What one frame cost and did (the thesis's Table 6 figures). */
typedef struct rt_render_stats {
    double sah_cost;  /* of the mesh BVHs, triangle-weighted mean (Ct = 1, Ci = 2) */
    double build_ms;  /* host BVH builds done for this frame */
    double render_ms; /* tracing and shading */
    uint64_t rays;    /* all rays traced: primary, shadow, secondary */
    uint64_t primary_rays;
    uint64_t box_tests;        /* ray/box tests, all rays */
    uint64_t tri_tests;        /* ray/triangle tests, all rays */
    uint64_t packets;          /* primary packets traced (packet backend), else 0 */
    uint64_t packet_box_tests; /* box tests of whole vectors of a packet (and its
                                  interval tests, one per child), all packets */
    uint64_t packet_tri_tests; /* triangle tests of whole vectors, all packets */
    int packet_rays;           /* rays per packet */
    int packet_vector;         /* lanes per vector of the build that ran ... */
    const char *packet_isa;    /* ... and its instruction set */
    const char *backend;       /* the backend that ran */
    /* What ran the frame at once: the CPU backends' worker threads; opencl:
     * the device's compute units; vulkan: a CPU device's threads (lavapipe:
     * llvmpipe's), a GPU's invocations of the frame's largest dispatch. */
    int threads;
    /* Set when "auto" could not use the device and rendered on the CPU: the
     * reason, for the caller to show (the library never prints). */
    const char *notice;
    /* Device backends (opencl, vulkan); zero or empty on the CPU. */
    char device[128]; /* the device that ran */
    int exact;        /* the backend promises the CPU oracle's bits (0 with device_options); the
                         CPU backends always (they are the oracle, in the denormal mode asked for) */
    const char *math_profile; /* "native" or "portable" (device backends), "ieee" (CPU) */
    const char *denormals;    /* "preserve" or "flush" */
    char specialisation[192]; /* the -D feature switches of the kernels */
    char device_options[256]; /* the extra options the kernels were built with ("": none) */
    double compile_ms;        /* kernel program builds done for this frame */
    double upload_ms;         /* host-to-device copies */
    uint64_t upload_bytes;    /* bytes copied to the device for this frame */
    double download_ms;       /* device-to-host copies */
    double kernel_ms[3];      /* summed OpenCL profiling times: camera, trace, shade */
    uint32_t launches;        /* kernel launches (tiles x kernels) */
    uint32_t tile_pixels;     /* the largest tile launched */
    uint32_t wave_tiles;      /* tiles shaded as wavefront passes (secondary rays) */
    uint32_t wave_fallbacks;  /* of those, redone with rt_k_shade (a queue overflowed) */
    /* Which kernels rendered: "packet 4x4" (CPU devices: a block of rays per
     * work-item, kernels/rt_ray_packet.cl) or "one ray per work-item". */
    char kernels[48];
} rt_render_stats;

/* ---- the renderer ------------------------------------------------------ */

typedef struct rt_renderer rt_renderer;

/* Kernel choices of the OpenCL backend, for tests and comparisons (all give
 * the same bits; docs/OPENCL.md). Zero-initialised: the defaults. */
typedef struct rt_opencl_tuning {
    /* 0: a CPU device traces blocks of rays per work-item (rt_k_packet), other
     * devices one ray per work-item; 1: one ray per work-item everywhere. */
    int one_ray_kernels;
    int packet_lanes; /* 0: 16 (4x4 blocks); 4 (2x2) or 8 (4x2) */
    /* 0: images with reflection or refraction are shaded as wavefront passes
     * on one-ray devices; 1: every image through rt_k_shade's stack. */
    int no_wavefront;
    /* 0: the wavefront's queues are sized to the tile; N > 0: at most N rays
     * (a smaller queue overflows sooner: the overflow path is tested so). */
    uint32_t wave_queue_cap;
} rt_opencl_tuning;

/* How a device divides and takes square roots (docs/PORTABLE_MATH.md). Both
 * profiles give the CPU oracle's bits where the device qualifies:
 * native needs correctly rounded fp32 divide/sqrt from the device;
 * portable computes them in software from 32-bit integer operations and
 * needs nothing beyond correctly rounded + - * (every conforming device). */
typedef enum rt_device_math {
    RT_DEVICE_MATH_AUTO = 0, /* native where the device promises correctly rounded
                                divide/sqrt, else portable */
    RT_DEVICE_MATH_NATIVE,
    RT_DEVICE_MATH_PORTABLE
} rt_device_math;

/* Denormal policy of every backend (docs/PORTABLE_MATH.md). */
typedef enum rt_denormals {
    RT_DENORMALS_PRESERVE = 0, /* IEEE gradual underflow (the CPU's default) */
    /* Flush results to zero and read denormal inputs as zero, as most GPUs
     * do: the CPU backends set FTZ/DAZ (x86 MXCSR) or FZ (AArch64 FPCR) on
     * their threads; kernels are built with -cl-denorms-are-zero and the
     * software division and sqrt flush too. Compare a flushing device with
     * a flushing oracle. */
    RT_DENORMALS_FLUSH
} rt_denormals;

typedef struct rt_renderer_options {
    /* "cpu" (the scalar oracle, the default), "packet" (the SIMD packet
     * tracer), "opencl" or "vulkan" (or "opencl:DEVICE", "vulkan:DEVICE", a
     * device index or a part of its name), "auto" (a device backend when one
     * is built and a device exists, else cpu, with rt_render_stats.notice
     * saying why). NULL: "cpu". */
    const char *backend;
    int threads; /* worker threads of the CPU backends and builders; <= 0: all cores */
    /* Extra OpenCL C compiler options for the speed-versus-error study
     * ("-cl-mad-enable", "-cl-fast-relaxed-math", "-DRT_NATIVE_MATH", ...),
     * appended to the program's build options. They may change results: with
     * any set, stats->exact is 0. NULL or "": the exact build. At most 255
     * characters. Ignored by the CPU backends. */
    const char *device_options;
    /* The packet backend's instruction set: NULL or "" for the widest the CPU
     * runs, else "generic", "avx2" or "avx512" (x86-64); one the build or CPU
     * lacks is RT_ERROR_UNSUPPORTED. All give the same bits. */
    const char *packet_isa;
    rt_opencl_tuning opencl;
    rt_device_math device_math; /* device backends; the CPU is IEEE, the oracle */
    rt_denormals denormals;     /* every backend */
    /* Called by the opencl backend just before it compiles its kernels from
     * source because the on-disk kernel cache (README, "Kernel cache") holds
     * no binary for them: the first run on a device or driver, a new
     * version of this library, a new scene specialisation, or the cache off
     * (RTCL_CACHE_DIR=off). Not called when a cached binary is used.
     * backend is "opencl", device the device's name, cache_dir the folder
     * the result will be kept in (NULL when the cache is off or its folder
     * unusable). Called on the rendering thread before the compiler starts,
     * so a caller can say that the wait is a one-time compile (rtcl prints
     * one line when stderr is a terminal); the library itself never prints.
     * NULL: not called. */
    void (*on_compile)(void *user, const char *backend, const char *device, const char *cache_dir);
    void *on_compile_user;
} rt_renderer_options;

/* cpu, all cores, no device options. */
rt_renderer_options rt_renderer_options_default(void);

/* Creates a renderer. An unknown backend, or one this build or machine lacks,
 * is RT_ERROR_UNSUPPORTED with the reason in err (err may be NULL); *out is
 * then NULL. Devices are opened at the first frame. */
rt_status rt_renderer_create(const rt_renderer_options *options, rt_renderer **out, rt_error *err);
void rt_renderer_destroy(rt_renderer *renderer);

/* The last error's message, "" when none. */
const char *rt_renderer_error(const rt_renderer *renderer);

/* Switches to another backend ("cpu", "packet", "opencl[:DEVICE]",
 * "vulkan[:DEVICE]", "auto")
 * for the next frames. The BVHs and the layout are kept; so is the state of
 * a device backend used before (switching back does not recompile). On
 * failure the renderer keeps its backend. */
rt_status rt_renderer_set_backend(rt_renderer *renderer, const char *backend);

/* The backend that renders now ("cpu", "packet", "opencl", "vulkan"). */
const char *rt_renderer_backend(const rt_renderer *renderer);

/* The device compiler's messages from the current backend's last kernel
 * build: the build log, then anything the driver printed on stderr during
 * the build (the library captures that rather than let it reach the
 * terminal). "" when there was none or the backend compiles nothing. Valid
 * until the next call on the renderer. For callers that show it on request
 * (rtcl --verbose); a failed build's error message includes it already. */
const char *rt_renderer_build_log(const rt_renderer *renderer);

/* Ray/triangle tests (rt_render_options.tri_test). Watertight is the default;
 * the others exist for the speed-versus-error study (docs/ROBUSTNESS.md). */
typedef enum rt_triangle_test {
    RT_TRI_TEST_WATERTIGHT = 0, /* Woop, Benthin, Wald 2013 */
    RT_TRI_TEST_MOLLER,         /* Moller-Trumbore 1997 */
    RT_TRI_TEST_PLUECKER,       /* signed volumes (Pluecker coordinates) */
    RT_TRI_TEST_BADOUEL         /* plane hit, then a 2D test (Badouel; Wald) */
} rt_triangle_test;

/* What one frame asks for. */
typedef struct rt_render_options {
    rt_render_stats *stats; /* filled when not NULL */
    rt_aov aov;             /* RT_AOV_NONE: the shaded image */
    /* Progress in [0, 1] for long renders; may be NULL. */
    void (*progress)(void *user, double done);
    void *progress_user;
    rt_triangle_test tri_test; /* RT_TRI_TEST_WATERTIGHT (0) unless set */
    /* 1: primary and shadow rays only, no reflection or refraction rays (the
     * thesis's benchmark set-up: one light, Phong, shadows). 0: Whitted. */
    int direct_only;
    /* 1: *fb holds a framebuffer of an earlier rt_render (or pixels NULL),
     * and when its size and channels match, its memory is reused, so that
     * a frame loop touches no fresh pages (every pixel is written anew). 0:
     * *fb is overwritten, as a new framebuffer. */
    int reuse_framebuffer;
    /* Samples per pixel of the shaded image: 0 or 1, one ray through each
     * pixel's centre; N > 1, N passes, each with every primary ray moved to
     * the same point of its pixel (stratified: a k x k grid when N = k * k,
     * else N columns of the pixel with rows by the base-2 radical inverse),
     * summed in pass order and divided by N. Each pass is the oracle's frame
     * on every backend, and so the mean is the same bits everywhere. At most
     * RT_MAX_SAMPLES; AOVs refuse N > 1. */
    int samples;
} rt_render_options;

/* The most samples per pixel rt_render takes. */
#define RT_MAX_SAMPLES 4096

/* The shaded image, Whitted, watertight test, no statistics. */
rt_render_options rt_render_options_default(void);

/* Renders one frame of scene (the camera's resolution) into fb, after
 * applying its queued transforms; BVHs of meshes that changed are rebuilt,
 * the rest reused. options NULL: the defaults. */
rt_status rt_render(rt_renderer *renderer, rt_scene *scene, const rt_render_options *options,
                    rt_framebuffer *fb);

void rt_framebuffer_free(rt_framebuffer *fb);

/* ---- ray queries ---------------------------------------------------------- */

/* A ray o + t d for t in [tmin, tmax] (inclusive). d need not be normalised;
 * t is in units of its length. */
#ifndef RT_RAY_DEFINED /* kernels/rt_ray.h defines the same type */
#define RT_RAY_DEFINED
typedef struct rt_ray {
    float org[3];
    float dir[3];
    float tmin;
    float tmax;
} rt_ray;
#endif

/* The closest hit (smaller t wins; equal t: lower inst, then lower prim) or,
 * for any-hit queries, some hit in range. p = (1 - u - v) v0 + u v1 + v v2.
 * A miss: hit 0, t inf, u = v = 0, prim = inst = mesh = UINT32_MAX, normal 0.
 *
 * normal is the hit triangle's geometric normal in world space, unit length,
 * on the side of the triangle's winding (v0, v1, v2 counter-clockwise seen
 * from where it points), whichever side the ray came from. rt_trace_rays
 * computes it on the host after any backend's trace, from the scene's vertices
 * and the layout's inverse instance matrix, so every backend gives the same
 * bits. In double precision, each step rounded once, in this order:
 *   e1 = v1 - v0, e2 = v2 - v0 (componentwise);
 *   n = e1 x e2: n.x = e1.y e2.z - e1.z e2.y, n.y = e1.z e2.x - e1.x e2.z,
 *                n.z = e1.x e2.y - e1.y e2.x;
 *   an object that is not the identity: n'_j = (W_0j n.x + W_1j n.y) + W_2j n.z
 *     with W the 3x3 part of the inverse object-to-world matrix (normals
 *     transform by its transpose, so a scaled or mirrored object keeps its
 *     normals on the surface's side);
 *   m = max(|n.x|, |n.y|, |n.z|); n = n / m (componentwise); n = n / sqrt(n.n);
 *   each component rounded to float.
 * Scaling by m first keeps huge and tiny triangles from overflowing or
 * underflowing. mesh is the scene mesh the object shows (its selected
 * keyframe, or the blend mesh the scene made for a morphing object). An
 * any-hit answer has the normal and mesh of the triangle it names; the
 * packet backend's packets name none (inst UINT32_MAX): normal 0, mesh
 * UINT32_MAX. */
typedef struct rt_hit {
    float t, u, v;
    uint32_t prim; /* 0-based triangle index in the mesh's file order */
    uint32_t inst; /* object index */
    int hit;
    float normal[3]; /* unit geometric normal in world space (see above) */
    uint32_t mesh;   /* the scene mesh id of the hit triangle */
    /* The ray's id (rt_trace_options.ray_ids[i], or i when NULL), for every
     * ray, hit or miss; the host sets it after any backend's trace. */
    uint32_t ray_id;
} rt_hit;

/* What one rt_trace_rays call did (rt_trace_options.stats). */
typedef struct rt_trace_stats {
    double trace_ms;      /* the backend's tracing alone: not the copies of rays and hits
                             into and out of the library, not BVH builds */
    double build_ms;      /* host builds this call needed (the backends' wide BVHs) */
    uint64_t rays;        /* rays traced */
    uint64_t packet_rays; /* of them, traced in packets (packet backend: coherent groups) */
    uint64_t single_rays; /* of them, one at a time through wide BVHs (packet backend:
                             incoherent groups, cpu_ref/single_trace.h) */
    const char *backend;  /* the backend that traced */
    const char *isa;      /* the packet backend's instruction set, else "" */
    char device[128];     /* the device that traced (opencl, vulkan), else "" */
    /* Set when "auto" could not use a device and traced on the CPU: the
     * reason (rt_render_stats.notice's), else NULL. */
    const char *notice;
} rt_trace_stats;

/* How the packet backend traces a query's rays. AUTO: each group of 64
 * consecutive rays that is coherent (one direction sign per axis, close
 * directions and origins: cpu_ref/ray_coherence.h) as a packet, the others
 * one at a time through wide BVHs. PACKETS and SINGLE force one path (for
 * tests and measurements). Every path gives the same hits. */
typedef enum rt_trace_path {
    RT_TRACE_PATH_AUTO = 0,
    RT_TRACE_PATH_PACKETS,
    RT_TRACE_PATH_SINGLE
} rt_trace_path;

typedef struct rt_trace_options {
    int any_hit;               /* 1: any hit in range (occlusion), 0: the closest */
    rt_triangle_test tri_test; /* RT_TRI_TEST_WATERTIGHT (0) unless set */
    rt_trace_stats *stats;     /* filled when not NULL */
    rt_trace_path packet_path; /* the packet backend's path [auto] */
    /* Per ray, its mask: ray i skips every object whose mask
     * (rt_object_set_mask) has no bit in common with ray_masks[i]. NULL:
     * every ray's mask is 0xffffffff. */
    const uint32_t *ray_masks;
    /* Per ray, the id its hit reports (rt_hit.ray_id). NULL: ray i's id is
     * i (its index in the call). */
    const uint32_t *ray_ids;
} rt_trace_options;

/* Traces count rays through scene (after applying its queued transforms) on
 * the renderer's backend; every backend gives identical closest hits. A ray
 * with a NaN or infinite component, or a zero direction, is a miss. options
 * NULL: closest hits, watertight test. */
rt_status rt_trace_rays(rt_renderer *renderer, rt_scene *scene, const rt_ray *rays, size_t count,
                        rt_hit *hits, const rt_trace_options *options);

/* Counts, per ray, the triangles it crosses for t in [tmin, tmax]
 * (inclusive), each triangle once (a triangle a kd-tree keeps in several
 * leaves too), into counts[i]: the basis of inside/outside tests (an odd
 * count from a point to infinity: inside a closed mesh). A crossing is a
 * hit of the watertight test that rt_trace_rays would accept (its default
 * test and its acceptance rule), with one more rule where the ray passes
 * exactly through an edge or a vertex (an edge
 * function exactly zero, after the test's exact re-check): there the ray
 * counts as if it were moved by an infinitesimal (e, e*e) in the test's
 * sheared 2D frame, so that of the triangles around a shared edge or vertex
 * that the ray crosses exactly one counts, and a ray that only touches a
 * mesh's silhouette edge or vertex counts 0 or 2 crossings there. Grazing
 * rays in a triangle's plane cross nothing. A closed mesh's inside/outside
 * parity is then exact for every ray whose crossings' t (a few ulps) lie
 * clear of tmin and tmax, with denormals preserved (RT_DENORMALS_PRESERVE;
 * flushing may lose a crossing of edges shorter than the smallest normal
 * float) and coordinates whose products neither overflow nor underflow.
 * Runs on the CPU, the scalar oracle's code on the renderer's threads,
 * whatever the renderer's backend. A ray with a NaN or infinite component,
 * or a zero direction, counts 0. */
rt_status rt_count_intersections(rt_renderer *renderer, rt_scene *scene, const rt_ray *rays,
                                 size_t count, uint32_t *counts);

/* ---- acceleration structure per mesh ------------------------------------ */

/* The structure a renderer builds for a mesh: a BVH (the default), or an SAH
 * kd-tree built exactly (Wald and Havran 2006) or by binning. Every choice
 * gives identical hits and images; it changes build time, memory and
 * tracing speed. Meant for static meshes: a kd-tree is rebuilt whole when its
 * mesh changes, and a deforming mesh (rt_mesh_set_positions, an update
 * policy other than RT_UPDATE_SAH) has a BVH whatever was set. */
typedef enum rt_accel {
    RT_ACCEL_BVH = 0,
    RT_ACCEL_KD = 1,       /* exact SAH kd-tree */
    RT_ACCEL_KD_BINNED = 2 /* binned SAH kd-tree */
} rt_accel;

/* Sets mesh_id's structure (the next frame builds it). */
rt_status rt_mesh_set_accel(rt_scene *scene, uint32_t mesh_id, rt_accel accel);

/* Sets the structure of every static mesh: every mesh that is no keyframe
 * of an object with several, no blend mesh of one, and whose update policy
 * is RT_UPDATE_SAH (deforming meshes keep theirs, a BVH unless set). */
rt_status rt_scene_set_static_accel(rt_scene *scene, rt_accel accel);

/* mesh_id's structure, RT_ACCEL_BVH for a mesh that does not exist or
 * whose update policy is not RT_UPDATE_SAH. */
rt_accel rt_mesh_accel(const rt_scene *scene, uint32_t mesh_id);

/* "bvh", "kd", "kd-binned"; rt_accel_parse gives 0 for an unknown name. */
const char *rt_accel_name(rt_accel accel);
int rt_accel_parse(const char *name, rt_accel *accel);
/* ---- dynamic scenes: deforming meshes, update policies, time ------------ */

/* How a renderer brings a mesh's BVH up to date after its vertices moved
 * (rt_mesh_set_positions). Every policy gives the same hits (closest hits
 * have a total order); they differ in update time and tree quality. The two
 * policies that build are named for their builder, the same name `rtcl
 * bench` gives that builder's rows. */
typedef enum rt_update_policy {
    RT_UPDATE_SAH = 0, /* "sah": a fresh binned SAH build (the default) */
    RT_UPDATE_REFIT,   /* "refit": keep the tree, recompute its boxes bottom-up */
    RT_UPDATE_LBVH,    /* "lbvh": a Morton-code LBVH build: fastest build, lower quality */
    RT_UPDATE_AUTO     /* "auto": refit while the refitted tree's SAH cost stays within
                          RT_UPDATE_AUTO_BOUND of the last SAH build's, else an SAH build */
} rt_update_policy;
/* The names before 0.2, kept for source compatibility. */
#define RT_UPDATE_REBUILD RT_UPDATE_SAH
#define RT_UPDATE_FAST    RT_UPDATE_LBVH

/* The SAH cost ratio (refitted / last rebuild) above which "auto" rebuilds.
 * Measured (docs/BENCHMARKS.md, "Dynamic scenes"): refitting stops paying
 * where the refitted tree's extra traversal costs what a rebuild saves; on
 * the brainstem animation (61,666 triangles, packet backend, 1024x576, 2
 * threads) that is at an SAH ratio of 1.53. Small meshes break even sooner
 * (robot walk, 3,237 triangles: 1.02) but there a rebuild saves under 1 ms,
 * so the bound follows the large meshes, whose rebuilds matter. */
#define RT_UPDATE_AUTO_BOUND 1.5

/* "sah", "refit", "lbvh", "auto"; and back (returns 0 for an unknown name).
 * The parser also takes the names before 0.2: "rebuild" (sah) and "fast"
 * (lbvh). */
const char *rt_update_policy_name(rt_update_policy policy);
int rt_update_policy_parse(const char *name, rt_update_policy *out);

/* Replaces the positions (3 floats each) of all vertex_count vertices of a
 * mesh, and its normals when normals is not NULL (only for a mesh that has
 * normals). vertex_count must equal the mesh's; the triangles stay. The
 * mesh's version is bumped, so renderers update its BVH by its policy; a
 * kd-tree mesh becomes a BVH mesh (RT_ACCEL_BVH: it deforms). */
rt_status rt_mesh_set_positions(rt_scene *scene, uint32_t mesh_id, const float *positions,
                                const float *normals, uint32_t vertex_count);

/* The mesh's update policy (RT_UPDATE_SAH until set). Any other policy
 * gives the mesh a BVH, whatever its rt_accel says. */
rt_status rt_mesh_set_update(rt_scene *scene, uint32_t mesh_id, rt_update_policy policy);

/* Keyframe animation of an object: keyframe i is shown at time i / rate
 * seconds, looping (rate > 0). With interpolate, positions (and normals) are
 * blended linearly between consecutive keyframes of the same topology (the
 * last blends into the first); the blend lives in a mesh the scene adds for
 * the object (it takes the update policy of the object's first keyframe).
 * Keyframes of different topologies switch. Takes effect at rt_scene_set_time. */
rt_status rt_object_set_animation(rt_scene *scene, uint32_t object_id, float keyframe_rate,
                                  int interpolate);

/* A key of an object's animated transform: M = translate * rotate * scale. */
typedef struct rt_transform_key {
    double time; /* seconds; keys strictly increasing in time */
    float translate[3];
    float axis[3]; /* rotation axis (not zero; any length) */
    float degrees;
    float scale; /* uniform scale, > 0 */
} rt_transform_key;

/* The object's transform follows the keys (copied): translation and scale
 * blended linearly, rotations along the shortest arc (quaternion slerp);
 * before the first key the first holds, after the last the last. The keyed
 * transform replaces the object's transform at rt_scene_set_time. count 0
 * removes the keys. */
rt_status rt_object_set_transform_keys(rt_scene *scene, uint32_t object_id,
                                       const rt_transform_key *keys, uint32_t count);

/* A key of the camera's path. */
typedef struct rt_camera_key {
    double time; /* seconds; keys strictly increasing in time */
    float position[3];
    float look_at[3];
} rt_camera_key;

/* The camera's eye and look-at point follow the keys (copied), blended
 * linearly, held before the first and after the last; up, fov and size stay
 * the camera's. count 0 removes the path. */
rt_status rt_camera_set_path(rt_scene *scene, const rt_camera_key *keys, uint32_t count);

/* Sets the scene's time in seconds (finite): selects or blends keyframes,
 * places keyed objects and the camera. What did not change is not touched,
 * so a renderer redoes only what moved. A scene without animation stays as
 * it is. Loading a scene file sets time 0. */
rt_status rt_scene_set_time(rt_scene *scene, double seconds);

/* The threads of the scene's own per-frame work at rt_scene_set_time (a
 * glTF file's instances posed, skinned and morphed, one mesh per job; the
 * vertices are the same whatever the count): <= 0, the default, one per
 * core; 1: the caller's thread only. The threads are made when first
 * needed and kept until the scene is destroyed or the count changes. */
rt_status rt_scene_set_threads(rt_scene *scene, int threads);

/* 1 when some object or the camera is animated (rt_scene_set_time changes
 * something), else 0. */
int rt_scene_is_animated(const rt_scene *scene);

/* Animation clips of a scene file that has several (a glTF file's
 * animations; 0 for other scenes). A glTF scene plays clip 0 unless another
 * is selected. */
uint32_t rt_scene_clip_count(const rt_scene *scene);
/* Clip index's name ("" when unnamed) and duration in seconds (its last
 * key time); the name lives as long as the scene. */
rt_status rt_scene_clip_info(const rt_scene *scene, uint32_t index, const char **name,
                             double *duration);
/* The clip being played (0 when there are none). */
uint32_t rt_scene_selected_clip(const rt_scene *scene);
/* Plays the clip named clip, or else of that decimal index, from now on:
 * the scene at its current time is evaluated again. Fails, listing the
 * clips, when there is none such. */
rt_status rt_scene_select_clip(rt_scene *scene, const char *clip);

/* What the last rt_render or rt_trace_rays did to bring the scene's
 * acceleration structures up to date, per mesh that it touched. */
typedef enum rt_update_action {
    RT_ACTION_NONE = 0,
    RT_ACTION_BUILD,  /* SAH build */
    RT_ACTION_REFIT,  /* boxes recomputed */
    RT_ACTION_LBVH,   /* LBVH build */
    RT_ACTION_REBUILD /* "auto": refitted, found worse than the bound, rebuilt */
} rt_update_action;

typedef struct rt_mesh_update {
    uint32_t mesh;
    rt_update_action action;
    double ms;  /* time of the update */
    double sah; /* the tree's SAH cost after it */
} rt_mesh_update;

typedef struct rt_update_stats {
    const rt_mesh_update *meshes; /* valid until the renderer's next frame */
    uint32_t mesh_count;
    double object_bvh_ms;  /* the object BVH */
    double layout_ms;      /* the flattened layout (whole or in place) */
    int layout_in_place;   /* 1: only changed ranges were rewritten */
    uint64_t layout_bytes; /* bytes of the layout rewritten */
    int camera_only;       /* 1: only the camera changed: the header alone was rewritten */
} rt_update_stats;

/* The renderer's last update (after rt_render or rt_trace_rays). */
rt_status rt_renderer_update_stats(const rt_renderer *renderer, rt_update_stats *out);

/* Memory held, in bytes, by part (docs/BENCHMARKS.md, "Memory per
 * triangle"): what the scene holds and what a renderer keeps between frames
 * for it. Counted from the arrays' sizes (not allocator overhead). */
typedef struct rt_memory_stats {
    uint64_t scene;      /* the scene's meshes: positions, normals, indices, per-triangle
                            materials */
    uint64_t mesh_bvhs;  /* the renderer's per-mesh BVHs (nodes, primitive indices) and kd-trees */
    uint64_t object_bvh; /* the object BVH */
    uint64_t kept;       /* kept for the next frame's updates: refit records, build scratch */
    uint64_t layout;     /* the flattened layout every backend reads */
    uint64_t backend;    /* the current backend's own host copies (packet: its wide BVHs) */
    uint64_t device;     /* device memory the current backend holds (opencl, vulkan) */
    uint64_t triangles;  /* triangles of the meshes the layout holds, for bytes per triangle */
} rt_memory_stats;

/* The memory of scene and of renderer's structures for it (as the last
 * rt_render or rt_trace_rays left them; zero for a scene the renderer has
 * not drawn). */
rt_status rt_renderer_memory(const rt_renderer *renderer, const rt_scene *scene,
                             rt_memory_stats *out);

/* ---- for programs on the library (rtcl is one): scenes by name, saving,
 * describing, images, ray files, the backends and their devices ---------- */

/* Opens a scene: source "builtin:NAME" builds the built-in scene NAME
 * (rt_scene_builtin), anything else is a file for rt_scene_load. On failure
 * *out is NULL and err says why. */
rt_status rt_scene_open(const char *source, rt_scene **out, rt_error *err);

/* Builds the built-in scene called name (rt_builtin_scene_name) into a new
 * scene; an unknown name is RT_ERROR_INVALID_ARGUMENT naming the known ones. */
rt_status rt_scene_builtin(const char *name, rt_scene **out, rt_error *err);

/* The name of built-in scene index (0, 1, ...: "cornell", "keyframes"), NULL
 * past the last. */
const char *rt_builtin_scene_name(int index);

/* Writes dir/name.json and dir/name_MESH.obj for each mesh (dir must exist).
 * MESH is the mesh's name when every mesh has a plain name (letters, digits,
 * '_', '-', '.', not starting with '.') and no two are alike, else
 * mesh_INDEX for every mesh. Floats are written with %.9g so that loading
 * the files gives the same bits. Meshes with per-triangle materials are
 * RT_ERROR_UNSUPPORTED. Everything the JSON reader reads about time is
 * written: objects' "animation" and "transform_keys", the camera's "path",
 * meshes' "update" and "accel"; the blend meshes of morphing objects are
 * left out (the loader makes them again), so that the saved scene renders at
 * every time as the scene does. Each file is written whole or not at all
 * (a temporary beside it, renamed once complete: an existing file is never
 * left cut short), the OBJ files first and the JSON file, which names them,
 * last; a scene that cannot be saved (per-triangle materials, a path too
 * long) is refused before any file is written. */
rt_status rt_scene_save_json(const rt_scene *scene, const char *dir, const char *name,
                             rt_error *err);

/* Whether rt_scene_save_json could write into dir, checked before the work
 * that makes the scene: dir is an existing, writable folder and
 * dir/name.json fits a path. RT_OK, or RT_ERROR_IO naming the fault and the
 * folder. Nothing is created. */
rt_status rt_scene_save_check(const char *dir, const char *name, rt_error *err);

/* What a scene holds (rt_scene_describe). */
typedef struct rt_scene_info {
    uint32_t meshes, objects, materials, lights;
    uint64_t triangles;     /* in the current frame: the mesh each object shows */
    uint64_t all_triangles; /* in all meshes */
    /* Features the backends specialise to. */
    int reflection;    /* some material has reflectivity > 0 */
    int refraction;    /* some material has transparency > 0 */
    int instancing;    /* more than one object, or a transform other than identity */
    int normals;       /* some mesh has vertex normals */
    int keyframes;     /* some object has more than one mesh */
    int tri_materials; /* some mesh has per-triangle materials */
    /* Time (rt_scene_is_animated is animated). */
    int animated;
    uint32_t switched_objects; /* objects whose keyframes switch with time */
    uint32_t blended_objects;  /* objects whose keyframes blend */
    uint32_t keyed_objects;    /* objects with transform keys */
    uint32_t camera_path_keys; /* keys of the camera's path, 0: none */
} rt_scene_info;

/* Fills *out with what scene holds now (a few operations per mesh, object
 * and material: cheap enough for every frame). */
rt_status rt_scene_describe(const rt_scene *scene, rt_scene_info *out);

/* The world-space box of the triangles shown in the current frame (the
 * vertices their triangles use, through each object's transform): 1, or 0
 * for a scene without triangles (bmin/bmax then +inf/-inf). It reads every
 * triangle. */
int rt_scene_bounds(const rt_scene *scene, float bmin[3], float bmax[3]);

/* One mesh (rt_mesh_describe). */
typedef struct rt_mesh_info {
    const char *name; /* where it came from (a file name) or "": valid while the scene lives */
    uint32_t triangles, vertices;
    int normals;             /* 1: it has vertex normals */
    rt_update_policy update; /* rt_mesh_set_update's, RT_UPDATE_REBUILD until set */
    rt_accel accel;          /* the structure a renderer builds for it (rt_mesh_accel) */
} rt_mesh_info;

/* Fills *out for mesh_id (RT_ERROR_INVALID_ARGUMENT for an id out of range). */
rt_status rt_mesh_describe(const rt_scene *scene, uint32_t mesh_id, rt_mesh_info *out);

/* One object (rt_object_describe). */
typedef struct rt_object_info {
    uint32_t keyframes;      /* meshes added (rt_object_add_mesh) */
    uint32_t selected;       /* the keyframe shown now (0-based) */
    uint32_t material;       /* the object's material id */
    float keyframe_rate;     /* rt_object_set_animation's, 0 when none */
    int interpolate;         /* keyframes blend (rt_object_set_animation) */
    int morphing;            /* 1: a blend of two keyframes is shown now */
    uint32_t transform_keys; /* rt_object_set_transform_keys' count */
    uint32_t mask;           /* rt_object_set_mask's, 0xffffffff unless set */
} rt_object_info;

/* Fills *out for object_id (RT_ERROR_INVALID_ARGUMENT for an id out of range). */
rt_status rt_object_describe(const rt_scene *scene, uint32_t object_id, rt_object_info *out);

/* An image in memory: floats, row-major, top row first, channels interleaved. */
typedef struct rt_image {
    int width;
    int height;
    int channels;
    float *pixels;
} rt_image;

/* An image format rt_image_write writes (one row of the library's table,
 * formats/image_formats.def). */
typedef struct rt_image_format {
    const char *extension; /* ".png": lower case, matched case-insensitively */
    const char *name;      /* "PNG" */
    int bits;              /* per channel: 8 or 16 (levels of [0,1], clamped, rounded to nearest,
                              NaN as 0) or 32 (float, linear) */
    int lossy;             /* 1: the encoding loses more than that rounding (JPEG, WebP, HDR) */
    int module;            /* 1: written through the image module (OpenImageIO); 0: in C */
} rt_image_format;

/* The index-th format (0, 1, ...), NULL past the last. */
const rt_image_format *rt_image_format_at(int index);

/* The format of path's extension (of the file name, not a folder), NULL
 * when it names none. */
const rt_image_format *rt_image_format_of(const char *path);

/* Every format's extension, ".png, .jpg, ..., .pfm", in the table's order:
 * the list the errors of an unknown extension give. */
const char *rt_image_format_list(void);

/* Writes pixels in the format of the file's extension (rt_image_format_of:
 * .png, .jpg, .tif, .exr, .hdr, .ppm, .pfm and the others of
 * rt_image_format_list), at its bits per channel. err names the file on
 * failure. Any other extension is RT_ERROR_UNSUPPORTED, as is a .ppm or .pfm
 * with other than 1 (written as grey, P5 or Pf) or 3 channels, or a channel
 * count the format cannot hold. An alpha channel is stored as given, never
 * premultiplied. A file that cannot be created or written in full is
 * RT_ERROR_IO with the system's reason. The formats written through the
 * image module (librtcl_image.so, OpenImageIO: all but PPM, PGM and PFM)
 * need it: without it they are RT_ERROR_UNSUPPORTED saying so. The file is written whole or not at
 * all (a temporary beside it, flushed and renamed once complete): on any failure an existing file
 * at path is left as it was. No time stamp or other varying field is written, so equal pixels give
 * equal files. */
rt_status rt_image_write(const char *path, const rt_image *image, rt_error *err);

/* What rt_image_write_with may add to a file. */
typedef struct rt_image_write_options {
    /* 1: PNG and EXR files record when they were written (EXR capDate, PNG
     * time) and the software ("rtcl"), so two writes of one image differ;
     * DPX records the time and the file's name too; PPM and PFM have no
     * place for either. 0 (the default): none of these, so equal pixels give
     * equal files under any name. */
    int metadata;
} rt_image_write_options;

/* rt_image_write with options (NULL: the defaults). */
rt_status rt_image_write_with(const char *path, const rt_image *image,
                              const rt_image_write_options *options, rt_error *err);

/* Whether rt_image_write could write path, checked before the work that
 * makes the image: a known extension, the image module for its formats, a
 * folder that exists and is writable, a path that is no folder. RT_OK or
 * rt_image_write's error for that fault. Nothing is created. */
rt_status rt_image_check_output(const char *path, rt_error *err);

/* Reads an image as floats in [0,1] for 8-bit files; the format is told by
 * the file's first bytes (PPM/PGM and PFM in the library, anything else
 * through the image module). The caller frees with rt_image_free. 8- and
 * 16-bit levels k read as exactly k / 255.0f and k / 65535.0f, so an 8-bit
 * file written from such values reads back bit-identical. Subimage 0 only,
 * all its channels. A file that cannot be opened is RT_ERROR_IO; one that is
 * not an image or is damaged or cut short is RT_ERROR_PARSE
 * (RT_ERROR_UNSUPPORTED for deep images, and for images of more than
 * 32768 x 32768 pixels or 16 channels: refused from the header, before any
 * pixel memory is taken). On failure *out is zeroed. */
rt_status rt_image_read(const char *path, rt_image *out, rt_error *err);

void rt_image_free(rt_image *image);

/* How far two images are apart (rt_image_compare). */
typedef struct rt_image_diff {
    double max_abs;     /* largest absolute channel difference */
    double rmse;        /* over all channels */
    double psnr;        /* dB, against a peak of 1; INFINITY when identical */
    uint64_t differing; /* pixels with any channel different */
    uint64_t pixels;
    int first_x, first_y; /* first differing pixel in row order, -1 if none */
} rt_image_diff;

/* Compares a and b (same size and channel count, else RT_ERROR_INVALID_ARGUMENT).
 * If diff_out is not NULL it receives |a - b| per channel (caller frees with
 * rt_image_free; zeroed on failure). Equal values, infinities included,
 * differ by 0; NaN against NaN counts as equal, NaN against a number as an
 * infinite difference, so a NaN in one image never passes as a match. */
rt_status rt_image_compare(const rt_image *a, const rt_image *b, rt_image_diff *result,
                           rt_image *diff_out, rt_error *err);

/* Reads a ray file (a regular text file of at most 4 GiB): one ray per line,
 * "ox oy oz dx dy dz tmin tmax", plus "nx ny nz" when with_normals (the
 * origin is then a surface point with that normal and is moved off the
 * surface with the engine's offset, to the side the direction points to).
 * Blank lines and lines starting with '#' are skipped. The file is read a
 * chunk at a time: memory is the rays and one line (of at most 1 MiB, else
 * RT_ERROR_UNSUPPORTED with file:line), and a NUL byte fails the file at
 * its line before the rest is read. On success *rays (to free(), NULL when
 * there are none) holds *count rays; on failure *rays is NULL, *count 0, and
 * err says "file:line: reason". */
rt_status rt_rays_load(const char *path, int with_normals, rt_ray **rays, size_t *count,
                       rt_error *err);

/* Writes the hit file of `rtcl trace --out`: per ray one line "1 t u v prim"
 * (t, u, v with %.9g, so they read back as the same floats) or "0 inf 0 0 -1"
 * for a miss, followed by " inst" (" -1" for a miss) when with_instances.
 * Whole or not at all, as rt_image_write; err names the file. */
rt_status rt_hits_write(const char *path, const rt_hit *hits, size_t count, int with_instances,
                        rt_error *err);

/* Whether rt_hits_write could write path (its folder exists and is
 * writable), checked before the rays are traced; nothing is created. */
rt_status rt_hits_check_output(const char *path, rt_error *err);

/* A file another program writes (a video by ffmpeg), put in place whole or
 * not at all: rt_output_reserve creates an empty temporary beside target
 * (".STEM.tmp-UNIQUE.EXT", the target's extension kept) and gives its path
 * (rt_output_path) for that program to write; rt_output_commit renames it
 * over target once complete (an error there: RT_ERROR_IO, the temporary
 * removed); rt_output_discard removes it. Each frees the handle; an
 * existing target is untouched until the commit. A target that exists and
 * is no regular file (/dev/null) is given as it is, written in place.
 * what names the file's kind in messages ("video"). */
typedef struct rt_output rt_output;
rt_status rt_output_reserve(const char *target, const char *what, rt_output **out, rt_error *err);
const char *rt_output_path(const rt_output *output);
rt_status rt_output_commit(rt_output *output, rt_error *err);
void rt_output_discard(rt_output *output);

/* Whether a file of kind what could be written at target, checked before
 * the work that makes it: its folder exists and is writable, target is no
 * folder. RT_OK or RT_ERROR_IO naming the fault; nothing is created. */
rt_status rt_output_check(const char *target, const char *what, rt_error *err);

/* Removes the temporary file of every write this process has under way
 * (images, hit files, scenes, reserved outputs not yet committed or
 * discarded); the targets are untouched. Async-signal-safe: for a program's
 * SIGINT or SIGTERM handler, which then ends the process, so that an
 * interrupted write leaves neither a part of a file nor a stray temporary
 * (rtcl does this). Paths are as given: call it before any chdir. */
void rt_output_remove_temporaries(void);

/* What a backend is (rt_backend_describe): the registry's facts, for
 * programs that list or check backends without naming them. */
typedef struct rt_backend_info {
    const char *name;    /* "cpu", "packet", "opencl", "vulkan", or "auto" */
    const char *summary; /* one line: what it runs on */
    int built;           /* 1: this build has it */
    const char *missing; /* when not built: why, and what to install; else "" */
    /* 1: it runs on a device, chosen as NAME:DEVICE (an index or a part of
     * its name, rt_devices); "auto" passes the device to the backend it picks. */
    int takes_device;
    /* 1: it gives the CPU oracle's bits on every machine (the CPU backends);
     * 0: where the device promises them (rt_device_info.exact). */
    int exact_always;
} rt_backend_info;

/* The name of registered backend index (0, 1, ...), built in this build or
 * not: the CPU backends first, then the device backends, "auto" last; NULL
 * past the last. */
const char *rt_backend_name(int index);

/* Fills *out for the backend called name; an unknown name is
 * RT_ERROR_UNSUPPORTED naming the known ones (err may be NULL). */
rt_status rt_backend_describe(const char *name, rt_backend_info *out, rt_error *err);

/* One device of a device backend (rt_devices). Fields that the backend's API
 * does not report are 0, "" or -1 as said. */
typedef struct rt_device_info {
    char backend[16]; /* "opencl" or "vulkan" */
    int index;        /* the number NAME:N takes, in the backend's own numbering */
    char name[256];
    int platform_index; /* OpenCL: the platform's position in the ICD loader's list; else -1 */
    char platform[128]; /* OpenCL: the platform's name; else "" */
    char vendor[128];   /* OpenCL; else "" */
    char type[24];      /* Vulkan: "integrated GPU", "discrete GPU", "CPU", ...; else "" */
    char version[128];  /* the API version the device reports */
    char driver[160];
    uint32_t compute_units; /* OpenCL; else 0 */
    uint64_t memory;        /* bytes: OpenCL's global memory, Vulkan's largest device-local heap */
    uint64_t max_buffer;    /* bytes: the largest buffer */
    /* OpenCL: 1 or 0 (correctly rounded float divide and sqrt; hardware FMA,
     * never used by contraction; fp64, used by no kernel); else -1. */
    int cr_div_sqrt, fma, fp64;
    int timestamps; /* Vulkan: the compute queue has timestamps; else -1 */
    /* Vulkan float controls (VK_KHR_shader_float_controls, for 32-bit
     * floats): float_controls is 0 when the device does not report them
     * (then the others are 0), -1 for OpenCL. */
    int float_controls, rte, denorm_preserve, denorm_flush, signed_zero_inf_nan;
    char math_profile[16]; /* with device_math auto: "native" or "portable" */
    int exact;             /* the CPU oracle's bits promised with the defaults ... */
    char exact_note[400];  /* ... and why, one line */
    int exact_flush;       /* the same with RT_DENORMALS_FLUSH */
    char exact_flush_note[400];
    char denormals_note[400]; /* OpenCL: which denormal policy compares it; else "" */
    char kernels_note[400];   /* OpenCL: which kernels render there; else "" */
} rt_device_info;

/* The devices of the device backend called backend ("opencl", "vulkan"), or
 * with selector not NULL only the one it picks (an index or a part of a
 * name, as NAME:DEVICE does). *out (to free()) holds *count devices. A
 * backend this build lacks, no driver or platform, no device or no match is
 * RT_ERROR_UNSUPPORTED or RT_ERROR_INVALID_ARGUMENT with the reason; *out is
 * then NULL. */
rt_status rt_devices(const char *backend, const char *selector, rt_device_info **out, int *count,
                     rt_error *err);

#ifdef __cplusplus
}
#endif
#endif /* RTCL_RT_H */
