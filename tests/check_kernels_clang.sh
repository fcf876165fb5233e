#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# check_kernels_clang.sh - the OpenCL kernels compile without a single
# warning for the x86 targets PoCL picks on common CPUs: baseline x86-64
# (SSE2), haswell (AVX2) and skylake-avx512, with the packet kernel's 16, 8
# and 4 lanes, with the scene switches off and on (kd-tree meshes too), and
# in the portable maths profile with and without flushed denormals. On a
# fresh machine PoCL compiles them at the first OpenCL frame; a warning
# there reached the user's terminal as "N warnings generated." (issue 19).
# Any clang warns the way PoCL's does: it is clang inside. Skips without
# clang.
set -u
src=${RT_SOURCE_DIR:-$(cd "$(dirname "$0")/.." && pwd)}
cc=""
for c in clang-15 clang-16 clang-14 clang; do command -v "$c" >/dev/null && { cc=$c; break; }; done
[ -n "$cc" ] || { echo "skipped: no clang to compile OpenCL C with"; exit 77; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
# One program, as the backend builds it on CPU devices.
cat "$src/kernels/rt_single_ray.cl" "$src/kernels/rt_ray_packet.cl" > "$dir/program.cl"
fail=0 runs=0
for cpu in x86-64 haswell skylake-avx512; do
    for lanes in 16 8 4; do
        for flags in "0u 1u 1u 0u" "15u 0u 3u 1u -DRT_PORTABLE_MATH" \
            "15u 0u 3u 0u -DRT_FLUSH_DENORMALS -DRT_PORTABLE_MATH" "15u 0u 7u 0u"; do
            set -- $flags
            out=$("$cc" -x cl -cl-std=CL1.2 -Xclang -finclude-default-header \
                -target x86_64-pc-linux-gnu -march="$cpu" -O0 -S -emit-llvm -o /dev/null \
                -I "$src/kernels" -Dcl_khr_fp64=1 -cl-fp32-correctly-rounded-divide-sqrt \
                -DRT_STATIC_FLAGS=$1 -DRT_STATIC_INST_SET=$2 -DRT_STATIC_INST_MASK=$3 \
                -DRT_STATIC_TRI_METHOD=$4 ${5:-} ${6:-} -DRT_PK_LANES=$lanes "$dir/program.cl" 2>&1)
            rc=$?
            runs=$((runs + 1))
            if [ $rc -ne 0 ] || [ -n "$out" ]; then
                echo "FAIL: -march=$cpu lanes $lanes switches $flags (exit $rc):"
                echo "$out" | grep -E "warning|error" | sort | uniq -c | sort -rn | head -5
                echo "$out" | tail -1
                fail=1
            fi
        done
    done
done
[ $fail -eq 0 ] && echo "ok: $runs builds with $cc, no warnings"
exit $fail
