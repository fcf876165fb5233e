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

finish
