#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# study_tri_tests.sh BUILD_DIR SHARED_SCENES OUT_DIR [--quick] - speed against
# error of the four triangle tests (issue 7, study a). Writes
# OUT_DIR/tri_tests.md (a report section) and OUT_DIR/plots/tri_tests.png;
# bench/report.sh runs it. --quick: small scenes, one run (checks that it works).
#
# Measured:
# - leaks: rays through shared vertices and edges of closed meshes (the
#   robustness suite's closed-mesh categories, tests/robust/gen_cases.py) that
#   miss, or pass through to a surface behind, per tests/robust/check_hits.py;
#   rtcl trace on the cpu oracle;
# - speed and the error of t on the primary rays of real scenes
#   (bench/bench_tri_study: t against t recomputed in double precision for the
#   reported triangle, and on a subsample the closest hit against a
#   double-precision brute-force reference).
set -euo pipefail
. "$(dirname "$0")/common_study_args.sh"
tests="watertight mt pluecker badouel"

if [ $quick = 1 ]; then
    runs=1 width=256 height=144 sample=256
    scenes=("$root/scenes/cornell.json" "$shared/robot_walk_anim/robot_walk_00.obj")
else
    runs=5 width=1024 height=576 sample=4096
    scenes=("$shared/stanford_bunny/stanford-bunny.obj" "$root/bench/scenes/sponza_interior.json"
            "$shared/armadillo_decimated/armadillo.obj" "$root/bench/scenes/sibenik_interior.json")
fi

# The robustness cases (generated once per version of the generator).
. "$root/bench/robust_cases.sh"
robust_cases "$build" "$root"
# Only the closed-mesh categories (shared vertices and edges that must hit).
mkdir -p "$data/cases"
closed=$(python3 - "$cases/manifest.json" "$data/cases/manifest.json" <<'EOF'
import json, sys
m = json.load(open(sys.argv[1]))
keep = ('closed_vertex_edge', 'moved_1e3', 'moved_1e5', 'moved_1e6', 'scaled_1e-4', 'scaled_1e5')
m['cases'] = [c for c in m['cases'] if c['category'] in keep and not c['flags']]
json.dump(m, open(sys.argv[2], 'w'))
print(' '.join(c['name'] for c in m['cases']))
EOF
)
for t in $tests; do
    mkdir -p "$data/hits-$t"
    for name in $closed; do
        "$build/rtcl" trace "$cases/$name.obj" --rays "$cases/$name.rays" --out "$data/hits-$t/$name.hits" \
            --backend cpu --tri-test "$t" >/dev/null
    done
    python3 "$root/tests/robust/check_hits.py" "$data/cases" "$data/hits-$t" "cpu/$t" \
        --json="$data/leaks-$t.json" >"$data/leaks-$t.txt"
done

i=0
for s in "${scenes[@]}"; do
    i=$((i + 1))
    echo "study_tri_tests: $(basename "$s")" >&2
    "$build/bench/bench_tri_study" "$s" --width $width --height $height --runs $runs \
        --threads $threads --sample $sample >"$data/scene$i.tsv"
    echo "$s" >"$data/scene$i.name"
done

cmd="bash bench/study_tri_tests.sh build \$S OUT"
[ $quick = 1 ] && cmd+=" --quick"
python3 "$root/bench/study_report.py" tri_tests "$data" "$out" --command "$cmd" --root "$root" \
    --shared "$shared" --runs $runs --threads $threads --width $width --height $height \
    --sample $sample
