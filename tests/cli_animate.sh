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
expect 2 "--fps: must be > 0" -- "$RTCL" animate "$scene" --fps 0 --frames 2 -o "$tmp/x%d.png"
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
expect 2 "--update: unknown policy 'lazy'" -- \
    "$RTCL" animate "$scene" --fps 4 --frames 2 --update lazy -o "$tmp/x%d.png"
expect 2 "--update: unknown policy 'lazy'" -- "$RTCL" render "$scene" --update lazy
expect 2 "--time: 'nan' is not a finite number" -- "$RTCL" render "$scene" --time nan
finish
