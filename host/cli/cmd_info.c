/* SPDX-License-Identifier: Apache-2.0 */
/* cmd_info.c - 'rtcl info': what a scene holds and which features it uses,
 * as text or as one JSON object (--json). */
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "cli_util.h"
#include "commands.h"
#include "engines/bench_print.h"

typedef struct info_args {
    int json;
    cli_scene_args scene;
    cli_renderer_args renderer; /* the kernel options alone */
} info_args;

static const cli_option info_options[] = {
    {"--json", 0, CLI_FLAG, NULL, offsetof(info_args, json),
     .help = "the same as one JSON object on stdout: scene, triangles, all_triangles, meshes "
             "[{name, triangles, vertices, normals, update, accel}], objects, animation, "
             "materials, lights, light_list [{position, color}], camera, bounds, features, "
             "specialised, opencl, device_math, "
             "denormals, vulkan"},
    {NULL}};

static const cli_group info_groups[] = {
    {NULL, info_options, 0},
    {CLI_SCENE_TITLE, cli_scene_options, offsetof(info_args, scene)},
    {CLI_SCENE_TITLE, cli_time_options, offsetof(info_args, scene)},
    {"Kernel options (what info says of the device kernels, as render would be given)",
     cli_kernel_options, offsetof(info_args, renderer)},
    {NULL}};

const cli_command cmd_info_spec = {
    "info",
    "print what a scene holds and which features it uses",
    "SCENE",
    "scene",
    1,
    1,
    "Prints the triangles, meshes, objects, materials and lights of SCENE (a .json\n"
    "scene, a bare .obj, a .gltf or .glb, or builtin:NAME; a glTF file's animation\n"
    "clips with their durations), its camera, and the features it uses:\n"
    "backends specialise to these (no secondary rays without reflective or\n"
    "refractive materials, no instance transforms for one identity object, no\n"
    "normal interpolation without normals; OpenCL as -D switches, Vulkan as\n"
    "specialization constants), whether the OpenCL kernels are the exact build,\n"
    "and the Vulkan shaders' maths profile. Each mesh's line ends with the\n"
    "structure a renderer builds for it (bvh, kd or kd-binned).\n",
    info_groups,
    NULL,
    NULL};

static const char *on_off(int v) {
    return v ? "on" : "off";
}

static const char *choice_name(const cli_choice *choices, int value) {
    for (; choices->name; choices++)
        if (choices->value == value) return choices->name;
    return "?";
}

/* One JSON object of all info prints, on one line. */
static void print_json(const char *path, const rt_scene *s, const rt_scene_info *in,
                       const info_args *a, int kd, int vulkan) {
    const cli_renderer_args *r = &a->renderer;
    printf("{\"scene\": ");
    json_out_string(path);
    printf(", \"triangles\": %llu, \"all_triangles\": %llu, \"meshes\": [",
           (unsigned long long)in->triangles, (unsigned long long)in->all_triangles);
    for (uint32_t i = 0; i < in->meshes; i++) {
        rt_mesh_info m;
        rt_mesh_describe(s, i, &m);
        printf("%s{\"name\": ", i ? ", " : "");
        json_out_string(m.name);
        printf(", \"triangles\": %u, \"vertices\": %u, \"normals\": %s, \"update\": \"%s\", "
               "\"accel\": \"%s\"}",
               m.triangles, m.vertices, cli_json_bool(m.normals), rt_update_policy_name(m.update),
               rt_accel_name(m.accel));
    }
    printf("], \"objects\": %u, \"animation\": {\"animated\": %s, \"switched_objects\": %u, "
           "\"blended_objects\": %u, \"keyed_objects\": %u, \"camera_path_keys\": %u}",
           in->objects, cli_json_bool(in->animated), in->switched_objects, in->blended_objects,
           in->keyed_objects, in->camera_path_keys);
    printf(", \"materials\": %u, \"lights\": %u, \"light_list\": [", in->materials, in->lights);
    for (uint32_t i = 0; i < in->lights; i++) {
        float p[3], c[3];
        if (rt_light_get(s, i, p, c) != RT_OK) break;
        printf("%s{\"position\": [%.9g, %.9g, %.9g], \"color\": [%.9g, %.9g, %.9g]}", i ? ", " : "",
               (double)p[0], (double)p[1], (double)p[2], (double)c[0], (double)c[1], (double)c[2]);
    }
    printf("]");
    rt_camera c;
    rt_camera_get(s, &c);
    printf(", \"camera\": {\"position\": [%.9g, %.9g, %.9g], \"look_at\": [%.9g, %.9g, %.9g], "
           "\"up\": [%.9g, %.9g, %.9g], \"fov\": %.9g, \"width\": %d, \"height\": %d}",
           (double)c.position[0], (double)c.position[1], (double)c.position[2],
           (double)c.look_at[0], (double)c.look_at[1], (double)c.look_at[2], (double)c.up[0],
           (double)c.up[1], (double)c.up[2], (double)c.hfov_degrees, c.width, c.height);
    float lo[3], hi[3];
    if (rt_scene_bounds(s, lo, hi))
        printf(", \"bounds\": {\"min\": [%.9g, %.9g, %.9g], \"max\": [%.9g, %.9g, %.9g]}",
               (double)lo[0], (double)lo[1], (double)lo[2], (double)hi[0], (double)hi[1],
               (double)hi[2]);
    else
        printf(", \"bounds\": null");
    printf(", \"clips\": [");
    for (uint32_t i = 0; i < rt_scene_clip_count(s); i++) {
        const char *name;
        double duration;
        rt_scene_clip_info(s, i, &name, &duration);
        printf("%s{\"name\": ", i ? ", " : "");
        json_out_string(name);
        printf(", \"duration\": %.9g}", duration);
    }
    printf("]");
    printf(", \"features\": {\"reflection\": %s, \"refraction\": %s, \"instancing\": %s, "
           "\"normals\": %s, \"keyframes\": %s, \"tri_materials\": %s}",
           cli_json_bool(in->reflection), cli_json_bool(in->refraction),
           cli_json_bool(in->instancing), cli_json_bool(in->normals), cli_json_bool(in->keyframes),
           cli_json_bool(in->tri_materials));
    printf(", \"specialised\": {\"secondary_rays\": %s, \"instance_transforms\": %s, "
           "\"normal_interpolation\": %s, \"tri_materials\": %s, \"kd_traversal\": %s}",
           cli_json_bool(in->reflection || in->refraction), cli_json_bool(in->instancing),
           cli_json_bool(in->normals), cli_json_bool(in->tri_materials), cli_json_bool(kd));
    int extra = r->cl_options && r->cl_options[0];
    printf(", \"opencl\": {\"exact_build\": %s, \"cl_options\": ", cli_json_bool(!extra));
    json_out_string(extra ? r->cl_options : "");
    printf("}, \"device_math\": \"%s\", \"denormals\": \"%s\"",
           choice_name(cli_device_math_choices, r->device_math),
           choice_name(cli_denormals_choices, r->denormals));
    if (vulkan)
        printf(", \"vulkan\": {\"maths\": \"portable\"}");
    else
        printf(", \"vulkan\": null");
    printf("}\n");
}

int cmd_info(int argc, char **argv) {
    info_args a;
    memset(&a, 0, sizeof a);
    cli_args_init(NULL, &a.scene, &a.renderer);
    int code;
    if (cli_parse(&cmd_info_spec, &a, argc, argv, &code) < 0) return code;
    const char *path = argv[0];
    const char *cl_options = a.renderer.cl_options;
    const char *math = choice_name(cli_device_math_choices, a.renderer.device_math);
    const char *denormals = choice_name(cli_denormals_choices, a.renderer.denormals);
    rt_scene *s = cli_scene_open("info", path, &a.scene, a.renderer.threads);
    if (!s) return 2;
    rt_scene_info in;
    rt_scene_describe(s, &in);
    int kd = 0;
    for (uint32_t i = 0; i < in.meshes; i++) kd |= rt_mesh_accel(s, i) != RT_ACCEL_BVH;
    rt_backend_info vk;
    int vulkan = rt_backend_describe("vulkan", &vk, NULL) == RT_OK && vk.built;
    if (a.json) {
        print_json(path, s, &in, &a, kd, vulkan);
        rt_scene_destroy(s);
        return 0;
    }
    printf("scene        %s\n", path);
    printf("triangles    %llu in the current frame (%llu in all meshes)\n",
           (unsigned long long)in.triangles, (unsigned long long)in.all_triangles);
    printf("meshes       %u\n", in.meshes);
    for (uint32_t i = 0; i < in.meshes; i++) {
        rt_mesh_info m;
        rt_mesh_describe(s, i, &m);
        printf("  %-24s %u triangles, %u vertices%s%s%s, %s\n", m.name, m.triangles, m.vertices,
               m.normals ? ", normals" : "", m.update ? ", update " : "",
               m.update ? rt_update_policy_name(m.update) : "", rt_accel_name(m.accel));
    }
    printf("objects      %u\n", in.objects);
    uint32_t clips = rt_scene_clip_count(s);
    if (clips)
        printf("animation    a glTF clip at every time (node animation, skins, morph targets); "
               "rigid parts are objects, skinned meshes deform\n");
    else if (in.animated)
        printf("animation    keyframes switched on %u objects, blended on %u; transform keys on %u "
               "objects; camera path of %u keys\n",
               in.switched_objects, in.blended_objects, in.keyed_objects, in.camera_path_keys);
    else
        printf("animation    none (the scene stays still)\n");
    if (clips) {
        printf("clips        %u (playing %u)\n", clips, rt_scene_selected_clip(s));
        for (uint32_t i = 0; i < clips; i++) {
            const char *name;
            double duration;
            rt_scene_clip_info(s, i, &name, &duration);
            printf("  %-3u %-24s %.6g s\n", i, name[0] ? name : "(unnamed)", duration);
        }
    }
    printf("materials    %u\n", in.materials);
    printf("lights       %u\n", in.lights);
    rt_camera cam;
    rt_camera_get(s, &cam);
    const rt_camera *c = &cam;
    printf("camera       eye (%g, %g, %g) look-at (%g, %g, %g) fov %g, %dx%d\n",
           (double)c->position[0], (double)c->position[1], (double)c->position[2],
           (double)c->look_at[0], (double)c->look_at[1], (double)c->look_at[2],
           (double)c->hfov_degrees, c->width, c->height);
    float lo[3], hi[3];
    if (rt_scene_bounds(s, lo, hi))
        printf("bounds       (%g, %g, %g) .. (%g, %g, %g)\n", (double)lo[0], (double)lo[1],
               (double)lo[2], (double)hi[0], (double)hi[1], (double)hi[2]);
    const rt_scene_info f = in; /* its features */
    printf("features     reflection %s, refraction %s, instancing %s, normals %s, "
           "keyframes %s, per-triangle materials %s\n",
           on_off(f.reflection), on_off(f.refraction), on_off(f.instancing), on_off(f.normals),
           on_off(f.keyframes), on_off(f.tri_materials));
    /* What the specialised backends (OpenCL -D switches, see rtcl render
     * --stats) switch on for this scene. */
    printf("specialised  secondary-ray pass %s, instance transforms %s, normal interpolation %s, "
           "per-triangle materials %s\n",
           on_off(f.reflection || f.refraction), on_off(f.instancing), on_off(f.normals),
           on_off(f.tri_materials));
    if (cl_options && cl_options[0])
        printf("opencl build NOT exact: extra options '%s' (--cl-options) are appended; results "
               "may differ from the CPU oracle\n",
               cl_options);
    else
        printf("opencl build exact (no extra options): the CPU oracle's bits where the device "
               "promises them (rtcl devices)\n");
    if (!strcmp(math, "auto"))
        printf("device maths auto: native (correctly rounded divide/sqrt) where the device "
               "promises it, else portable (software divide/sqrt); rtcl devices names each\n");
    else
        printf("device maths %s%s\n", math,
               !strcmp(math, "portable") ? ": software divide/sqrt, exact on any conforming device"
                                         : ": exact only where divide/sqrt are correctly rounded");
    printf("denormals    %s%s\n", denormals,
           !strcmp(denormals, "flush") ? ": compared with a flushing oracle (FTZ/DAZ)" : " (IEEE)");
    /* The Vulkan shaders take the same switches as specialization constants
     * (rtcl render --stats prints their values); the kd-tree traversal is
     * compiled in only where a mesh has a kd-tree. */
    if (vulkan)
        printf("vulkan       specialization constants: secondary rays %s, instance transforms %s, "
               "normal interpolation %s, per-triangle materials %s, kd-tree traversal %s; portable "
               "maths (software division and sqrt, no fp64, no contraction): the CPU oracle's bits "
               "where the device promises them (rtcl devices)\n",
               on_off(f.reflection || f.refraction), on_off(f.instancing), on_off(f.normals),
               on_off(f.tri_materials), on_off(kd));
    rt_scene_destroy(s);
    return 0;
}
