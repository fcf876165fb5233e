#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# kd_shared_scenes.sh - the SAH kd-trees (issue 18) against the BVH on the
# shared scenes (../shared/scenes): for each scene, the image and the depth
# and primitive-id AOVs rendered with --accel kd and --accel kd-binned on
# every backend must equal the BVH oracle's (cpu, --accel bvh) bit for bit.
# Prints a Markdown table (docs/KD_SHARED_SCENES.md holds a run's output).
#
# usage: bench/kd_shared_scenes.sh [RTCL] [SCENES_DIR]   (from the repository root)
# environment: KD_BACKENDS (default "cpu packet opencl"), KD_SIZE (WxH, default 320x180),
# KD_MAX_TRIS (larger scenes are listed as skipped; default 300000, which
# leaves out the full-resolution dragon: 18 exact builds of 871k triangles)
set -u
RTCL=${1:-build/rtcl}
DIR=${2:-../shared/scenes}
BACKENDS=${KD_BACKENDS:-"cpu packet opencl"}
SIZE=${KD_SIZE:-320x180}
MAX_TRIS=${KD_MAX_TRIS:-300000}
W=${SIZE%x*}
H=${SIZE#*x}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if ! "$RTCL" devices > /dev/null 2>&1; then BACKENDS=${BACKENDS//opencl/}; fi

# The interiors through their views (bench/scenes/*_interior.json, from
# ../shared/scenes/VIEWS.md); the default (bounding-box) camera elsewhere.
# Animated scenes: their first frame.
scene_file() { # obj -> a scene file to render
    case "$(basename "$1" .obj)" in
    sponza) echo bench/scenes/sponza_interior.json ;;
    sibenik) echo bench/scenes/sibenik_interior.json ;;
    *) echo "$1" ;;
    esac
}

same() { "$RTCL" compare "$1" "$2" > /dev/null 2>&1; }

echo "| scene | triangles | accel | backends | image | depth | primid | kd build ms (render --stats) |"
echo "|---|---:|---|---|---|---|---|---:|"
fails=0
for obj in "$DIR"/*/*.obj; do
    case "$obj" in *_anim/*) case "$obj" in *_00.obj) ;; *) continue ;; esac ;; esac
    scene=$(scene_file "$obj")
    tris=$("$RTCL" info "$scene" 2>/dev/null | sed -n 's/^triangles *\([0-9]*\).*/\1/p')
    if [ "${tris:-0}" -gt "$MAX_TRIS" ]; then
        echo "| ${obj#"$DIR"/} | $tris | - | - | skipped (KD_MAX_TRIS=$MAX_TRIS) | | | |"
        continue
    fi
    for out in image depth primid; do
        aov=""; ext=ppm
        [ "$out" != image ] && aov="--aov $out" && ext=exr
        # shellcheck disable=SC2086
        "$RTCL" render "$scene" -o "$tmp/ref-$out.$ext" --width "$W" --height "$H" $aov \
            > /dev/null 2>&1 || echo "rtcl render failed on $scene" >&2
    done
    for accel in kd kd-binned; do
        row=(ok ok ok)
        build=""
        for backend in $BACKENDS; do
            i=0
            for out in image depth primid; do
                aov=""; ext=ppm
                [ "$out" != image ] && aov="--aov $out" && ext=exr
                # shellcheck disable=SC2086
                log=$("$RTCL" render "$scene" -o "$tmp/kd-$out.$ext" --width "$W" --height "$H" \
                    $aov --accel $accel --backend "$backend" --stats 2>&1)
                [ -z "$build" ] && build=$(sed -n 's/^build *\([0-9.]*\) ms.*/\1/p' <<< "$log")
                same "$tmp/ref-$out.$ext" "$tmp/kd-$out.$ext" ||
                    { row[$i]="DIFFERS ($backend)"; fails=$((fails + 1)); }
                i=$((i + 1))
            done
        done
        echo "| ${obj#"$DIR"/} | $tris | $accel | ${BACKENDS// /, } | ${row[0]} | ${row[1]} | ${row[2]} | $build |"
    done
done
echo
echo "$fails differences"
[ "$fails" = 0 ]
