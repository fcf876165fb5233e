#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# gpu_check.sh - one run, on a machine with a GPU, of everything that needs
# one: build, list the devices, render the shared scenes and run the
# robustness suite on every OpenCL device in both maths profiles (native,
# portable) and on every Vulkan device (portable), in both denormal policies, compare each result with the CPU
# oracle of the same policy (identical, or the first differing pixel with
# both values), time the frames, and write one report file.
#
#   bench/gpu_check.sh [REPORT] [SHARED_SCENES]
#
# REPORT defaults to gpu_check_report.md in the current folder. Needs cmake,
# a C/C++ compiler and an OpenCL ICD loader with a driver; OpenImageIO,
# jansson and Embree are optional (without OpenImageIO images are PFM;
# without jansson the JSON interior views are skipped and the bare OBJ scenes
# run). Aims at under 8 minutes: each render is one warm-up frame and
# FRAMES (default 3) timed frames at 1024x576; the robustness suite runs the
# watertight test only. CI never runs this script.
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
report=$(realpath -m "${1:-gpu_check_report.md}")
shared=${2:-${RT_SHARED_SCENES:-$root/../shared/scenes}}
frames=${FRAMES:-3}
build=${BUILD:-$root/build-gpu}
start=$(date +%s)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
say() { echo "$*" | tee -a "$report"; }
: > "$report"

say "# gpu_check: $(date -u '+%Y-%m-%d %H:%M UTC') on $(hostname)"
say ""
say "commit $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown); CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ //'), $(nproc) cores"
command -v nvidia-smi > /dev/null && say "GPU: $(nvidia-smi --query-gpu=name,driver_version --format=csv,noheader 2>/dev/null | head -3 | tr '\n' ';')"

# ---- build ------------------------------------------------------------------
gen=""; command -v ninja > /dev/null && gen="-G Ninja"
# shellcheck disable=SC2086
if ! { cmake -S "$root" -B "$build" $gen -DCMAKE_BUILD_TYPE=Release > "$tmp/configure.log" 2>&1 &&
       cmake --build "$build" -j "$(nproc)" --target rtcl > "$tmp/build.log" 2>&1; }; then
    say ""; say "BUILD FAILED:"; tail -30 "$tmp/configure.log" "$tmp/build.log" | tee -a "$report"; exit 2
fi
rtcl=$build/rtcl
say "build: $(( $(date +%s) - start )) s ($build)"

# Image format: PFM where this build writes it (no OpenImageIO needed), else EXR.
ext=pfm
"$rtcl" render builtin:cornell --width 8 --height 8 -o "$tmp/probe.pfm" > /dev/null 2>&1 || ext=exr

# ---- devices ----------------------------------------------------------------
say ""; say "## Devices"; say ""; say '```'
"$rtcl" devices --api opencl 2>&1 | tee -a "$report" > "$tmp/devices.txt"
"$rtcl" devices --api vulkan 2>&1 | tee -a "$report" > "$tmp/vk_devices.txt"
say '```'
# Device backends to check: "opencl:N" and "vulkan:N" for every device found.
targets=()
for d in $(sed -n -E 's/^  device ([0-9]+): .*/\1/p' "$tmp/devices.txt"); do targets+=("opencl:$d"); done
for d in $(sed -n -E 's/^  device ([0-9]+): .*/\1/p' "$tmp/vk_devices.txt"); do targets+=("vulkan:$d"); done
[ "${#targets[@]}" -gt 0 ] || { say "no OpenCL or Vulkan device: nothing to check"; exit 2; }

# ---- scenes -----------------------------------------------------------------
scenes=()
for obj in cornell_box/CornellBox-Original.obj stanford_bunny/stanford-bunny.obj \
           armadillo_decimated/armadillo.obj stanford_dragon/dragon_vrip.obj \
           brainstem_anim/brainstem_00.obj robot_walk_anim/robot_walk_00.obj; do
    [ -f "$shared/$obj" ] && scenes+=("$shared/$obj")
done
for json in "$root"/bench/scenes/*.json; do
    sed "s#\.\./\.\./\.\./shared/scenes#$shared#g" "$json" > "$tmp/$(basename "$json")"
    if "$rtcl" info "$tmp/$(basename "$json")" > /dev/null 2>&1; then
        scenes+=("$tmp/$(basename "$json")")
    else
        say "skipped $(basename "$json"): $("$rtcl" info "$tmp/$(basename "$json")" 2>&1 | tail -1)"
    fi
done
scenes+=(builtin:cornell builtin:keyframes)

# render SCENE OUT ARGS...: one frame to OUT; prints "min median Mrays" of the timed frames.
render() {
    local scene=$1 out=$2
    shift 2
    local log
    log=$("$rtcl" render "$scene" "$@" --frames "$((frames + 1))" --stats -o "$out" 2>&1) || {
        echo "FAILED: $(tail -1 <<< "$log")"; return 1; }
    sed -n -E 's/^frames.*min ([0-9.]+) ms, median ([0-9.]+) ms.*\(([0-9.]+) \/.*/\1 \2 \3/p' <<< "$log"
}
# compare A B: "identical" or the first differing pixel.
compare() {
    if "$rtcl" compare "$1" "$2" --max-diff 0 > "$tmp/cmp.txt" 2>&1; then echo identical
    else echo "DIFFERS: $(grep -i -m1 'first' "$tmp/cmp.txt" || tail -1 "$tmp/cmp.txt")"; fi
}

status=0
say ""; say "## Images against the CPU oracle (1024x576, Whitted; ms: min / median of $frames frames)"
say ""
say "| scene | policy | cpu ms | device | profile | result | device ms | Mrays/s | portable / native |"
say "|---|---|---|---|---|---|---|---|---|"
for scene in "${scenes[@]}"; do
    name=$(basename "$scene")
    for policy in preserve flush; do
        cpu=$(render "$scene" "$tmp/cpu.$ext" --backend cpu --denormals "$policy") || {
            say "| $name | $policy | $cpu | | | | | | |"; status=1; continue; }
        read -r cmin cmed _ <<< "$cpu"
        for d in "${targets[@]}"; do
            declare -A med=()
            profiles="native portable"
            [ "${d%%:*}" = vulkan ] && profiles=portable # Vulkan promises no correctly rounded division
            for profile in $profiles; do
                r=$(render "$scene" "$tmp/dev.$ext" --backend "$d" \
                    --device-math "$profile" --denormals "$policy") || {
                    say "| $name | $policy | $cmin / $cmed | $d | $profile | $r | | | |"; status=1; continue; }
                read -r dmin dmed dmr <<< "$r"
                med[$profile]=$dmed
                res=$(compare "$tmp/cpu.$ext" "$tmp/dev.$ext")
                [ "$res" = identical ] || status=1
                ratio=""
                [ "$profile" = portable ] && [ -n "${med[native]:-}" ] &&
                    ratio=$(awk -v p="$dmed" -v n="${med[native]}" 'BEGIN { if (n > 0) printf "%.2f", p / n }')
                say "| $name | $policy | $cmin / $cmed | $d | $profile | $res | $dmin / $dmed | $dmr | $ratio |"
            done
        done
    done
done

# ---- robustness suite -------------------------------------------------------
say ""; say "## Robustness suite (watertight), every device, both profiles and policies"; say ""
words="cpu cpu+flush"
for d in "${targets[@]}"; do
    profiles="native portable"
    [ "${d%%:*}" = vulkan ] && profiles=portable
    for p in $profiles; do words="$words $d+$p $d+$p+flush"; done
done
mkdir -p "$tmp/robust"
if RTCL=$rtcl RT_SOURCE_DIR=$root RT_BINARY_DIR=$tmp/robust RT_ROBUST_BACKENDS=$words \
   RT_ROBUST_TRI_TESTS=watertight bash "$root/tests/cli_robust.sh" > "$tmp/robust.log" 2>&1; then
    say "passed: $(tail -1 "$tmp/robust.log")"
else
    status=1; say "FAILED:"; say '```'; grep -E 'FAIL|checks' "$tmp/robust.log" | head -40 | tee -a "$report"; say '```'
fi

say ""; say "total $(( $(date +%s) - start )) s; $([ $status = 0 ] && echo 'every result identical to the oracle' || echo 'SOME RESULTS DIFFER OR FAILED (above)')"
echo "report: $report"
exit $status
