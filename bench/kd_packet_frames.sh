#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# kd_packet_frames.sh - frame times of the packet tracers on kd meshes
# (issue 18): ROUNDS interleaved rounds, each running every configuration
# once per scene ('rtcl render SCENE --backend B --accel A --direct --frames
# 8 --threads 2': primary plus shadow rays, min and median of the 7 frames
# after the first), so that a busy machine slows them alike; then a Markdown
# table of the min over the rounds' mins and the median of their medians.
# BASE is an rtcl from before the packet kd traversal (its packet backend
# traced kd meshes lane by lane; its OpenCL CPU devices ran the one-ray
# kernels for kd layouts); NEW the one measured.
#
# usage: bench/kd_packet_frames.sh NEW_RTCL BASE_RTCL ROUNDS SCENE...
set -eu
new=$1 base=$2 rounds=$3
shift 3
out=$(mktemp)
trap 'rm -f "$out" "$out.ppm"' EXIT
configs="base:packet:kd new:packet:kd new:packet:bvh base:opencl:kd new:opencl:kd new:opencl:bvh"
for _ in $(seq "$rounds"); do
    for scene in "$@"; do
        for cfg in $configs; do
            IFS=: read -r which backend accel <<< "$cfg"
            rtcl=$new
            [ "$which" = base ] && rtcl=$base
            line=$("$rtcl" render "$scene" --backend "$backend" --accel "$accel" --direct \
                --frames 8 --threads 2 -o "$out.ppm" 2>&1 | grep '^frames')
            echo "$(basename "$scene" .json) $which $backend $accel $line" >> "$out"
        done
    done
done
python3 - "$out" << 'PY'
import re, statistics, sys, collections
runs = collections.OrderedDict()
for line in open(sys.argv[1]):
    scene, which, backend, accel = line.split()[:4]
    m = re.search(r"min ([\d.]+) ms, median ([\d.]+) ms", line)
    runs.setdefault((scene, backend, which, accel), []).append((float(m[1]), float(m[2])))
print("| scene | backend | build | meshes | min ms | median ms | vs new kd (median) |")
print("|---|---|---|---|---:|---:|---:|")
for (scene, backend, which, accel), v in runs.items():
    med = statistics.median(x[1] for x in v)
    ref = statistics.median(x[1] for x in runs[(scene, backend, "new", "kd")])
    print(f"| {scene} | {backend} | {which} | {accel} | {min(x[0] for x in v):.1f} | {med:.1f} | "
          f"{med / ref:.2f}x |")
PY
