#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# cli_pictures.sh - what makes a picture a user is glad to see, each the same
# bits on every backend: --spp (stratified supersampling: passes averaged on
# the host), --exposure and the scene's "exposure" (a host-side 2^EV scale).
# A backend this machine cannot run is named as skipped; the cpu and packet
# backends always run.
set -u
RTCL=${RTCL:?RTCL must name the rtcl binary}
here=$(cd "$(dirname "$0")" && pwd)
. "$here/shell_check.sh"
PY=/usr/bin/python3
scene="$here/../scenes/cornell.json"
size=(--width 48 --height 32)

backends=(cpu packet)
for api in opencl vulkan; do
    if no_leak_check "$RTCL" devices --api "$api" >"$tmp/$api.txt" 2>&1; then
        backends+=("$api")
    else
        echo "skipped: the $api backend: $(head -1 "$tmp/$api.txt")"
    fi
done

# same A B WHAT: the two files are byte-identical.
same() {
    checks=$((checks + 1))
    if ! cmp -s "$1" "$2"; then
        echo "FAIL: $3 ($1 and $2 differ)"
        fails=$((fails + 1))
    fi
}

# pfm_check A B RULE: every float of PFM B relates to A's by the Python
# expression RULE over a and b (exact float32 arithmetic, numpy).
pfm_check() {
    checks=$((checks + 1))
    if ! "$PY" - "$1" "$2" "$3" <<'EOF'; then
import sys
import numpy as np

def pfm(path):
    data = open(path, "rb").read()
    head = data.split(b"\n", 3)
    return np.frombuffer(head[3], "<f4")

a, b = pfm(sys.argv[1]), pfm(sys.argv[2])
ok = a.shape == b.shape and bool(np.all(eval(sys.argv[3])))
sys.exit(0 if ok else 1)
EOF
        echo "FAIL: $1 -> $2 does not satisfy '$3'"
        fails=$((fails + 1))
    fi
}

# --spp: the same image on every backend, for a square and a non-square count.
for n in 4 3; do
    for b in "${backends[@]}"; do
        expect 0 "wrote" -- no_leak_check "$RTCL" render "$scene" "${size[@]}" --spp "$n" \
            --backend "$b" -o "$tmp/spp${n}_$b.pfm"
        [ "$b" = cpu ] || same "$tmp/spp${n}_cpu.pfm" "$tmp/spp${n}_$b.pfm" "--spp $n on $b"
    done
done
# One sample is the pixel's centre: the image without --spp.
expect 0 "wrote" -- "$RTCL" render "$scene" "${size[@]}" -o "$tmp/plain.pfm"
expect 0 "wrote" -- "$RTCL" render "$scene" "${size[@]}" --spp 1 -o "$tmp/spp1.pfm"
same "$tmp/plain.pfm" "$tmp/spp1.pfm" "--spp 1 is the pixel centre"
# Four samples move the rays: some pixel differs, none leaves the range of
# the plain image by much (the mean of four nearby rays of the same scene).
checks=$((checks + 1))
if cmp -s "$tmp/plain.pfm" "$tmp/spp4_cpu.pfm"; then
    echo "FAIL: --spp 4 gave the one-sample image"
    fails=$((fails + 1))
fi
pfm_check "$tmp/plain.pfm" "$tmp/spp4_cpu.pfm" "(b >= 0) & (b <= max(a.max(), 1.0) * 1.0001)"
expect 2 "only the shaded image" -- "$RTCL" render "$scene" "${size[@]}" --spp 4 --aov depth \
    -o "$tmp/d.pfm"
expect 2 "--spp" -- "$RTCL" render "$scene" "${size[@]}" --spp 0 -o "$tmp/x.pfm"

# --exposure: 2^EV times each value, exactly (a power of two), on every backend.
for b in "${backends[@]}"; do
    expect 0 "wrote" -- no_leak_check "$RTCL" render "$scene" "${size[@]}" --exposure 1 \
        --backend "$b" -o "$tmp/ev1_$b.pfm"
    [ "$b" = cpu ] || same "$tmp/ev1_cpu.pfm" "$tmp/ev1_$b.pfm" "--exposure 1 on $b"
done
pfm_check "$tmp/plain.pfm" "$tmp/ev1_cpu.pfm" "b == a * np.float32(2)"
expect 0 "wrote" -- "$RTCL" render "$scene" "${size[@]}" --exposure -0.5 -o "$tmp/evh.pfm"
pfm_check "$tmp/plain.pfm" "$tmp/evh.pfm" "b == a * np.float32(2.0 ** -0.5)"
# AOVs are not scaled.
expect 0 "wrote" -- "$RTCL" render "$scene" "${size[@]}" --aov depth -o "$tmp/depth.pfm"
expect 0 "wrote" -- "$RTCL" render "$scene" "${size[@]}" --aov depth --exposure 3 \
    -o "$tmp/depth3.pfm"
same "$tmp/depth.pfm" "$tmp/depth3.pfm" "--exposure leaves an AOV alone"
expect 2 "exposure|--exposure" -- "$RTCL" render "$scene" "${size[@]}" --exposure 65 \
    -o "$tmp/x.pfm"

# The scene's "exposure", and --exposure over it.
"$PY" - "$scene" "$tmp/ev_scene.json" <<'EOF'
import json, os, sys
doc = json.load(open(sys.argv[1]))
doc["exposure"] = 1
base = os.path.dirname(os.path.abspath(sys.argv[1]))
for m in doc.get("meshes", {}).values():
    if "file" in m and not os.path.isabs(m["file"]):
        m["file"] = os.path.join(base, m["file"])
json.dump(doc, open(sys.argv[2], "w"))
EOF
expect 0 "wrote" -- "$RTCL" render "$tmp/ev_scene.json" "${size[@]}" -o "$tmp/ev_scene.pfm"
same "$tmp/ev1_cpu.pfm" "$tmp/ev_scene.pfm" "the scene's exposure 1 is --exposure 1"
expect 0 "wrote" -- "$RTCL" render "$tmp/ev_scene.json" "${size[@]}" --exposure 0 \
    -o "$tmp/ev_over.pfm"
same "$tmp/plain.pfm" "$tmp/ev_over.pfm" "--exposure 0 overrides the scene's"
sed 's/"exposure": 1/"exposure": "bright"/' "$tmp/ev_scene.json" >"$tmp/ev_bad.json"
expect 2 "ev_bad.json.*exposure must be a number" -- "$RTCL" render "$tmp/ev_bad.json" \
    "${size[@]}" -o "$tmp/x.pfm"

# Emission: a surface that gives off e, with no light, no ambient and a
# black background, shows exactly e where it covers the pixel, on every
# backend.
cat >"$tmp/quad.obj" <<'EOF'
v -1 -1 0
v 1 -1 0
v 1 1 0
v -1 1 0
f 1 2 3
f 1 3 4
EOF
cat >"$tmp/glow.json" <<EOF
{"camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 40,
            "width": 16, "height": 16},
 "background": [0, 0, 0], "ambient": [0, 0, 0], "lights": [],
 "materials": {"glow": {"color": [1, 1, 1], "diffuse": 0, "emission": [0.25, 0.5, 0.75]}},
 "meshes": {"quad": {"file": "$tmp/quad.obj"}},
 "objects": [{"mesh": "quad", "material": "glow"}]}
EOF
for b in "${backends[@]}"; do
    expect 0 "wrote" -- no_leak_check "$RTCL" render "$tmp/glow.json" --backend "$b" \
        -o "$tmp/glow_$b.pfm"
    [ "$b" = cpu ] || same "$tmp/glow_cpu.pfm" "$tmp/glow_$b.pfm" "emission on $b"
done
pfm_check "$tmp/glow_cpu.pfm" "$tmp/glow_cpu.pfm" \
    "np.all(b.reshape(-1, 3) == np.array([0.25, 0.5, 0.75], np.float32), axis=1).sum() >= 64"
sed 's/"emission": \[0.25, 0.5, 0.75\]/"emission": [0.25, -1, 0.75]/' "$tmp/glow.json" \
    >"$tmp/glow_bad.json"
expect 2 "glow_bad.json.*emission" -- "$RTCL" render "$tmp/glow_bad.json" -o "$tmp/x.pfm"

# MTL Ke: a bare OBJ whose ceiling panel emits gets one light just below the
# panel (the area-weighted centre, moved off it along its normal) and no
# other; a bare OBJ without emitters, one light above and right of the camera.
cat >"$tmp/room.obj" <<'EOF'
mtllib room.mtl
v -1 0 -1
v 1 0 -1
v 1 0 1
v -1 0 1
v -1 2 -1
v 1 2 -1
v 1 2 1
v -1 2 1
v -0.2 1.99 -0.2
v 0.2 1.99 -0.2
v 0.2 1.99 0.2
v -0.2 1.99 0.2
usemtl wall
f 1 2 3 4
f 5 8 7 6
f 1 5 6 2
usemtl lamp
f 9 10 11 12
EOF
cat >"$tmp/room.mtl" <<'EOF'
newmtl wall
Kd 0.8 0.8 0.8
newmtl lamp
Kd 0.8 0.8 0.8
Ke 10 5 2.5
EOF
expect 0 '"lights": 1, "light_list": \[\{"position": \[-?[0-9.e-]+, 1\.98[0-9]*, -?[0-9.e-]+\], "color": \[1, 0\.5, 0\.25\]\}\]' \
    -- "$RTCL" info "$tmp/room.obj" --json
for b in "${backends[@]}"; do
    expect 0 "wrote" -- no_leak_check "$RTCL" render "$tmp/room.obj" "${size[@]}" \
        --backend "$b" -o "$tmp/room_$b.pfm"
    [ "$b" = cpu ] || same "$tmp/room_cpu.pfm" "$tmp/room_$b.pfm" "the lamp-lit room on $b"
done
grep -v -E '^(mtllib|usemtl)' "$tmp/room.obj" | head -17 >"$tmp/plain_room.obj"
"$RTCL" info "$tmp/plain_room.obj" --json >"$tmp/plain_room.json"
checks=$((checks + 1))
if ! "$PY" - "$tmp/plain_room.json" <<'EOF'; then
import json, sys
import numpy as np
d = json.load(open(sys.argv[1]))
cam = d["camera"]
p, a, up = (np.array(cam[k], np.float64) for k in ("position", "look_at", "up"))
f = (a - p) / np.linalg.norm(a - p)
r = np.cross(f, up); r /= np.linalg.norm(r)
u = np.cross(r, f)
want = p + (0.3 * u + 0.2 * r) * np.linalg.norm(a - p)
got = np.array(d["light_list"][0]["position"])
sys.exit(0 if d["lights"] == 1 and np.allclose(got, want, rtol=0, atol=1e-5) else 1)
EOF
    echo "FAIL: a bare OBJ's default light is not beside its camera: $(cat "$tmp/plain_room.json")"
    fails=$((fails + 1))
fi

finish
