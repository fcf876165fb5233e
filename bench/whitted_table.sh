#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# whitted_table.sh RTCL SHARED_SCENES [FRAMES] - frame times of every backend on
# the shipped and shared scenes at 1024x576 (one light, Whitted shading), as
# the markdown table of docs/BENCHMARKS.md. Each cell: min / median ms of the
# frames after the first (the first, which builds the BVHs and, for OpenCL,
# uploads the scene, is excluded), and Mrays/s of the median (all rays:
# primary, shadow and secondary).
set -euo pipefail
rtcl=${1:?usage: whitted_table.sh RTCL SHARED_SCENES [FRAMES]}
shared=${2:?usage: whitted_table.sh RTCL SHARED_SCENES [FRAMES]}
frames=${3:-5}
here=$(cd "$(dirname "$0")" && pwd)
backends="cpu packet"
"$rtcl" devices --api opencl >/dev/null 2>&1 && backends="$backends opencl"

scenes=("$here/../scenes/cornell.json" "$here/../scenes/keyframes.json"
        "$here/scenes/sponza_interior.json" "$here/scenes/sibenik_interior.json"
        "$shared/stanford_bunny/stanford-bunny.obj" "$shared/armadillo_decimated/armadillo.obj"
        "$shared/stanford_dragon/dragon_vrip_res2.obj" "$shared/brainstem_anim/brainstem_00.obj")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

printf '| scene | triangles |'
for b in $backends; do printf ' %s ms (min / med) | %s Mrays/s |' "$b" "$b"; done
printf ' box tests/ray (cpu) | tri tests/ray (cpu) | packet: vector box / tri tests per primary packet |\n|---|---|'
for b in $backends; do printf -- '---|---|'; done
printf -- '---|---|---|\n'
for scene in "${scenes[@]}"; do
    [ -f "$scene" ] || continue
    tris=$("$rtcl" info "$scene" | awk '/^triangles/ {print $2}')
    printf '| %s | %s |' "$(basename "$scene")" "$tris"
    for b in $backends; do
        "$rtcl" render "$scene" --backend "$b" --frames "$frames" --stats -o "$out/x.png" \
            >"$out/$b.txt" 2>&1
        sed -n 's|^frames .* min \([0-9.]*\) ms, median \([0-9.]*\) ms (\([0-9.]*\) / \([0-9.]*\) Mrays/s).*| \1 / \2 \| \4 \||p' \
            "$out/$b.txt" | tr -d '\n'
    done
    # The thesis's counts are the scalar traversal's; the packet tracer counts
    # vector tests (one per node or triangle per group of lanes) per packet.
    awk '/^box tests\/ray/ {b = $3} /^tri tests\/ray/ {t = $3}
         END {printf " %s | %s |", b, t}' "$out/cpu.txt"
    awk '/^vector tests/ {p = $3 " / " $7} END {printf " %s |\n", p}' "$out/packet.txt"
done
