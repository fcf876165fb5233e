/* SPDX-License-Identifier: Apache-2.0 */
/* scene_default_view.h - what a scene whose file gives no camera or no
 * lights gets: the default view, and lights from its emissive surfaces (the
 * Cornell box OBJ's ceiling panel, a glTF emissive material) or else one
 * beside the camera, so that such a scene is not black. */
#ifndef RT_SCENE_DEFAULT_VIEW_H
#define RT_SCENE_DEFAULT_VIEW_H

#include <stdint.h>

#include "rt.h"

/* The most lights rt_scene_add_emitter_lights makes: the strongest emitters
 * (by emission times area) when a scene has more. */
#define RT_MAX_EMITTER_LIGHTS 16

/* Adds one point light per (object, emissive material) pair of the scene's
 * shown meshes: at the world-space, area-weighted centroid of its triangles,
 * moved off them by 1/1000 of the scene's diagonal along their summed normal
 * (a closed lamp keeps it inside; a ceiling panel, just below), with the
 * colour emission x area scaled so that the brightest channel of all the
 * lights together is 1 (one default light's worth). Triangles of zero area
 * count for nothing. *added gets the number made (0: no emitter). */
rt_status rt_scene_add_emitter_lights(rt_scene *scene, uint32_t *added);

/* The default view of a bare OBJ (docs/SCENE_FORMAT.md): camera, the
 * default lights (none when scene->no_default_light) and ambient 0.1, from
 * the bounding box of all meshes. Fails on an empty scene. */
rt_status rt_scene_apply_default_view(rt_scene *scene, int width, int height);

/* The lights of a scene whose file gives none: a point light per emissive
 * surface (rt_scene_add_emitter_lights), or, without one, a white light
 * above and to the right of the current camera. */
rt_status rt_scene_add_default_lights(rt_scene *scene);

#endif /* RT_SCENE_DEFAULT_VIEW_H */
