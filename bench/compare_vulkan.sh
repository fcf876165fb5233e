#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# compare_vulkan.sh - renders every scene of the shared benchmark set with the
# CPU oracle and with the Vulkan backend, compares the images exactly (the
# float EXRs pixel by pixel, the 8-bit PNGs byte for byte), and times both.
#
#   bench/compare_vulkan.sh [RTCL] [SHARED_SCENES] [FRAMES] [DEVICE]
#
# The scenes and views of bench/compare_opencl.sh (bare OBJ files with the
# default view; Sponza and Sibenik with the interior views of VIEWS.md),
# 1024x576, one light, Whitted. Timings: 'rtcl render --frames N' (first
# frame apart, then min and median of the others) in one process per
# backend (the first frame holds the driver's shader compile). DEVICE: a Vulkan
# device (index or name) [the default]. Prints a Markdown table; exit status
# 1 when an image differs.
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
rtcl=${1:-$root/build/rtcl}
shared=${2:-${RT_SHARED_SCENES:-$root/../shared/scenes}}
frames=${3:-3}
vk=vulkan${4:+:$4}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
[ -d "$shared" ] || { echo "no shared scenes at $shared"; exit 2; }
shared=$(cd "$shared" && pwd) # the JSON scenes are rewritten to name it

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

device=$("$rtcl" devices --api vulkan ${4:+--device "$4"} 2>&1 | sed -n 's/^  device [0-9]*: //p' | head -1)
echo "Vulkan device: ${device:-none}"
echo
echo "| scene | triangles | image (EXR, PNG) | cpu ms min / med | vulkan ms min / med | cpu / vulkan Mrays/s (min) |"
echo "|---|---|---|---|---|---|"
status=0
for scene in "${scenes[@]}"; do
    name=$(basename "$scene")
    tris=$("$rtcl" info "$scene" 2>/dev/null | awk '/^triangles/ { print $2 }')
    declare -A ms=() mr=()
    for b in cpu "$vk"; do
        key=${b%%:*}
        out=$("$rtcl" render "$scene" --backend "$b" --frames "$frames" --stats -o "$tmp/$key.exr" 2>&1) || {
            echo "| $name | $tris | $b FAILED: $(echo "$out" | tail -1) | | | | |"; status=1; continue 2; }
        line=$(grep '^frames' <<<"$out")
        ms[$key]=$(sed -E 's/.*min ([0-9.]+) ms, median ([0-9.]+) ms.*/\1 \/ \2/' <<<"$line")
        mr[$key]=$(sed -E 's/.*\(([0-9.]+) \/ .*/\1/' <<<"$line")
        "$rtcl" render "$scene" --backend "$b" -o "$tmp/$key.png" >/dev/null 2>&1
    done
    same="identical"
    "$rtcl" compare "$tmp/cpu.exr" "$tmp/vulkan.exr" --max-diff 0 >"$tmp/cmp.txt" 2>&1 || {
        same="FLOATS DIFFER ($(grep 'first difference' "$tmp/cmp.txt"))"; status=1; }
    cmp -s "$tmp/cpu.png" "$tmp/vulkan.png" || { same="$same, PNG DIFFERS"; status=1; }
    echo "| $name | $tris | $same | ${ms[cpu]} | ${ms[vulkan]} | ${mr[cpu]} / ${mr[vulkan]} |"
done
exit $status
