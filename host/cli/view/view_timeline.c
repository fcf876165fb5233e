/* SPDX-License-Identifier: Apache-2.0 */
/* view_timeline.c - the viewer's clock applied to the scene. */
#include "view_timeline.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

rt_status view_timeline_init(view_timeline *tl, const rt_scene *scene, double rate) {
    memset(tl, 0, sizeof *tl);
    tl->rate = rate;
    rt_scene_info info;
    rt_scene_describe(scene, &info);
    if (!info.objects) return RT_OK;
    tl->base = malloc(sizeof(uint32_t) * info.objects);
    if (!tl->base) return RT_ERROR_OUT_OF_MEMORY;
    tl->objects = info.objects;
    for (uint32_t o = 0; o < info.objects; o++) {
        rt_object_info oi;
        rt_object_describe(scene, o, &oi);
        tl->base[o] = oi.selected;
        if (oi.keyframes > 1) tl->animated = 1;
    }
    if (rt_scene_is_animated(scene)) tl->animated = 1;
    return RT_OK;
}

rt_status view_timeline_apply(view_timeline *tl, rt_scene *scene, double t) {
    /* A scene with time (keyframe rates, morphing, transform keys:
     * docs/SCENE_FORMAT.md) is put at time t by the library, exactly as
     * 'rtcl render --time t' does. The camera stays the viewer's: the user
     * flies, so a camera path is not followed here. */
    if (rt_scene_is_animated(scene)) {
        /* A glTF clip loops in the viewer (render and animate hold its
         * last pose after its end, as the file says). */
        double duration = 0.0;
        if (rt_scene_clip_count(scene) &&
            rt_scene_clip_info(scene, rt_scene_selected_clip(scene), NULL, &duration) == RT_OK &&
            duration > 0.0) {
            t = fmod(t, duration);
            if (t < 0.0) t += duration;
        }
        rt_camera cam;
        rt_camera_get(scene, &cam);
        rt_status st = rt_scene_set_time(scene, t);
        rt_camera now;
        rt_camera_get(scene, &now);
        if (st == RT_OK && memcmp(&cam, &now, sizeof cam) != 0) st = rt_camera_set(scene, &cam);
        return st;
    }
    /* Otherwise keyframe objects step at the viewer's rate (--keyframe-rate). */
    double step = floor(t * tl->rate);
    for (uint32_t o = 0; o < tl->objects; o++) {
        rt_object_info oi;
        if (rt_object_describe(scene, o, &oi) != RT_OK) break;
        uint32_t count = oi.keyframes;
        if (count < 2) continue;
        double k = fmod((double)tl->base[o] + step, (double)count);
        if (k < 0) k += count;
        uint32_t keyframe = (uint32_t)k;
        if (keyframe >= count) keyframe = 0; /* fmod's rounding at the edge */
        if (keyframe == oi.selected) continue;
        rt_status st = rt_object_select_mesh(scene, o, keyframe);
        if (st != RT_OK) return st;
    }
    return RT_OK;
}

void view_timeline_free(view_timeline *tl) {
    free(tl->base);
    memset(tl, 0, sizeof *tl);
}
