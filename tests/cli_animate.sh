# SPDX-License-Identifier: Apache-2.0
# cli_animate.sh - 'rtcl animate' and 'rtcl render --time': frame k of an
# animation is, bit for bit (32-bit float EXR), the image 'rtcl render --time
# k/F' gives, for every update policy and on the cpu and packet backends;
# frame ranges render only their frames; --stats writes one JSON line per
# frame; nothing reaches stderr when it is not a terminal; bad arguments are
# refused with a reason.
. "$(dirname "$0")/shell_check.sh"
: "${RTCL:?RTCL must name the rtcl binary}"
: "${RT_SOURCE_DIR:?RT_SOURCE_DIR must name the repository}"
scene="$RT_SOURCE_DIR/scenes/keyframes_animated.json"
size=(--width 80 --height 45)

same() { # same A B: the two images are identical
    checks=$((checks + 1))
    if ! "$RTCL" compare "$1" "$2" --max-diff 0 >/dev/null 2>&1; then
        echo "FAIL: $1 and $2 differ"; "$RTCL" compare "$1" "$2" | head -5
        fails=$((fails + 1))
    fi
}

# The reference frames: 'rtcl render --time' (time k / 4).
for k in 0 1 2 3 4 5; do
    t=$(awk "BEGIN { printf \"%.17g\", $k / 4 }")
    expect 0 "" -- "$RTCL" render "$scene" "${size[@]}" --time "$t" -o "$tmp/ref_$k.exr"
done

for backend in cpu packet; do
    for policy in refit fast auto rebuild; do
        dir="$tmp/$backend-$policy"
        mkdir -p "$dir"
        "$RTCL" animate "$scene" --fps 4 --frames 6 "${size[@]}" -o "$dir/f_%02d.exr" \
            --update "$policy" --backend "$backend" --stats >"$dir/stats" 2>"$dir/err"
        rc=$?
        checks=$((checks + 1))
        if [ "$rc" != 0 ] || [ -s "$dir/err" ]; then
            echo "FAIL: animate $backend $policy: status $rc, stderr:"; cat "$dir/err"
            fails=$((fails + 1))
        fi
        checks=$((checks + 1))
        lines=$(grep -c '^{"frame": [0-9]*, "time": .*"update": \[.*"render_ms": ' "$dir/stats")
        if [ "$lines" != 6 ]; then
            echo "FAIL: animate $backend $policy --stats: $lines frame lines, expected 6"
            head -3 "$dir/stats"
            fails=$((fails + 1))
        fi
        for k in 0 1 2 3 4 5; do same "$dir/f_0$k.exr" "$tmp/ref_$k.exr"; done
    done
done
# A refit frame says so.
expect 0 '"action": "refit"' -- grep -m1 '"frame": 3' "$tmp/cpu-refit/stats"

# A range renders only its frames, and they are the same frames.
mkdir -p "$tmp/range"
expect 0 "" -- "$RTCL" animate "$scene" --fps 4 --duration 1.5 --frame-range 4:5 "${size[@]}" \
    -o "$tmp/range/r%d.exr"
checks=$((checks + 1))
if [ "$(ls "$tmp/range")" != "$(printf 'r4.exr\nr5.exr')" ]; then
    echo "FAIL: --frame-range 4:5 wrote: $(ls "$tmp/range")"; fails=$((fails + 1))
fi
same "$tmp/range/r4.exr" "$tmp/ref_4.exr"
same "$tmp/range/r5.exr" "$tmp/ref_5.exr"

# Bad arguments.
expect 0 "usage: rtcl animate" -- "$RTCL" animate --help
expect 2 "no scene given" -- "$RTCL" animate --fps 4 --frames 2 -o "$tmp/x%d.png"
expect 2 "--fps F is required" -- "$RTCL" animate "$scene" --frames 2 -o "$tmp/x%d.png"
expect 2 "--fps: '0' is out of range \\(> 0\\)" -- "$RTCL" animate "$scene" --fps 0 --frames 2 -o "$tmp/x%d.png"
expect 2 "give one of --duration S and --frames N" -- \
    "$RTCL" animate "$scene" --fps 4 -o "$tmp/x%d.png"
expect 2 "give one of --duration S and --frames N" -- \
    "$RTCL" animate "$scene" --fps 4 --frames 2 --duration 1 -o "$tmp/x%d.png"
expect 2 "-o PATTERN is required" -- "$RTCL" animate "$scene" --fps 4 --frames 2
expect 2 "must hold exactly one %d conversion" -- \
    "$RTCL" animate "$scene" --fps 4 --frames 2 -o "$tmp/x.png"
expect 2 "must hold exactly one %d conversion" -- \
    "$RTCL" animate "$scene" --fps 4 --frames 2 -o "$tmp/x%d%s.png"
expect 2 "--frame-range: '3:1' is not A:B" -- \
    "$RTCL" animate "$scene" --fps 4 --frames 5 --frame-range 3:1 -o "$tmp/x%d.png"
expect 2 "the animation has frames 0..4" -- \
    "$RTCL" animate "$scene" --fps 4 --frames 5 --frame-range 3:5 -o "$tmp/x%d.png"
expect 2 "--update: 'lazy' is not one of sah, refit, lbvh or auto" -- \
    "$RTCL" animate "$scene" --fps 4 --frames 2 --update lazy -o "$tmp/x%d.png"
# A video without ffmpeg on PATH: the reason and the way to get frames instead,
# and no file (tests/cli_animate_video.sh tests videos where ffmpeg is).
mkdir -p "$tmp/nopath"
expect 2 "needs ffmpeg, which is not on PATH .*apt-get install ffmpeg.*-o DIR/frame_%04d.png" -- \
    env PATH="$tmp/nopath" "$RTCL" animate "$scene" --fps 4 --frames 2 -o "$tmp/v.mp4"
checks=$((checks + 1))
if [ -e "$tmp/v.mp4" ]; then echo "FAIL: v.mp4 written without ffmpeg"; fails=$((fails + 1)); fi

# A camera path alone: each frame after the first rewrites only the layout's
# header (no mesh update, no object BVH, the header's bytes alone, and on a
# device backend only those uploaded), and is the frame 'render --time' gives.
cat >"$tmp/cam.json" <<EOF
{"camera": {"path": [{"time": 0, "position": [0, 2, 6], "look_at": [0, 1, 0]},
                     {"time": 1, "position": [2, 1, 4], "look_at": [0, 0.5, 0]}]},
 "lights": [{"position": [2, 4, 3]}],
 "meshes": {"floor": {"file": "$RT_SOURCE_DIR/scenes/keyframes_floor.obj"},
            "column": {"file": "$RT_SOURCE_DIR/scenes/keyframes_column_0.obj"}},
 "objects": [{"mesh": "floor"}, {"mesh": "column", "transform": {"translate": [0.5, 0, 0]}},
             {"mesh": "column", "transform": {"translate": [-0.5, 0, 0]}}]}
EOF
cam_backends="cpu packet"
"$RTCL" devices >/dev/null 2>&1 && cam_backends="$cam_backends opencl"
no_leak_check "$RTCL" devices --api vulkan >/dev/null 2>&1 && cam_backends="$cam_backends vulkan"
for k in 0 1 2 3; do
    t=$(awk "BEGIN { printf \"%.17g\", $k / 4 }")
    expect 0 "" -- "$RTCL" render "$tmp/cam.json" "${size[@]}" --time "$t" -o "$tmp/cref_$k.exr"
done
for backend in $cam_backends; do
    dir="$tmp/cam-$backend"
    mkdir -p "$dir"
    leaks=()
    [ "$backend" = vulkan ] && leaks=(no_leak_check)
    "${leaks[@]}" "$RTCL" animate "$tmp/cam.json" --fps 4 --frames 4 "${size[@]}" \
        --backend "$backend" -o "$dir/f%d.exr" --stats >"$dir/stats" 2>"$dir/err"
    rc=$?
    checks=$((checks + 1))
    if [ "$rc" != 0 ] || [ -s "$dir/err" ]; then
        echo "FAIL: camera path on $backend: status $rc, stderr:"; cat "$dir/err"
        fails=$((fails + 1))
    fi
    for k in 0 1 2 3; do same "$dir/f$k.exr" "$tmp/cref_$k.exr"; done
    checks=$((checks + 1))
    bad=$(awk -v dev="$([ "$backend" != cpu ] && [ "$backend" != packet ] && echo 1)" '
        NR == 1 { next }
        {
            ok = index($0, "\"update\": [],") && index($0, "\"object_bvh_ms\": 0.000,") &&
                 index($0, "\"camera_only\": true")
            match($0, /"layout_bytes": [0-9]+/); lb = substr($0, RSTART + 16, RLENGTH - 16) + 0
            match($0, /"upload_bytes": [0-9]+/); ub = substr($0, RSTART + 16, RLENGTH - 16) + 0
            if (lb <= 0 || lb > 1024) ok = 0
            if (dev && ub != lb) ok = 0
            if (!dev && ub != 0) ok = 0
            if (!ok) print
        }' "$dir/stats")
    lines=$(wc -l <"$dir/stats")
    if [ -n "$bad" ] || [ "$lines" != 4 ]; then
        echo "FAIL: $backend: camera-only frames rebuilt or uploaded more than the header:"
        echo "$bad" | head -3
        fails=$((fails + 1))
    fi
done
expect 2 "--update: 'lazy' is not one of sah, refit, lbvh or auto" -- "$RTCL" render "$scene" --update lazy
expect 2 "--time: 'nan' is not a finite number" -- "$RTCL" render "$scene" --time nan
finish
