/* SPDX-License-Identifier: Apache-2.0 */
/* rtcl_py.h - what the files of the extension module rtcl._rtcl share. The
 * module calls the library through rt.h alone (tests/python/
 * check_public_api.sh checks its objects' undefined symbols against rt.h). */
#ifndef RTCL_PY_H
#define RTCL_PY_H

#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <stddef.h>
#include <stdint.h>

#include "rt.h"

/* What the queries are. */
enum { RTCL_CAST = 0, RTCL_OCCLUSION = 1, RTCL_COUNT = 2 };

/* One ray query over n rays read in place from the caller's arrays: ray i's
 * origin at org + i * org_step (3 floats), its direction at dir + i *
 * dir_step, its range tmin[i * tmin_step], tmax[i * tmax_step] (a step of 0
 * repeats the first). The outputs the query's kind fills (the others NULL):
 * cast: t, prim, mesh, inst (n each), uv (2n), normal (3n); occlusion:
 * occluded (n bytes 0 or 1); count: counts (n). */
typedef struct rtcl_query {
    int kind;
    size_t n;
    const float *org, *dir;
    size_t org_step, dir_step;
    const float *tmin, *tmax;
    size_t tmin_step, tmax_step;
    float *t;
    uint32_t *prim, *mesh, *inst;
    float *uv, *normal;
    uint8_t *occluded;
    uint32_t *counts;
} rtcl_query;

/* Runs q on renderer and scene in blocks of rays (the library's rt_ray
 * array of a block is the only copy), without touching Python: the caller
 * releases the GIL around it. The error is the renderer's. */
rt_status rtcl_run_query(rt_renderer *renderer, rt_scene *scene, const rtcl_query *q);

#endif /* RTCL_PY_H */
