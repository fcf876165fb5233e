#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# count_instructions.sh BUILD_DIR N SCENE... - instructions per ray, counted
# exactly by valgrind's cachegrind (Debian valgrind; no cache simulation), of
# our packet backend's rt_trace_rays and of Embree's rtcIntersect1 /
# rtcOccluded1 over the same incoherent rays (bench --incoherent's sets:
# diffuse bounces and random rays, seed 7), one thread each (issue 32 item 4).
#
# For every scene, set, query and engine, bench_count_rays runs twice under
# cachegrind: tracing N rays, and with the same set-up tracing none
# (--no-trace); the difference over N is what one ray costs, set-up, builds
# and the first (warming) ray excluded. A noisy machine cannot blur it. The
# table prints ours, Embree's and their ratio (< 1: fewer instructions than
# Embree's). valgrind runs no AVX-512: build without it, or the packet
# backend picks AVX2 under valgrind by itself (its CPU check sees what
# valgrind emulates). N = 100000 takes minutes a scene.
set -euo pipefail
build=${1:?usage: count_instructions.sh BUILD_DIR N SCENE...}
n=${2:?usage: count_instructions.sh BUILD_DIR N SCENE...}
shift 2
prog=$build/bench/bench_count_rays
[ -x "$prog" ] || { echo "count_instructions.sh: no $prog (build first)" >&2; exit 2; }
command -v valgrind >/dev/null || { echo "count_instructions.sh: valgrind is not installed (apt-get install valgrind)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# refs ARGS...: the instructions cachegrind counts for one run of prog.
refs() {
    valgrind --tool=cachegrind --cache-sim=no --cachegrind-out-file=/dev/null "$prog" "$@" \
        >"$tmp/out" 2>"$tmp/err" || { cat "$tmp/err" >&2; exit 1; }
    sed -n 's/.*I *refs: *\([0-9,]*\).*/\1/p' "$tmp/err" | tr -d ,
}

printf '| scene | rays | query | ours (instructions/ray) | Embree | ours / Embree | hits ours / Embree |\n'
printf '|---|---|---|---:|---:|---:|---|\n'
for scene in "$@"; do
    for set in diffuse random; do
        for query in closest any; do
            declare -A per hits
            for engine in packet embree; do
                full=$(refs "$scene" $set $query $engine "$n")
                hits[$engine]=$(sed -n 's/.*rays traced, \([0-9]*\) hits/\1/p' "$tmp/out")
                base=$(refs "$scene" $set $query $engine "$n" --no-trace)
                per[$engine]=$(( (full - base) / n ))
            done
            ratio=$(awk -v a="${per[packet]}" -v b="${per[embree]}" 'BEGIN { printf "%.2f", a / b }')
            printf '| %s | %s | %s | %d | %d | %s | %s / %s |\n' "$(basename "$scene")" $set $query \
                "${per[packet]}" "${per[embree]}" "$ratio" "${hits[packet]}" "${hits[embree]}"
        done
    done
done
