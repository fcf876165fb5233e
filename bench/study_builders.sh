#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# study_builders.sh BUILD_DIR SHARED_SCENES OUT_DIR [--quick] - BVH builders
# and their settings: build time against SAH cost against the time to trace
# a frame through the tree (issue 7, study b). Writes OUT_DIR/builders.md and
# OUT_DIR/plots/builders.png; bench/report.sh runs it. --quick: small scenes,
# one repetition (checks that it works).
#
# The setups: the thesis's three (one thread scalar, one thread NEON binning,
# two-phase threaded; 16 bins, leaf size 10), the SAH builder (the default)
# at 4, 8, 16, 32 and 64 bins (leaf size 10) and at leaf sizes 1, 2, 4, 8 and
# 16 (16 bins), and Embree's rtcBuildBVH (leaf size 10). bench/bench_builders
# builds every mesh BVH with each, renders the thesis's benchmark frame
# (primary and shadow rays) through the trees with the scalar oracle, and
# checks that the image is the default build's, bit for bit.
set -euo pipefail
. "$(dirname "$0")/common_study_args.sh"
setups=(thesis-scalar:16:10 thesis-neon:16:10 thesis-mt:16:10
        sah:4:10 sah:8:10 sah:16:10 sah:32:10 sah:64:10
        sah:16:1 sah:16:2 sah:16:4 sah:16:8 sah:16:16 embree::10)
grep -q "RT_HAVE_EMBREE=1" "$build/build.ninja" 2>/dev/null || {
    echo "study_builders: this build has no Embree: its row is left out" >&2
    unset 'setups[13]'
}
if [ $quick = 1 ]; then
    reps=1 width=256 height=144
    scenes=("$root/scenes/cornell.json" "$shared/robot_walk_anim/robot_walk_00.obj")
else
    reps=5 width=1024 height=576
    scenes=("$root/bench/scenes/sponza_interior.json" "$root/bench/scenes/sibenik_interior.json"
            "$shared/armadillo_decimated/armadillo.obj")
fi
i=0
for s in "${scenes[@]}"; do
    i=$((i + 1))
    echo "study_builders: $(basename "$s")" >&2
    "$build/bench/bench_builders" "$s" --width $width --height $height --reps $reps \
        --threads $threads "${setups[@]}" >"$data/scene$i.tsv"
    echo "$s" >"$data/scene$i.name"
done
cmd="bash bench/study_builders.sh build \$S OUT"
[ $quick = 1 ] && cmd+=" --quick"
python3 "$root/bench/study_report.py" builders "$data" "$out" --command "$cmd" --root "$root" \
    --shared "$shared" --runs $reps --threads $threads --width $width --height $height
