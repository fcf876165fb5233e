#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# memory_section.sh [BUILD_DIR] [SHARED_SCENES] [--quick] - prints the
# Markdown section "Memory per triangle" of docs/BENCHMARKS.md (issue 31) on
# stdout: bench/report.sh calls it, and it runs alone (about 4 minutes;
# --quick: the height field only).
#
# For each mesh (a 1M-triangle height field made by the program, the
# Stanford Dragon, Sponza) and each backend, in a process of its own
# (build/bench/bench_memory): the bytes per triangle the scene and the
# renderer hold by part (rt_renderer_memory) after one frame, and after ray
# queries where those add to them (the packet backend's single-ray trees),
# the process's resident growth and its peak; then Embree's footprint for
# the same triangles (its memory monitor callback), at its default quality
# and compact. Memory is counted, not timed: the figures hold on a loaded
# machine.
set -euo pipefail
# shellcheck source=bench/common_args.sh
. "$(dirname "$0")/common_args.sh"
build=$(cd "${args[0]:-$root/build}" && pwd)
shared=$(cd "${args[1]:-$root/../shared/scenes}" && pwd)
bench=$build/bench/bench_memory
[ -x "$bench" ] || { echo "memory_section.sh: no $bench (build first)" >&2; exit 2; }
py=/usr/bin/python3
[ -x "$py" ] || py=python3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scenes=("--grid 1000000" "$shared/stanford_dragon/dragon_vrip.obj" "$shared/sponza_dabrovic/sponza.obj")
names=("height field" "Stanford Dragon" "Sponza")
[ "$quick" = 1 ] && scenes=("${scenes[0]}") && names=("${names[0]}")
for i in "${!scenes[@]}"; do
    for b in cpu packet opencl vulkan none; do
        embree=--no-embree
        [ $b = none ] && embree=
        # shellcheck disable=SC2086
        "$bench" ${scenes[$i]} --backend $b --threads 2 --json $embree 2> /dev/null |
            sed "s/^{/{\"mesh\": \"${names[$i]}\", /" >> "$tmp/rows.jsonl" || true
    done
    # shellcheck disable=SC2086
    "$bench" ${scenes[$i]} --backend packet --accel kd --threads 2 --json --no-embree --no-rays \
        2> /dev/null | sed "s/^{/{\"mesh\": \"${names[$i]}\", /" >> "$tmp/rows.jsonl" || true
done
cat <<'EOF'
## Memory per triangle (issue 31): each backend beside Embree

```
bash bench/memory_section.sh build $S   # build/bench/bench_memory MESH --backend B --json, one process each
```

Bytes per triangle after one 64x64 frame (and after 64 ray queries where they add to it).
*Scene arrays*: the scene's positions, normals and indices, which every renderer needs
(Embree shares them: they are not in its figure). *BVHs*: the renderer's per-mesh trees
(a static mesh's tree is held by the layout alone; a kd mesh keeps its tree beside the
layout). *Layout*: the flattened arrays every backend reads (nodes, triangles, ids,
normals). *Backend's copies*: the packet backend's wide BVHs (packets; with ray queries
also the single-ray trees and their triangle blocks). *All structures*: BVHs + layout +
backend's copies, the figure to set beside Embree's. *Resident growth* and *peak
growth*: the process's VmRSS after the frame and its VmHWM, less VmRSS before the
renderer was made; they include the allocator's retained memory and, for OpenCL and
Vulkan, the device driver's own (PoCL's compiler, lavapipe; their device copies live in
host memory there). *embree*: one triangle geometry sharing our arrays, built at medium
quality (Embree's default, the peer of the timed sections); *embree-c*: with
`RTC_SCENE_FLAG_COMPACT`; both from Embree's memory monitor callback (held after
`rtcCommitScene`, and the peak during it).

EOF
$py - "$tmp/rows.jsonl" <<'PY'
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1]) if l.strip()]
print("| mesh (triangles) | backend | structure | scene arrays | BVHs | layout | backend's copies | all structures | resident growth | peak growth |")
print("|---|---|---|---:|---:|---:|---:|---:|---:|---:|")
prev = None
for r in rows:
    t = r["triangles"] or 1
    # Ray queries change only the packet backend (its single-ray trees).
    same = prev and r["what"].endswith("+rays") and r["structures"] == prev["structures"]
    prev = r
    if same:
        continue
    f = lambda k: "%.1f" % (r[k] / t)
    what = r["what"].replace("+rays", " + ray queries")
    peak = f("peak_delta") if r["peak_delta"] else "-"
    rss = f("rss_delta") if r["rss_delta"] else "-"
    print("| %s (%d) | %s | %s | %s | %.1f | %s | %s | **%s** | %s | %s |" % (
        r["mesh"], r["triangles"], what, r["accel"], f("scene"),
        (r["mesh_bvhs"] + r["object_bvh"]) / t, f("layout"), f("backend"), f("structures"),
        rss, peak))
PY
