/* SPDX-License-Identifier: Apache-2.0 */
/* gltf_load.h - glTF 2.0 scenes (.gltf, .glb) into a scene.
 *
 * The file is read by the glTF module (formats/gltf_module.h, tinygltf,
 * loaded on first use); what it holds is mapped onto the scene here:
 *
 * - Geometry: the default scene's node hierarchy (matrix or TRS) is
 *   flattened to world transforms; every triangle primitive (TRIANGLES,
 *   TRIANGLE_STRIP, TRIANGLE_FAN; points and lines are left out with a
 *   notice) of every node with a mesh becomes one object with one mesh. A
 *   rigid (unskinned) primitive's mesh holds its node-space vertices and the
 *   object's transform is the node's world matrix, so that rigid node
 *   animation moves objects under the object BVH and rebuilds no mesh
 *   (while that matrix is singular, a node scaled to 0, the mesh holds the
 *   world-space vertices under the identity). Skinned primitives' meshes
 *   are in world space under the identity, skinned (linear blend, JOINTS_0/WEIGHTS_0 and _1, joint
 *   matrix = world(joint) * inverseBind; the node's own transform is not
 *   applied, as the specification says); morph targets are blended first
 *   (the node's weights over the mesh's, animated weights over both).
 * - Time: the clip being played (clip 0 unless rt_scene_select_clip) is
 *   evaluated at every rt_scene_set_time: STEP, LINEAR (rotations by
 *   shortest-path slerp) and CUBICSPLINE (tangents scaled by the key
 *   interval) samplers, clamped before the first and after the last key.
 *   Every mesh's positions (and normals) are evaluated again from the rest
 *   pose, so the scene at time t does not depend on the times before it.
 * - Materials (glTF metallic-roughness onto Phong, docs/SCENE_FORMAT.md):
 *   colour = baseColorFactor's rgb; ambient 1; diffuse = 1 - metallic;
 *   specular = (1 - roughness) * (0.04 + 0.96 metallic); shininess =
 *   2 / roughness^4 - 2 clamped to 1..1024 (the Blinn-Phong exponent of
 *   the same highlight width); reflectivity = metallic * (1 - roughness)^2;
 *   alpha, emission and textures are not used (textures: one notice).
 *   A primitive without a material gets rt_material_default().
 * - The camera: the first perspective camera met in the node hierarchy
 *   (looking down the node's -Z, up its +Y; horizontal field of view from
 *   yfov and aspectRatio, 1024 pixels wide). KHR_lights_punctual point
 *   lights at their nodes' positions, colour = the light's colour (its
 *   intensity is not used: the renderer's lights do not fall off); spot and
 *   directional lights are left out with a notice. Without a camera the
 *   default view of a bare OBJ; without lights its default light.
 * - Errors name the file and the JSON pointer of what is wrong: a node
 *   graph with a cycle or a node with two parents, an index out of range
 *   (vertex, node, mesh, skin, joint, sampler), a key time that is NaN or
 *   not increasing, a key value that is not finite, an output of the wrong
 *   size. Nothing is half-loaded. */
#ifndef RT_GLTF_LOAD_H
#define RT_GLTF_LOAD_H

#include "rt.h"

/* Loads the glTF file at path into scene (empty), animation and all. */
rt_status rt_scene_load_gltf(rt_scene *scene, const char *path, rt_error *err);

/* Adds the glTF file at path to scene as one static mesh (for a JSON
 * scene's "file" mesh): every triangle primitive of its default scene at
 * time 0 of clip 0, in world space, each triangle with its primitive's
 * material (added to scene) as a per-triangle material. No object, camera
 * or light is added; the file's animation is not played. */
rt_status rt_gltf_add_mesh(rt_scene *scene, const char *path, uint32_t *mesh_id, rt_error *err);

/* Is path a .gltf or .glb file name? */
int rt_gltf_is_gltf_path(const char *path);

#endif /* RT_GLTF_LOAD_H */
