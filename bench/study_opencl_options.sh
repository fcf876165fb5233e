#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# study_opencl_options.sh BUILD_DIR SHARED_SCENES OUT_DIR [--quick] - OpenCL
# kernel build options against image error (issue 7, study c). Writes
# OUT_DIR/opencl_options.md and OUT_DIR/plots/opencl_options.png;
# bench/report.sh runs it. --quick: a small image, one frame.
#
# The variants (rtcl render --cl-options, appended to the exact build's
# options): none (the exact build), -cl-mad-enable, -cl-fast-relaxed-math,
# -DRT_NATIVE_MATH (division and square root of kernels/rt_shared.h as
# native_divide and native_sqrt), and the last two together.
# bench/bench_cl_options renders each (and the CPU oracle) interleaved frame
# by frame; each image is compared with the oracle's by rtcl compare, as
# float EXR and as 8-bit PNG. Without an OpenCL device the section says so.
set -euo pipefail
. "$(dirname "$0")/common_study_args.sh"
# The study's option variants ("" is the exact build).
variants=("" -cl-mad-enable -cl-fast-relaxed-math -DRT_NATIVE_MATH "-cl-fast-relaxed-math -DRT_NATIVE_MATH")
if [ $quick = 1 ]; then
    frames=1 width=256 height=144
    scenes=("$root/scenes/cornell.json")
else
    frames=7 width=1024 height=576
    scenes=("$root/scenes/cornell.json" "$root/bench/scenes/sponza_interior.json"
            "$shared/stanford_bunny/stanford-bunny.obj")
fi
"$build/rtcl" devices --api opencl >"$data/devices.txt" 2>&1 || true
if "$build/rtcl" devices --api opencl >/dev/null 2>&1; then
    i=0
    for s in "${scenes[@]}"; do
        i=$((i + 1))
        echo "study_opencl_options: $(basename "$s")" >&2
        mkdir -p "$data/scene$i"
        "$build/bench/bench_cl_options" "$s" --out "$data/scene$i" --width $width --height $height \
            --frames $frames --threads $threads "${variants[@]}" >"$data/scene$i.tsv"
        echo "$s" >"$data/scene$i.name"
    done
fi
cmd="bash bench/study_opencl_options.sh build \$S OUT"
[ $quick = 1 ] && cmd+=" --quick"
python3 "$root/bench/study_report.py" opencl_options "$data" "$out" --command "$cmd" --root "$root" \
    --shared "$shared" --runs $frames --threads $threads --width $width --height $height \
    --rtcl "$build/rtcl"
