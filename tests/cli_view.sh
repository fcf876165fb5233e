#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# cli_view.sh - 'rtcl view' under Xvfb, driven by --script: a scripted camera
# move's screenshot equals 'rtcl render' of the camera the viewer prints (C),
# bit for bit (32-bit float EXR, and the 8-bit PNG); switching backends
# mid-run (cpu, packet, opencl where a device exists, back to cpu) and the
# view keys (AOV, direct lighting) give exactly the images 'rtcl render'
# gives; the timeline steps keyframes as documented; bad scripts are
# rejected with file:line:column. Skips, saying why, when the viewer was not
# built (no SDL2) or Xvfb is missing.
set -u

RTCL=${RTCL:?RTCL must name the rtcl binary}
SRC=${RT_SOURCE_DIR:?RT_SOURCE_DIR must name the source tree}

help=$("$RTCL" view --help) || { echo "FAIL: rtcl view --help failed"; exit 1; }
case "$help" in
*"Note: this rtcl was built without the viewer"*)
    echo "skipped: $(printf '%s\n' "$help" | sed -n 's/^Note: //p')"
    exit 77
    ;;
esac

# Re-run under Xvfb (one server for the whole test).
if [ -z "${RT_VIEW_UNDER_XVFB:-}" ]; then
    if ! command -v xvfb-run >/dev/null; then
        echo "skipped: Xvfb is missing (install xvfb): the viewer needs a display to test"
        exit 77
    fi
    RT_VIEW_UNDER_XVFB=1 exec xvfb-run -a -s "-screen 0 640x480x24" bash "$0" "$@"
fi

# Present through SDL's software renderer into an X11 shared-memory image:
# the frames' bits do not depend on it, and it keeps Mesa (which SDL would
# otherwise load for an OpenGL texture, and which leaks when unloaded) out of
# the sanitizer build's leak check.
export SDL_RENDER_DRIVER=software SDL_FRAMEBUFFER_ACCELERATION=0
# Sanitizer build: when PoCL starts on the viewer's render thread, LLVM
# (llvm::sys::RemoveFileOnSignal) gives that thread an alternate signal stack
# from malloc, and AddressSanitizer's thread exit then tries to unmap it as if
# it were its own ("failed to deallocate ... unable to unmap"). Without ASan's
# own alternate stacks it leaves the thread's alone. Ignored by other builds.
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}use_sigaltstack=0"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() {
    echo "FAIL: $*"
    failures=$((failures + 1))
}

# run_rtcl: runs rtcl with the arguments, leaving $status, $out and $err.
run_rtcl() {
    "$RTCL" "$@" >"$work/stdout" 2>"$work/stderr"
    status=$?
    out=$(cat "$work/stdout")
    err=$(cat "$work/stderr")
}
expect_status() {
    [ "$status" -eq "$1" ] || fail "$2: exit status $status, expected $1 (stdout: $out; stderr: $err)"
}
expect_in() {
    case "$1" in
    *"$2"*) ;;
    *) fail "$3: output does not contain '$2': $1" ;;
    esac
}
# same A B WHAT: the two images are identical (every float channel).
same() {
    "$RTCL" compare "$1" "$2" >"$work/cmp" 2>&1 || fail "$3: $1 and $2 differ: $(cat "$work/cmp")"
}

# A copy of the shipped scenes, so that scene files with a new camera can sit
# beside their OBJ files.
cp "$SRC"/scenes/*.json "$SRC"/scenes/*.obj "$work/"
# with_camera SCENE CAMERA_LINE OUT: SCENE with the camera replaced.
with_camera() {
    python3 - "$1" "$2" "$3" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
scene["camera"] = json.loads("{" + sys.argv[2] + "}")["camera"]
json.dump(scene, open(sys.argv[3], "w"))
PY
}
command -v python3 >/dev/null || { echo "skipped: python3 is needed to edit scene files"; exit 77; }
size=(--width 160 --height 90)

# ---- 1. a scripted camera move equals rtcl render of the printed camera ----
cat >"$work/move.txt" <<'S'
# fly forward, turn left, drag, rise, faster, strafe, then print the camera
0 down W
6 up W
6 down Left
9 up Left
9 drag 30 -12
10 down E
12 up E
12 wheel 2
12 down A
14 up A
16 tap C
S
run_rtcl view "$work/cornell.json" "${size[@]}" --script "$work/move.txt" --frames 20 \
    --move-scale 2 --screenshot "$work/move.exr"
expect_status 0 "scripted move"
expect_in "$out" "screenshot: $work/move.exr (160x90," "scripted move: a full-resolution screenshot"
expect_in "$out" "view: 20 frames" "scripted move: --frames"
[ -z "$err" ] || fail "scripted move: stderr is not empty: $err"
camera=$(printf '%s\n' "$out" | grep '^"camera": ')
[ -n "$camera" ] || fail "scripted move: C printed no camera"
case "$camera" in
*'"position": [0, 0.899999976, 3]'*) fail "scripted move: the camera did not move: $camera" ;;
esac
with_camera "$work/cornell.json" "$camera" "$work/moved.json"
run_rtcl render "$work/moved.json" -o "$work/moved.exr"
expect_status 0 "render of the printed camera"
same "$work/move.exr" "$work/moved.exr" "scripted move against rtcl render"
# The same move again, saved as PNG: equal to rtcl render's PNG.
run_rtcl view "$work/cornell.json" "${size[@]}" --script "$work/move.txt" --frames 20 \
    --screenshot "$work/move.png"
expect_status 0 "scripted move, PNG"
run_rtcl render "$work/moved.json" -o "$work/moved.png"
same "$work/move.png" "$work/moved.png" "scripted move, PNG, against rtcl render"
cmp -s "$work/move.png" "$work/moved.png" || fail "scripted move: the PNG files' bytes differ"

# ---- 2. switching backends mid-run, the AOV and lighting keys ---------------
opencl=0
if "$RTCL" render "$work/cornell.json" --width 8 --height 8 --backend opencl \
    -o "$work/probe.exr" >/dev/null 2>"$work/probe.err"; then
    opencl=1
else
    echo "note: the opencl part is skipped: $(head -1 "$work/probe.err")"
fi
{
    echo "0 down D"
    echo "3 up D"
    echo "4 tap C"
    echo "4 screenshot $work/s_cpu.exr"
    echo "5 tap 2"
    echo "6 screenshot $work/s_packet.exr"
    if [ $opencl = 1 ]; then
        echo "7 tap 3"
        echo "8 screenshot $work/s_opencl.exr"
    fi
    echo "9 tap 1"
    echo "10 screenshot $work/s_cpu_again.exr"
    echo "11 tap 2"
    echo "11 tap V"
    echo "12 screenshot $work/s_depth.exr"
    echo "13 tap V"
    echo "14 screenshot $work/s_normal.exr"
    echo "15 tap V"
    echo "15 tap V"
    echo "15 tap V"
    echo "15 tap V"
    echo "15 tap V"
    echo "15 tap L"
    echo "16 screenshot $work/s_direct.exr"
    echo "17 quit"
} >"$work/switch.txt"
run_rtcl view "$work/cornell.json" "${size[@]}" --script "$work/switch.txt" --backend cpu
expect_status 0 "backend switches"
[ -z "$err" ] || fail "backend switches: stderr is not empty: $err"
view_out=$out
camera=$(printf '%s\n' "$view_out" | grep '^"camera": ')
with_camera "$work/cornell.json" "$camera" "$work/switched.json"
run_rtcl render "$work/switched.json" -o "$work/ref.exr"
run_rtcl render "$work/switched.json" --aov depth -o "$work/ref_depth.exr"
run_rtcl render "$work/switched.json" --aov normal -o "$work/ref_normal.exr"
run_rtcl render "$work/switched.json" --direct -o "$work/ref_direct.exr"
expect_in "$view_out" "s_cpu.exr (160x90, frame 4, backend cpu, shaded, Whitted)" "switch: cpu first"
expect_in "$view_out" "backend: packet" "switch: to packet"
expect_in "$view_out" "s_packet.exr (160x90, frame 6, backend packet" "switch: packet screenshot"
expect_in "$view_out" "s_cpu_again.exr (160x90, frame 10, backend cpu" "switch: back to cpu"
expect_in "$view_out" "s_depth.exr (160x90, frame 12, backend packet, depth" "switch: depth view"
expect_in "$view_out" "s_normal.exr (160x90, frame 14, backend packet, normal" "switch: normal view"
expect_in "$view_out" "s_direct.exr (160x90, frame 16, backend packet, shaded, direct)" "switch: direct"
for b in cpu packet cpu_again; do same "$work/s_$b.exr" "$work/ref.exr" "backend $b"; done
if [ $opencl = 1 ]; then
    expect_in "$view_out" "s_opencl.exr (160x90, frame 8, backend opencl" "switch: opencl"
    same "$work/s_opencl.exr" "$work/ref.exr" "backend opencl"
fi
same "$work/s_depth.exr" "$work/ref_depth.exr" "the depth view"
same "$work/s_normal.exr" "$work/ref_normal.exr" "the normal view"
same "$work/s_direct.exr" "$work/ref_direct.exr" "direct lighting"
if cmp -s "$work/s_direct.exr" "$work/ref.exr"; then fail "direct lighting changed nothing"; fi

# Without --backend the viewer starts on what --backend auto picks (the
# device backend rtcl render names, or the CPU when it finds no device).
run_rtcl render "$work/cornell.json" --width 8 --height 8 --backend auto -o "$work/probe.exr"
case "$err" in
*"notice: "*"using the CPU"*) auto=cpu ;;
*"backend "*) auto=$(printf '%s\n' "$err" | sed -n 's/^wrote .*, backend \([a-z]*\)[,)].*/\1/p') ;;
*) auto=; fail "render --backend auto names no backend: $err" ;;
esac
printf '1 screenshot %s\n2 quit\n' "$work/auto.exr" >"$work/auto.txt"
run_rtcl view "$work/cornell.json" "${size[@]}" --script "$work/auto.txt"
expect_status 0 "the default backend"
expect_in "$out" "auto.exr (160x90, frame 1, backend $auto," "the default backend is auto's ($auto)"

# ---- 3. the timeline steps keyframes: (k0 + floor(t rate)) mod count -------
# keyframes.json selects keyframe 2 of 4. At 10 keyframes/s and 30 steps/s,
# playing from frame 0 to frame 5 reaches t = 4/30 s: keyframe 3.
keyframe_scene() { # FRAME OUT: keyframes.json at 160x90 with that keyframe selected
    python3 - "$work/keyframes.json" "$1" "$2" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
scene["objects"][1]["frame"] = int(sys.argv[2])
scene["camera"]["width"], scene["camera"]["height"] = 160, 90
json.dump(scene, open(sys.argv[3], "w"))
PY
}
keyframe_scene 2 "$work/k2.json" && keyframe_scene 3 "$work/k3.json"
"$RTCL" render "$work/k2.json" -o "$work/k2.exr" 2>/dev/null
"$RTCL" render "$work/k3.json" -o "$work/k3.exr" 2>/dev/null
printf '0 tap Space\n1 screenshot %s\n5 tap Space\n' "$work/t1.exr" >"$work/play.txt"
run_rtcl view "$work/keyframes.json" "${size[@]}" --script "$work/play.txt" --frames 8 \
    --screenshot "$work/t_end.exr"
expect_status 0 "timeline"
same "$work/t1.exr" "$work/k2.exr" "timeline at t = 1/30 s (keyframe 2)"
same "$work/t_end.exr" "$work/k3.exr" "timeline paused at t = 4/30 s (keyframe 3)"
run_rtcl view "$work/keyframes.json" "${size[@]}" --time 0.25 --frames 2 \
    --screenshot "$work/t_start.exr"
expect_status 0 "--time"
"$RTCL" render "$work/k2.json" -o "$work/k2.exr" 2>/dev/null
keyframe_scene 0 "$work/k0.json" && "$RTCL" render "$work/k0.json" -o "$work/k0.exr" 2>/dev/null
same "$work/t_start.exr" "$work/k0.exr" "--time 0.25 (keyframe (2 + 2) mod 4 = 0)"

# ---- 4. Escape quits; bad input is rejected with its place -----------------
printf '3 tap Escape\n' >"$work/esc.txt"
run_rtcl view "$work/cornell.json" "${size[@]}" --script "$work/esc.txt"
expect_status 0 "Escape"
expect_in "$out" "view: 4 frames" "Escape ends the session after frame 3"

printf '0 down W\n1 jump W\n' >"$work/bad1.txt"
run_rtcl view "$work/cornell.json" --script "$work/bad1.txt"
expect_status 2 "unknown action"
expect_in "$err" "bad1.txt:2:3: unknown action 'jump'" "unknown action"
printf '0 down Shift\n' >"$work/bad2.txt"
run_rtcl view "$work/cornell.json" --script "$work/bad2.txt"
expect_status 2 "unknown key"
expect_in "$err" "bad2.txt:1:8: unknown key 'Shift'" "unknown key"
printf '5 tap C\n4 tap C\n' >"$work/bad3.txt"
run_rtcl view "$work/cornell.json" --script "$work/bad3.txt"
expect_status 2 "decreasing frames"
expect_in "$err" "bad3.txt:2:1: frame 4 comes after frame 5" "decreasing frames"
printf '0 drag 3\n' >"$work/bad4.txt"
run_rtcl view "$work/cornell.json" --script "$work/bad4.txt"
expect_status 2 "drag without DY"
expect_in "$err" "bad4.txt:1:9: this action needs 2 arguments" "drag without DY"
# Screenshot paths are checked before the session starts (issue 31): a
# missing folder or an unknown extension fails at once, naming the path.
printf '0 down W\n5 screenshot %s/nodir/a.png\n' "$work" >"$work/bad5.txt"
run_rtcl view "$work/cornell.json" --script "$work/bad5.txt"
expect_status 2 "screenshot into a missing folder"
expect_in "$err" "bad5.txt:2:14: screenshot: $work/nodir/a.png: cannot write the image file: folder" \
    "screenshot into a missing folder"
printf '5 screenshot %s/a.gif\n' "$work" >"$work/bad6.txt"
run_rtcl view "$work/cornell.json" --script "$work/bad6.txt"
expect_status 2 "screenshot of an unknown format"
expect_in "$err" "bad6.txt:1:14: screenshot: $work/a.gif: unknown image file extension" \
    "screenshot of an unknown format"
run_rtcl view "$work/cornell.json" --frames 1000000 --screenshot "$work/nodir/end.exr"
expect_status 2 "--screenshot into a missing folder"
expect_in "$err" "--screenshot: $work/nodir/end.exr: cannot write the image file: folder" \
    "--screenshot into a missing folder"
case "$out" in *frames*) fail "--screenshot into a missing folder: frames were rendered: $out" ;; esac
run_rtcl view "$work/cornell.json" --script "$work/missing.txt"
expect_status 2 "missing script"
expect_in "$err" "missing.txt: cannot open" "missing script"
run_rtcl view "$work/cornell.json" --step 0
expect_status 2 "--step 0"
run_rtcl view "$work/cornell.json" --frames 1 --backend nosuch
expect_status 2 "unknown backend"
expect_in "$err" "nosuch" "unknown backend"

if [ "$failures" -ne 0 ]; then
    echo "$failures check(s) failed"
    exit 1
fi
echo "all rtcl view checks passed (opencl part: $([ $opencl = 1 ] && echo run || echo skipped))"
