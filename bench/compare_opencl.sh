#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# compare_opencl.sh - renders every scene of the shared benchmark set with the
# CPU oracle and with OpenCL, compares the images exactly (the float EXRs pixel by
# pixel, the 8-bit PNGs byte for byte), and times cpu, packet and opencl side by side.
#
#   bench/compare_opencl.sh [RTCL] [SHARED_SCENES] [FRAMES]
#
# Bare OBJ files get the default view; Sponza and Sibenik the interior views of
# VIEWS.md (bench/scenes/*.json; their mesh paths are rewritten to
# SHARED_SCENES). 1024x576, one light. Timings: 'rtcl render --frames N' (first
# frame apart, then min and median of the others) in one process per backend.
# Prints a Markdown table.
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
rtcl=${1:-$root/build/rtcl}
shared=${2:-${RT_SHARED_SCENES:-$root/../shared/scenes}}
frames=${3:-4}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
[ -d "$shared" ] || { echo "no shared scenes at $shared"; exit 2; }

scenes=()
for obj in cornell_box/CornellBox-Original.obj stanford_bunny/stanford-bunny.obj \
           armadillo_decimated/armadillo.obj stanford_dragon/dragon_vrip.obj \
           brainstem_anim/brainstem_00.obj robot_walk_anim/robot_walk_00.obj; do
    [ -f "$shared/$obj" ] && scenes+=("$shared/$obj")
done
for json in "$root"/bench/scenes/*.json; do
    sed "s#\.\./\.\./\.\./shared/scenes#$shared#g" "$json" >"$tmp/$(basename "$json")"
    scenes+=("$tmp/$(basename "$json")")
done

echo "| scene | triangles | image (EXR, PNG) | cpu ms min / med | packet ms min / med | opencl ms min / med | cpu / packet / opencl Mrays/s (min) |"
echo "|---|---|---|---|---|---|---|"
status=0
for scene in "${scenes[@]}"; do
    name=$(basename "$scene")
    tris=$("$rtcl" info "$scene" 2>/dev/null | awk '/^triangles/ { print $2 }')
    declare -A ms=() mr=()
    for b in cpu packet opencl; do
        out=$("$rtcl" render "$scene" --backend "$b" --frames "$frames" --stats -o "$tmp/$b.exr" 2>&1) || {
            echo "| $name | $tris | $b FAILED: $(echo "$out" | tail -1) | | | | |"; status=1; continue 2; }
        line=$(grep '^frames' <<<"$out")
        ms[$b]=$(sed -E 's/.*min ([0-9.]+) ms, median ([0-9.]+) ms.*/\1 \/ \2/' <<<"$line")
        mr[$b]=$(sed -E 's/.*\(([0-9.]+) \/ .*/\1/' <<<"$line")
        [ "$b" = packet ] || "$rtcl" render "$scene" --backend "$b" -o "$tmp/$b.png" >/dev/null 2>&1
    done
    # EXR files carry metadata that may differ: compare their floats exactly
    # (rtcl compare --max-diff 0 reports the first differing pixel); the
    # 8-bit PNGs byte for byte.
    same="identical"
    "$rtcl" compare "$tmp/cpu.exr" "$tmp/opencl.exr" --max-diff 0 >"$tmp/cmp.txt" 2>&1 || {
        same="FLOATS DIFFER ($(grep 'first difference' "$tmp/cmp.txt"))"; status=1; }
    cmp -s "$tmp/cpu.png" "$tmp/opencl.png" || { same="$same, PNG DIFFERS"; status=1; }
    echo "| $name | $tris | $same | ${ms[cpu]} | ${ms[packet]} | ${ms[opencl]} | ${mr[cpu]} / ${mr[packet]} / ${mr[opencl]} |"
done
exit $status
