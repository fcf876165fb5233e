#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# kd_section.sh [BUILD_DIR] [SHARED_SCENES] [--quick] - prints the Markdown
# section "SAH kd-trees against the BVH in one run" of docs/BENCHMARKS.md
# (issue 18) on stdout: bench/report.sh calls it, and it runs alone (about
# 20 minutes on a loaded 2-core machine; --quick: the shipped Cornell box,
# one round, to check that it runs) when only this section is wanted.
#
# In one run, on the Bunny and the two architectural interiors of the shared
# scenes (their VIEWS.md views):
# - builds and frames: bench/kd_report.sh (rounds alternating 'rtcl bench
#   --accel bvh' and '--accel kd' at 512x288: BVH builders beside kd-exact
#   and kd-binned, and frame ms, Mrays/s, steps and triangle tests per ray of
#   each backend with BVH and with kd meshes, primary plus shadow rays);
# - incoherent ray queries: build/bench/bench_kd_rays (diffuse bounces and
#   random rays, closest and any hit, cpu and packet, kd against BVH);
# - the thesis's quoted Bunny figures (bench/thesis_kd_numbers.tsv) beside
#   this run's kd builds of the Bunny.
set -euo pipefail
# shellcheck source=bench/common_args.sh
. "$(dirname "$0")/common_args.sh"
build=$(cd "${args[0]:-$root/build}" && pwd)
shared=$(cd "${args[1]:-$root/../shared/scenes}" && pwd)
rtcl=$build/rtcl
rays_bench=$build/bench/bench_kd_rays
for p in "$rtcl" "$rays_bench"; do
    [ -x "$p" ] || { echo "kd_section.sh: no $p (build first)" >&2; exit 2; }
done
rounds=${KD_ROUNDS:-2} reps=${KD_REPS:-3} nrays=${KD_RAYS:-200000} threads=2
scenes=("$shared/stanford_bunny/stanford-bunny.obj" "$root/bench/scenes/sponza_interior.json"
        "$root/bench/scenes/sibenik_interior.json")
if [ $quick = 1 ]; then
    rounds=1 reps=1 nrays=20000
    scenes=("$root/scenes/cornell.json")
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
step() { echo "kd_section.sh: $*" >&2; }
rel() { local p=$1; p=${p#"$root/"}; echo "${p/#$shared/\$S}"; }

step "builds and frames (bench/kd_report.sh, $rounds rounds)"
KD_KEEP_JSON=$tmp KD_BENCH_ARGS="--width 512 --height 288 --threads $threads" \
    bash "$root/bench/kd_report.sh" "$rtcl" "$rounds" "$reps" "${scenes[@]}" |
    sed -e "s|$root/||g" -e "s|$shared|\$S|g" > "$tmp/frames.md"
step "incoherent ray queries (bench_kd_rays, $nrays rays)"
"$rays_bench" --json --rays "$nrays" --reps "$reps" --threads $threads "${scenes[@]}" \
    > "$tmp/rays.jsonl"

cpu=$(lscpu 2>/dev/null | sed -n 's/^Model name: *//p' | head -1)
load=$(cut -d' ' -f1-3 /proc/loadavg)
commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)
names=""
for s in "${scenes[@]}"; do names="$names $(rel "$s")"; done
cat << EOF
## SAH kd-trees against the BVH in one run (issue 18)

Measured $(date -u +%F) on ${cpu:-this machine} ($(nproc) cores, shared with other work: load
average $load at the end), commit $commit, $threads threads, by \`bench/kd_section.sh\` (\$S is ../shared/scenes). Scenes:$names.

### Builds and frames: primary plus shadow rays

\`bench/kd_report.sh build/rtcl $rounds $reps SCENES\` with \`--width 512 --height 288
--threads $threads\`: $rounds rounds alternating \`rtcl bench --accel bvh\` and \`--accel kd\`
(every static mesh an exact SAH kd-tree), min and median over the rounds. Build rows: the
BVH builders, then \`kd-exact\` and \`kd-binned\` (one kd-tree over all triangles; SAH with
Ct 1, Ci 2 as for the BVHs). Frame rows: each backend with BVH meshes and with kd meshes;
"box or node steps" counts box tests for BVHs and the root box plus inner nodes for
kd-trees; "vs embree" is against Embree in the same \`rtcl bench\` run.
$(cat "$tmp/frames.md")

### Incoherent ray queries

\`build/bench/bench_kd_rays --rays $nrays --reps $reps --threads $threads SCENES\`: the same
rays (diffuse bounces from the camera rays' hits, and random rays in the scene's bounds)
through the scene with BVH meshes and with kd meshes, closest and any hit, with
\`rt_trace_rays\` on the cpu oracle and the packet backend; one warm-up round, then $reps
rounds, every combination once per round. Steps and triangle tests per ray are the
oracle's; "differ" counts kd hits not identical to the BVH's (closest: every bit; any: the
flag).

$(python3 "$root/bench/kd_section_tables.py" rays "$tmp/rays.jsonl")

### The thesis's Bunny figures beside ours

As quoted by Rahikainen 2013 (\`../shared/thesis/FIGURES.md\`, \`bench/thesis_kd_numbers.tsv\`),
on other hardware and years; ours are this run's wall-clock builds of the Bunny (min and
median over the rounds above, $threads threads on a shared machine).

$(python3 "$root/bench/kd_section_tables.py" bunny "$tmp/kd.jsonl" "$root/bench/thesis_kd_numbers.tsv")
EOF
