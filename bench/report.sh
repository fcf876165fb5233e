#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# report.sh [BUILD_DIR] [SHARED_SCENES] [--quick] - regenerates docs/BENCHMARKS_REPORT.md
# (and its plots in docs/plots/) from the scenes in SHARED_SCENES: every table
# is printed by a program of this repository in this run; nothing is typed by
# hand but the prose around the tables and the thesis's own figures
# (bench/thesis_numbers.tsv, cited). Also the CMake target `report`.
#
# BUILD_DIR: a Release build (default: build). SHARED_SCENES: default
# ../shared/scenes. --quick: few repetitions and the studies' quick modes, to
# check that the report runs (minutes instead of about 20); do not commit its
# output.
#
# Run it on a quiet machine: it measures wall time. It writes to a temporary
# file and replaces docs/BENCHMARKS_REPORT.md only when every step succeeded;
# docs/BENCHMARKS.md (the summary, and the sections measured by their own
# commands) is never touched.
set -euo pipefail
# shellcheck source=bench/common_args.sh
. "$(dirname "$0")/common_args.sh"
build=$(cd "${args[0]:-$root/build}" && pwd)
shared=$(cd "${args[1]:-$root/../shared/scenes}" && pwd)
rtcl=$build/rtcl
[ -x "$rtcl" ] || { echo "report.sh: no $rtcl (build first)" >&2; exit 2; }
grep -q "CMAKE_BUILD_TYPE:STRING=Release" "$build/CMakeCache.txt" 2>/dev/null ||
    grep -q "CMAKE_BUILD_TYPE:STRING=$" "$build/CMakeCache.txt" 2>/dev/null ||
    echo "report.sh: warning: $build is not a Release build" >&2

reps=7 frames=5 parse_runs=15 study_mode=
if [ $quick = 1 ]; then reps=2 frames=2 parse_runs=2 study_mode=--quick; fi
threads=2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
step() { echo "report.sh: $*" >&2; }

cpu=$(lscpu 2>/dev/null | sed -n 's/^Model name: *//p' | head -1)
mem=$(awk '/MemTotal/ {printf "%.0f GiB", $2 / 1048576}' /proc/meminfo)
# The packet tracer picks its vector width at run time; ask it which it used.
packet_isa=$("$rtcl" render "$root/scenes/cornell.json" --backend packet --width 64 \
    --height 64 --stats -o "$tmp/isa.png" 2>&1 | sed -n 's/^packets .*vectors of \(.*\)$/\1/p')
date=$(date -u +%F)
commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)

scenes_build=(cornell_box/CornellBox-Original.obj stanford_bunny/stanford-bunny.obj
              sponza_dabrovic/sponza.obj sibenik/sibenik.obj armadillo_decimated/armadillo.obj
              brainstem_anim/brainstem_00.obj robot_walk_anim/robot_walk_00.obj
              stanford_dragon/dragon_vrip_res2.obj stanford_dragon/dragon_vrip.obj)
# The render part: the shipped Cornell box, the architectural scenes from
# their interior views (shared/scenes/VIEWS.md), the scanned models from the
# default view of a bare OBJ.
scenes_render=("$root/scenes/cornell.json" "$root/bench/scenes/sponza_interior.json"
               "$root/bench/scenes/sibenik_interior.json" "$shared/stanford_bunny/stanford-bunny.obj"
               "$shared/armadillo_decimated/armadillo.obj" "$shared/brainstem_anim/brainstem_00.obj"
               "$shared/stanford_dragon/dragon_vrip_res2.obj" "$shared/stanford_dragon/dragon_vrip.obj")
parse_files=(stanford_dragon/dragon_vrip.obj stanford_dragon/dragon_vrip_res2.obj
             sponza_dabrovic/sponza.obj stanford_bunny/stanford-bunny.obj sibenik/sibenik.obj
             armadillo_decimated/armadillo.obj brainstem_anim/brainstem_00.obj
             robot_walk_anim/robot_walk_00.obj)
if [ $quick = 1 ]; then
    scenes_build=(cornell_box/CornellBox-Original.obj robot_walk_anim/robot_walk_00.obj)
    scenes_render=("$root/scenes/cornell.json")
    parse_files=(robot_walk_anim/robot_walk_00.obj)
fi

step "OBJ parsing"
"$build/bench/bench_obj_parse" -n $parse_runs "${parse_files[@]/#/$shared/}" >"$tmp/parse.txt"
step "BVH builds (rtcl bench --no-render)"
"$rtcl" bench "${scenes_build[@]/#/$shared/}" --json --reps $reps --threads $threads --no-render \
    >"$tmp/build.json"
step "renders, thesis set-up (rtcl bench)"
"$rtcl" bench "${scenes_render[@]}" --json --reps $reps --threads $threads >"$tmp/render.json"
step "renders, Whitted"
bash "$root/bench/whitted_table.sh" "$rtcl" "$shared" $frames >"$tmp/whitted.md"
step "incoherent rays (bench/incoherent_report.sh)"
if [ $quick = 1 ]; then
    bash "$root/bench/incoherent_report.sh" "$rtcl" "$shared" 4000 2 --quick >"$tmp/incoherent.md"
else
    bash "$root/bench/incoherent_report.sh" "$rtcl" "$shared" 1000000 $frames >"$tmp/incoherent.md"
fi

mkdir -p "$tmp/studies/plots"
studies=()
for name in tri_tests builders opencl_options dynamic; do
    script=$root/bench/study_$name.sh
    [ -f "$script" ] || continue
    step "study $name"
    RT_STUDY_THREADS=$threads bash "$script" "$build" "$shared" "$tmp/studies" $study_mode >&2
    studies+=("$name")
done

# Separately callable sections: each prints its Markdown on stdout and runs
# alone too (bash bench/kd_section.sh [BUILD] [SHARED] [--quick]).
sections=()
for name in kd_section memory_section; do
    step "section $name"
    quick_arg=()
    [ $quick = 1 ] && quick_arg=(--quick)
    bash "$root/bench/$name.sh" "$build" "$shared" "${quick_arg[@]}" >"$tmp/$name.md"
    sections+=("$name")
done

rel() { local p=$1; p=${p#"$root/"}; echo "${p/#$shared/\$S}"; }
render_cmd="build/rtcl bench"
for s in "${scenes_render[@]}"; do render_cmd+=" $(rel "$s")"; done

{
    cat <<EOF
# Benchmarks: the report run

The summary of every headline figure, and the measurements made by their own commands, are in
[BENCHMARKS.md](BENCHMARKS.md). Regenerated by \`bash bench/report.sh\` (or \`cmake --build build --target report\`) on
$date from commit \`$commit\`: every table below was printed by a program of this
repository in that run, and the command stands above it; only the thesis's own figures
(\`bench/thesis_numbers.tsv\`) are copied, from the thesis. Steps taken to speed the code up,
with their measurements at the time, are in \`docs/OPTIMISATION_LOG.md\`.

Machine: \`$cpu\` (lscpu model name), $(nproc) cores, $mem, Linux $(uname -r). A virtual
machine with noisy neighbours: every figure is the min and median of several runs in one
process, with warm-up runs excluded, and ratios within one run mean more than absolute
times. Every peer and every backend ran with the same thread count ($threads; PoCL runs its
own pool of one thread per core). Release build (\`cmake -S . -B build -G Ninja &&
cmake --build build\`: \`-O3\`, no \`-march\`, so the builders' NEON code through SIMDe is
SSE2-level on x86; the packet tracer is compiled for several ISAs and picks the widest this
CPU runs, here vectors of ${packet_isa:-unknown width}; Embree picks its widest ISA at run time too). \`S=../shared/scenes\`.

## OBJ parsing

\`\`\`
build/bench/bench_obj_parse -n $parse_runs ${parse_files[*]/#/\$S/}
\`\`\`

\`rt_obj_load\` whole (file read, parse, mesh build), page cache warm, min and median of
$parse_runs loads. The target is 5 M triangles/s.

\`\`\`
$(cat "$tmp/parse.txt")
\`\`\`

## BVH build (the thesis's Tables 3 and 6)

\`\`\`
build/rtcl bench ${scenes_build[*]/#/\$S/} --json --reps $reps --threads $threads --no-render | python3 bench/build_table.py
\`\`\`

$(python3 "$root/bench/build_table.py" <"$tmp/build.json")

What is timed: \`rt_bvh_build\` over the boxes of all triangles of all meshes of the scene
(one tree per scene, as the thesis timed), including the conversion of the boxes and the
output allocation; for Embree, \`rtcBuildBVH\` alone (its build primitives are prepared
outside the timer, which favours Embree slightly). Each builder runs once as a warm-up that
is not counted, then $reps times. SAH is \`rt_bvh_measure\` (the thesis's "BVH cost": Ct = 1,
Ci = 2, areas relative to the root) for every tree, Embree's included (its binary tree is
converted to our node format). All builders: 16 bins (ours), leaf size 10, Ct = 1, Ci = 2.
Embree (libembree 3, Debian 12): \`rtcBuildBVH\` at \`RTC_BUILD_QUALITY_MEDIUM\`, branching
factor 2, \`maxLeafSize\` 10, the same costs, device \`threads=$threads\`. The SAH builder's
targets: SAH within a few percent of Embree's, build time no more than Embree's, about
100,000 triangles in under 10 ms.

### The thesis's own figures (a 2013 phone)

\`\`\`
python3 bench/thesis_table.py bench/thesis_numbers.tsv < (the JSON of the build table above and the render table below)
\`\`\`

$(cat "$tmp/build.json" "$tmp/render.json" | python3 "$root/bench/thesis_table.py" "$root/bench/thesis_numbers.tsv")

Different hardware (a phone SoC against a server core), so only orders of magnitude compare.

## Rendering, the thesis's set-up: our backends and Embree (the thesis's Tables 4 and 5)

\`\`\`
$render_cmd --json --reps $reps --threads $threads | python3 bench/render_table.py
\`\`\`

One point light, primary plus shadow rays, Phong (\`rt_render\` with \`direct_only\`; \`rtcl
render --direct\`). Each backend renders one warm-up frame (BVH build, kernel compile and
upload; not counted), then $reps frames, interleaved round by round with every other backend
and Embree width (every row's frame i before any row's frame i + 1), so that a disturbance
of the shared machine falls on all of them alike; each timed frame follows an untimed frame
of the same row, so that it finds the caches as its own previous frame left them (without
that, the Embree widths, which share one BVH, warmed each other's caches, while our
backends followed one another over different trees). Our packet backend traces packets of 64 rays
(8x8 pixels) in vectors of ${packet_isa:-unknown width}. Embree (\`host/embree_trace.c\`) traces the same
primary rays (our camera formula) with \`rtcIntersect1\` or packets of 2x2, 4x2 and 4x4
pixels (\`rtcIntersect4/8/16\`), then the same shadow rays (our origin offset and t range)
with \`rtcOccluded1/4/8/16\`, and computes the same Phong terms; its scene is the layout's
triangles in world space, committed at Embree's default quality (not timed). Its time
includes ray generation and shading, as ours does. The last column checks the answers:
pixels whose colour differs from the scalar oracle's by more than 1/256 (packet and
OpenCL must be 0: they are bit-exact; Embree differs where its own triangle test rounds a
grazing shadow ray the other way).

$(python3 "$root/bench/render_table.py" <"$tmp/render.json")

## Rendering, Whitted: CPU oracle, packets, OpenCL on PoCL

\`\`\`
bash bench/whitted_table.sh build/rtcl \$S $frames
\`\`\`

1024x576, one point light, Whitted shading (Phong, shadow rays, reflection and refraction
where materials have them), $threads threads (OpenCL: PoCL's pthread device on the same
cores). Each cell is min / median of frames 2 to $frames of one process (frame 1 builds the
BVHs and, for OpenCL, uploads the scene and is excluded); Mrays/s counts all rays
(primary, shadow, secondary) over the median frame. The three backends produce
bit-identical images (tests \`test_core_packet\`, \`test_opencl_oracle\`, \`cli_opencl\`).
The packet backend traces primary and shadow rays as packets of 64 rays (8x8 pixels) and
the secondary rays one by one, as the oracle does. Box and triangle tests per ray are the
scalar oracle's (the thesis's measure); the last column is the packet tracer's own count:
vector tests (one box against a group of lanes, or one box's interval bound against the
whole packet; one triangle against a group of lanes) per primary packet, its shadow rays
included.

$(cat "$tmp/whitted.md")

## Incoherent rays, \`rtcl bench --incoherent\`: our tracers beside Embree's single rays and 16-wide streams

Per scene two sets of rays (\`cpu_ref/ray_sets.h\`, seed 7): *diffuse*, a cosine bounce from
the closest hit of the camera ray through a random pixel, and *random*, origins uniform in
the scene's bounds and directions uniform on the sphere; each traced for the closest hit
and for any hit, by \`rt_trace_rays\` on \`cpu\` (the scalar oracle) and on \`packet\` (path
auto: incoherent groups of 64 rays go one at a time through the wide BVHs), and by Embree 3's
\`rtcIntersect1\`/\`rtcOccluded1\` and \`rtcIntersect16\`/\`rtcOccluded16\` on 16 consecutive rays
(scene: the layout's triangles in world space, default quality, the incoherent-ray hint),
on the same pool of $threads threads. Each time is one whole call. Then Whitted frames of the
shipped Cornell box on \`packet\` (secondary rays through the single-ray tracer) and on
\`cpu\`. The section alone: \`bash bench/incoherent_report.sh build/rtcl ../shared/scenes\`.

$(cat "$tmp/incoherent.md")
EOF
    for name in "${studies[@]}"; do
        echo
        cat "$tmp/studies/$name.md"
    done
    for name in "${sections[@]}"; do
        echo
        cat "$tmp/$name.md"
    done
} >"$tmp/BENCHMARKS.md"

if [ $quick = 1 ]; then
    out=${REPORT_OUT:-$tmp/keep}
    mkdir -p "$out/plots"
    cp "$tmp/BENCHMARKS.md" "$out/BENCHMARKS_REPORT.md"
    cp "$tmp/studies/plots/"*.png "$out/plots/" 2>/dev/null || true
    step "quick report written to $out (docs/ untouched)"
    [ -n "${REPORT_OUT:-}" ] || cat "$out/BENCHMARKS_REPORT.md"
else
    mkdir -p "$root/docs/plots"
    cp "$tmp/studies/plots/"*.png "$root/docs/plots/" 2>/dev/null || true
    cp "$tmp/BENCHMARKS.md" "$root/docs/BENCHMARKS_REPORT.md"
    step "wrote docs/BENCHMARKS_REPORT.md and docs/plots/"
fi
