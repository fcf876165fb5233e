# SPDX-License-Identifier: Apache-2.0
# cli_gltf.sh - glTF scenes through rtcl: 'rtcl render BrainStem.glb --time
# 1.0' works; 'rtcl info' lists the clips; --animation picks one by name or
# index and refuses an unknown one, listing them; frame k of 'rtcl animate'
# is bit for bit 'rtcl render --time t' for every update policy; every
# backend built here (cpu, packet, and opencl and vulkan where a device is
# found) gives the CPU oracle's image of both shared models at a time; trace
# takes --time; a JSON scene takes a .glb as a mesh. Skips without the
# shared scenes.
. "$(dirname "$0")/shell_check.sh"
: "${RTCL:?RTCL must name the rtcl binary}"
shared="${RT_SHARED_SCENES:-}"
brain="$shared/brainstem_anim/BrainStem.glb"
robot="$shared/robot_walk_anim/RobotExpressive.glb"
if [ ! -f "$brain" ] || [ ! -f "$robot" ]; then
    echo "skipped: the shared glTF scenes are not here (RT_SHARED_SCENES=$shared)"; exit 77
fi
size=(--width 96 --height 54)

same() { # same A B WHAT: the two images are identical
    checks=$((checks + 1))
    if ! "$RTCL" compare "$1" "$2" --max-diff 0 >/dev/null 2>&1; then
        echo "FAIL: $3: $1 and $2 differ"; "$RTCL" compare "$1" "$2" | head -5
        fails=$((fails + 1))
    fi
}

# The issue's command, at full size.
expect 0 "wrote .*a.png" -- "$RTCL" render "$brain" --time 1.0 -o "$tmp/a.png"

# Clips.
expect 0 "clips +1 \(playing 0\)" -- "$RTCL" info "$brain"
expect 0 "0 +animation_0 +34.88" -- "$RTCL" info "$brain"
expect 0 "10 +Walking +0.958333 s" -- "$RTCL" info "$robot"
expect 0 "clips +14 \(playing 10\)" -- "$RTCL" info "$robot" --animation Walking
expect 0 "clips +14 \(playing 3\)" -- "$RTCL" info "$robot" --animation 3
expect 0 '"clips": \[\{"name": "Dance", "duration": 3.3333' -- "$RTCL" info "$robot" --json
expect 2 "no animation clip 'Flying'.*Dance, Death" -- "$RTCL" render "$robot" --animation Flying \
    "${size[@]}" -o "$tmp/x.png"
expect 2 "no animation clips" -- "$RTCL" render builtin:cornell --animation 0 "${size[@]}" \
    -o "$tmp/x.png"

# Time changes the picture; the same time gives the same bits.
expect 0 "" -- "$RTCL" render "$brain" "${size[@]}" --time 0.4 -o "$tmp/t04.exr"
expect 0 "" -- "$RTCL" render "$brain" "${size[@]}" --time 1.2 -o "$tmp/t12.exr"
expect 1 "" -- "$RTCL" compare "$tmp/t04.exr" "$tmp/t12.exr" --max-diff 0

# animate frame k == render --time k/5, every policy (BrainStem 0, 0.2, 0.4 s).
for k in 0 1 2; do
    t=$(awk "BEGIN { printf \"%.17g\", $k / 5 }")
    expect 0 "" -- "$RTCL" render "$brain" "${size[@]}" --time "$t" -o "$tmp/ref_$k.exr"
done
for policy in rebuild refit fast auto; do
    mkdir -p "$tmp/$policy"
    expect 0 "" -- "$RTCL" animate "$brain" --fps 5 --frames 3 "${size[@]}" --update "$policy" \
        -o "$tmp/$policy/f_%d.exr"
    for k in 0 1 2; do same "$tmp/$policy/f_$k.exr" "$tmp/ref_$k.exr" "animate --update $policy"; done
done
# The robot through a chosen clip.
expect 0 "" -- "$RTCL" render "$robot" --animation Walking "${size[@]}" --time 0.2875 -o "$tmp/rw.exr"
mkdir -p "$tmp/rwa"
expect 0 "" -- "$RTCL" animate "$robot" --animation Walking --fps 10 --frame-range 2:3 --frames 4 \
    "${size[@]}" -o "$tmp/rwa/f_%d.exr"
expect 0 "" -- "$RTCL" render "$robot" --animation Walking "${size[@]}" --time 0.2 -o "$tmp/rw02.exr"
same "$tmp/rwa/f_2.exr" "$tmp/rw02.exr" "robot animate frame 2"

# Every backend gives the oracle's image.
backends="packet"
if "$RTCL" devices --api opencl >/dev/null 2>&1; then backends="$backends opencl"; else
    echo "note: opencl skipped (no OpenCL device or backend)"; fi
if no_leak_check "$RTCL" devices --api vulkan >/dev/null 2>&1; then backends="$backends vulkan"; else
    echo "note: vulkan skipped (no Vulkan device or backend)"; fi
for scene in brain robot; do
    file=$brain; clip=()
    [ "$scene" = robot ] && file=$robot && clip=(--animation Walking)
    expect 0 "" -- "$RTCL" render "$file" "${clip[@]}" "${size[@]}" --time 0.6 --backend cpu \
        -o "$tmp/$scene-cpu.exr"
    for b in $backends; do
        leaks=()
        [ "$b" = vulkan ] && leaks=(no_leak_check)
        expect 0 "" -- "${leaks[@]}" "$RTCL" render "$file" "${clip[@]}" "${size[@]}" --time 0.6 \
            --backend "$b" -o "$tmp/$scene-$b.exr"
        same "$tmp/$scene-$b.exr" "$tmp/$scene-cpu.exr" "$scene on $b"
    done
done

# trace takes --time: a ray down through the figure hits at 0 and at 1 s.
printf '0 5 0 0 -1 0 0 100\n0.1 5 0.05 0 -1 0 0 100\n' >"$tmp/rays.txt"
expect 0 "" -- "$RTCL" trace "$brain" --rays "$tmp/rays.txt" --time 0 -o "$tmp/h0.txt"
expect 0 "" -- "$RTCL" trace "$brain" --rays "$tmp/rays.txt" --time 1.0 -o "$tmp/h1.txt"
expect 0 "^1 " -- head -1 "$tmp/h0.txt"

# A glTF file as a mesh of a JSON scene: its rest pose (clip 0, time 0) as
# one mesh with per-triangle materials, twice under two transforms.
cat >"$tmp/two.json" <<JSON
{"materials": {"m": {"color": [1, 1, 1]}},
 "meshes": {"robot": {"file": "$brain"}},
 "objects": [{"mesh": "robot", "material": "m"},
             {"mesh": "robot", "material": "m", "transform": {"translate": [2, 0, 0]}}]}
JSON
expect 0 "triangles +123332 in the current frame" -- "$RTCL" info "$tmp/two.json"
expect 0 "per-triangle materials on" -- "$RTCL" info "$tmp/two.json"
expect 0 "" -- "$RTCL" render "$tmp/two.json" "${size[@]}" -o "$tmp/two.png"
printf '{"meshes": {"x": {"file": "missing.glb"}}, "objects": [{"mesh": "x"}]}' >"$tmp/missing.json"
expect 2 "missing.glb.*mesh file named at .*missing.json" -- "$RTCL" info "$tmp/missing.json"

# bench --animate plays a glTF clip: every policy's images are the sah policy's.
expect 0 "rtcl +refit .*= sah" -- "$RTCL" bench --animate "$robot" --animation Walking --frames 2 \
    --fps 10 --reps 1 --threads 1 --width 64 --height 36
expect 0 "rtcl +auto .*= sah" -- "$RTCL" bench --animate "$brain" --frames 2 --reps 1 \
    --threads 1 --width 64 --height 36
expect 2 "--animation need --animate" -- "$RTCL" bench "$robot" --animation Walking

# The viewer plays a chosen clip (under Xvfb, where it is here and the viewer is built).
if command -v xvfb-run >/dev/null && "$RTCL" view --help 2>/dev/null | grep -q -- "--play"; then
    # SDL's software renderer, as cli_view.sh: no Mesa (which leaks when
    # unloaded, in the sanitizer build's leak check).
    expect 0 "view: 6 frames" -- xvfb-run -a -s "-screen 0 640x480x24" \
        env SDL_RENDER_DRIVER=software SDL_FRAMEBUFFER_ACCELERATION=0 \
        ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}use_sigaltstack=0" "$RTCL" view "$robot" --play --animation Dance --frames 6 \
        --width 64 --height 36 --backend cpu
else
    echo "note: rtcl view skipped (no xvfb-run, or no viewer in this build)"
fi

# A file that is not glTF inside refuses with its name.
printf 'glTF\002\000\000\000' >"$tmp/bad.glb"
expect 2 "bad.glb" -- "$RTCL" info "$tmp/bad.glb"
finish
