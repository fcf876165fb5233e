/* SPDX-License-Identifier: Apache-2.0 */
/* embree_scene.h - the peer's traced scene, shared by embree_trace.c (which
 * traces it) and embree_anim.c (which updates it per frame). Private to
 * bench/peer/. */
#ifndef RT_EMBREE_SCENE_H
#define RT_EMBREE_SCENE_H

#include <embree3/rtcore.h>

#include "layout/flat.h"

/* An Embree scene whose geometry geomID is the layout's instance geomID and
 * whose primID + the instance's tri_first is the layout's entry; flat and
 * view are the layout the hits are shaded from. */
struct rt_embree_scene {
    RTCScene scene;
    const rt_flat *flat;
    rt_scene_view view;
};

#endif /* RT_EMBREE_SCENE_H */
