/* SPDX-License-Identifier: Apache-2.0 */
/* view_timeline.h - scene time for the viewer: the one place where the
 * viewer's clock reaches the scene.
 *
 * Today the scene's only animation is keyframe selection (objects with
 * several meshes, rt_object_select_mesh): at time t every such object shows
 * keyframe (k0 + floor(t * rate)) mod count, k0 being the keyframe the scene
 * file selected. When the library gains scene time (rt_scene_set_time and
 * animated transforms, the dynamic-scenes work), view_timeline_apply is
 * where that call goes; nothing else in the viewer changes. */
#ifndef RTCL_VIEW_TIMELINE_H
#define RTCL_VIEW_TIMELINE_H

#include <stdint.h>

#include "rt.h"

typedef struct view_timeline {
    uint32_t *base; /* per object: the keyframe selected at load */
    uint32_t objects;
    double rate;  /* keyframes per second */
    int animated; /* some object has more than one keyframe */
} view_timeline;

/* Remembers the scene's selected keyframes; rate in keyframes per second
 * (> 0). RT_ERROR_OUT_OF_MEMORY on failure, *tl then empty. */
rt_status view_timeline_init(view_timeline *tl, const rt_scene *scene, double rate);

/* Sets the scene to time t (seconds; any finite value, negative too):
 * selects each animated object's keyframe for t. Selects only what changed,
 * so a paused timeline costs the renderer nothing. */
rt_status view_timeline_apply(view_timeline *tl, rt_scene *scene, double t);

void view_timeline_free(view_timeline *tl);

#endif /* RTCL_VIEW_TIMELINE_H */
