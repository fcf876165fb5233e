# SPDX-License-Identifier: Apache-2.0
# cli_kernels_opencl.sh - the shared maths (kernels/rt_*.h up to rt_shade.h) are valid OpenCL C
# (checked with clang's OpenCL front end; skipped without clang).
command -v clang >/dev/null || { echo "skipped: clang not installed"; exit 77; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cat > "$tmp/k.cl" <<'K'
#pragma OPENCL FP_CONTRACT OFF
#include "rt_camera.h"
#include "rt_shade.h"
__kernel void render(__global const rt_scene_header *h, __global const rt_node *nodes,
                     __global const rt_tri *tris, __global const uint *tri_ids,
                     __global const float *tri_normals, __global const uint *tri_mats,
                     __global const rt_instance *inst, __global const uint *inst_ids,
                     __global const rt_material_d *mats, __global const rt_light_d *lights,
                     __global float *out) {
    rt_scene_view s = {h, nodes, tris, tri_ids, tri_normals, tri_mats, inst, inst_ids, mats, lights};
    int x = get_global_id(0), y = get_global_id(1);
    rt_ray r;
    rt_hit_d hit;
    rt_counters c = {0, 0, 0};
    float rgb[3];
    rt_camera_ray(h, x, y, &r);
    rt_trace(&s, &r, 0, &hit, &c);
    rt_shade_hit(&s, &r, &hit, &c, rgb);
    out[3 * (y * h->width + x)] = rgb[0];
}
K
for std in CL1.2 CL2.0; do
    if ! clang -x cl -cl-std=$std -Werror -fsyntax-only -I"$RT_SOURCE_DIR/kernels" "$tmp/k.cl"; then
        echo "FAIL: the shared headers are not valid OpenCL C ($std)"; exit 1
    fi
done
# The kernel files as the backend builds them (rt_single_ray.cl, plus rt_ray_packet.cl
# on CPU devices, in one program): every block size, triangle test, and the
# specialisations of a one-object scene and of a two-level one with normals
# and secondary rays.
printf '#include "rt_single_ray.cl"\n#include "rt_ray_packet.cl"\n' > "$tmp/both.cl"
for lanes in 4 8 16; do
    for tri in 0 1 2 3; do
        for spec in "2u 1u 1u" "13u 0u 3u"; do
            set -- $spec
            if ! clang -x cl -cl-std=CL1.2 -Werror -fsyntax-only -I"$RT_SOURCE_DIR/kernels" \
                -DRT_PK_LANES=$lanes -DRT_STATIC_TRI_METHOD=${tri}u -DRT_STATIC_FLAGS=$1 \
                -DRT_STATIC_INST_SET=$2 -DRT_STATIC_INST_MASK=$3 "$tmp/both.cl"; then
                echo "FAIL: rt_single_ray.cl + rt_ray_packet.cl (lanes $lanes, triangle test $tri, flags $1)"
                exit 1
            fi
        done
    done
done
echo "cli_kernels_opencl.sh: shared headers compile as OpenCL C 1.2 and 2.0; the kernel files too"

