/* cmd_info.c - 'rtcl info': what a scene holds and which features it uses. */
#include <stdio.h>
#include <string.h>

#include "cli_util.h"
#include "commands.h"
#include "scene/scene.h"

static const char usage[] =
    "usage: rtcl info SCENE [--accel A] [--cl-options OPTS] [--device-math M] [--denormals P]\n"
    "                 [--help]\n"
    "\n"
    "Prints the triangles, meshes, objects, materials and lights of SCENE (a .json\n"
    "scene, a bare .obj, or builtin:NAME), its camera, and the features it uses:\n"
    "backends specialise to these (no secondary rays without reflective or\n"
    "refractive materials, no instance transforms for one identity object, no\n"
    "normal interpolation without normals; OpenCL as -D switches, Vulkan as\n"
    "specialization constants), whether the OpenCL kernels are the exact build,\n"
    "and the Vulkan shaders' maths profile. Each mesh's line ends with the\n"
    "structure a renderer builds for it (bvh, kd or kd-binned).\n"
    "\n"
    "  --accel A          as for rtcl render: bvh, kd or kd-binned for every static\n"
    "                     mesh; info then shows that choice\n"
    "  --cl-options OPTS  the extra OpenCL compiler options rtcl render would be\n"
    "                     given (the speed-versus-error study): info then says the\n"
    "                     kernels are not the exact build\n"
    "  --device-math M    auto, native or portable: the maths profile render would\n"
    "                     build the kernels with [auto]\n"
    "  --denormals P      preserve or flush, as render would be given [preserve]\n";

int cmd_info(int argc, char **argv) {
    const char *path = NULL, *cl_options = NULL, *math = "auto", *denormals = "preserve";
    cli_renderer_args ra;
    cli_renderer_args_init(&ra);
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            fputs(usage, stdout);
            return 0;
        }
        if (!strcmp(argv[i], "--accel")) {
            if (cli_renderer_arg(argc, argv, &i, "info", &ra) < 0) return 2;
            continue;
        }
        if (!strcmp(argv[i], "--cl-options")) {
            if (!(cl_options = cli_value(argc, argv, &i, "info"))) return 2;
            continue;
        }
        if (!strcmp(argv[i], "--device-math") || !strcmp(argv[i], "--denormals")) {
            int m = !strcmp(argv[i], "--device-math");
            const char *o = argv[i], *v = cli_value(argc, argv, &i, "info");
            if (!v) return 2;
            if (m ? strcmp(v, "auto") && strcmp(v, "native") && strcmp(v, "portable")
                  : strcmp(v, "preserve") && strcmp(v, "flush")) {
                cli_error("info", "%s takes %s, not '%s'", o,
                          m ? "auto, native or portable" : "preserve or flush", v);
                return 2;
            }
            *(m ? &math : &denormals) = v;
            continue;
        }
        if (argv[i][0] == '-' || path) {
            cli_error("info", "unexpected argument '%s'\n%s", argv[i], usage);
            return 2;
        }
        path = argv[i];
    }
    if (!path) {
        cli_error("info", "no scene given\n%s", usage);
        return 2;
    }
    rt_scene *s;
    rt_error err;
    if (cli_load_scene(path, &s, &err) != RT_OK) {
        cli_error("info", "%s", err.message);
        return 2;
    }
    if (!cli_apply_accel("info", &ra, s)) {
        rt_scene_destroy(s);
        return 2;
    }
    uint64_t all_tris = 0;
    for (uint32_t i = 0; i < s->mesh_count; i++) all_tris += s->meshes[i].triangle_count;
    printf("scene        %s\n", path);
    printf("triangles    %llu in the current frame (%llu in all meshes)\n",
           (unsigned long long)rt_scene_triangle_count(s), (unsigned long long)all_tris);
    printf("meshes       %u\n", s->mesh_count);
    for (uint32_t i = 0; i < s->mesh_count; i++)
        printf("  %-24s %u triangles, %u vertices%s%s%s, %s\n", s->meshes[i].name,
               s->meshes[i].triangle_count, s->meshes[i].vertex_count,
               s->meshes[i].normals ? ", normals" : "",
               s->meshes[i].update_policy ? ", update " : "",
               s->meshes[i].update_policy
                   ? rt_update_policy_name((rt_update_policy)s->meshes[i].update_policy)
                   : "",
               rt_accel_name(rt_mesh_accel(s, i)));
    printf("objects      %u\n", s->object_count);
    uint32_t keyed = 0, blended = 0, switched = 0;
    for (uint32_t i = 0; i < s->object_count; i++) {
        const rt_object_data *o = &s->objects[i];
        keyed += o->transform_key_count > 0;
        if (o->keyframe_rate > 0.0f && o->mesh_count > 1) {
            blended += o->interpolate != 0;
            switched += o->interpolate == 0;
        }
    }
    if (rt_scene_is_animated(s))
        printf("animation    keyframes switched on %u objects, blended on %u; transform keys on %u "
               "objects; camera path of %u keys\n",
               switched, blended, keyed, s->camera_path_count);
    else
        printf("animation    none (the scene stays still)\n");
    printf("materials    %u\n", s->material_count);
    printf("lights       %u\n", s->light_count);
    const rt_camera *c = &s->camera;
    printf("camera       eye (%g, %g, %g) look-at (%g, %g, %g) fov %g, %dx%d\n",
           (double)c->position[0], (double)c->position[1], (double)c->position[2],
           (double)c->look_at[0], (double)c->look_at[1], (double)c->look_at[2],
           (double)c->hfov_degrees, c->width, c->height);
    float lo[3], hi[3];
    if (rt_scene_bounds(s, lo, hi))
        printf("bounds       (%g, %g, %g) .. (%g, %g, %g)\n", (double)lo[0], (double)lo[1],
               (double)lo[2], (double)hi[0], (double)hi[1], (double)hi[2]);
    rt_scene_features f = rt_scene_features_of(s);
    printf("features     reflection %s, refraction %s, instancing %s, normals %s, "
           "keyframes %s, per-triangle materials %s\n",
           f.reflection ? "on" : "off", f.refraction ? "on" : "off", f.instancing ? "on" : "off",
           f.normals ? "on" : "off", f.keyframes ? "on" : "off", f.tri_materials ? "on" : "off");
    /* What the specialised backends (OpenCL -D switches, see rtcl render
     * --stats) switch on for this scene. */
    printf("specialised  secondary-ray pass %s, instance transforms %s, normal interpolation %s, "
           "per-triangle materials %s\n",
           (f.reflection || f.refraction) ? "on" : "off", f.instancing ? "on" : "off",
           f.normals ? "on" : "off", f.tri_materials ? "on" : "off");
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
#ifdef RT_HAVE_VULKAN
    /* The Vulkan shaders take the same switches as specialization constants
     * (rtcl render --stats prints their values); the kd-tree traversal is
     * compiled in only where a mesh has a kd-tree. */
    int kd = 0;
    for (uint32_t i = 0; i < s->mesh_count; i++) kd |= rt_mesh_accel(s, i) != RT_ACCEL_BVH;
    printf("vulkan       specialization constants: secondary rays %s, instance transforms %s, "
           "normal interpolation %s, per-triangle materials %s, kd-tree traversal %s; portable "
           "maths (software division and sqrt, no fp64, no contraction): the CPU oracle's bits "
           "where the device promises them (rtcl devices)\n",
           (f.reflection || f.refraction) ? "on" : "off", f.instancing ? "on" : "off",
           f.normals ? "on" : "off", f.tri_materials ? "on" : "off", kd ? "on" : "off");
#endif
    rt_scene_destroy(s);
    return 0;
}
