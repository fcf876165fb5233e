#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# study_dynamic.sh BUILD_DIR SHARED_SCENES OUT_DIR [--quick] - the update
# policies of deforming meshes (issue 16): per-frame update ms against trace
# ms over our policies and Embree's build qualities on the morphing
# animations, and a long morph where refit's tree drifts from a fresh
# build's (SAH cost and trace ms per frame, refit against auto and rebuild).
# Writes OUT_DIR/dynamic.md and OUT_DIR/plots/dynamic.png; bench/report.sh
# runs it, and it runs alone (about 10 minutes on 2 cores; --quick: tiny
# frames, to check that it works).
#
# Everything is measured by 'rtcl bench --animate' (bench/engines/bench_animate.c):
# frame k at time k/F, each row's frames after the first build, rows
# interleaved frame by frame; the short runs use one frame per keyframe (the
# thesis's section 4.1 method), the long morph FPS x seconds frames.
set -euo pipefail
. "$(dirname "$0")/common_study_args.sh"
if [ $quick = 1 ]; then
    reps=1 width=64 height=36 long_frames=12 long_fps=20 long_reps=1
    scenes=("$root/scenes/keyframes_animated.json" "$root/bench/scenes/robot_walk_anim.json")
    long_scene=$root/bench/scenes/robot_walk_anim.json
else
    reps=${RT_STUDY_DYNAMIC_REPS:-5} width=1024 height=576 long_frames=120 long_fps=20
    long_reps=${RT_STUDY_DYNAMIC_LONG_REPS:-2}
    scenes=("$root/bench/scenes/brainstem_anim.json" "$root/bench/scenes/robot_walk_anim.json"
            "$root/scenes/keyframes_animated.json")
    long_scene=$root/bench/scenes/brainstem_anim.json
fi
echo "study_dynamic: policies ($reps runs)" >&2
"$build/rtcl" bench --animate "${scenes[@]}" --json --reps $reps --threads $threads \
    --width $width --height $height >"$data/policies.jsonl"
echo "study_dynamic: long morph ($long_frames frames, $long_reps runs)" >&2
"$build/rtcl" bench --animate "$long_scene" --json --reps $long_reps --threads $threads \
    --width $width --height $height --fps $long_fps --frames $long_frames --series \
    >"$data/long.jsonl"
cmd="bash bench/study_dynamic.sh build \$S OUT"
[ $quick = 1 ] && cmd+=" --quick"
rel() { local p=$1; p=${p#"$root/"}; echo "${p/#$shared/\$S}"; }
cmd+=$'\n# which runs\n'"build/rtcl bench --animate"
for s in "${scenes[@]}"; do cmd+=" $(rel "$s")"; done
cmd+=" --json --reps $reps --threads $threads --width $width --height $height"
cmd+=$'\n'"build/rtcl bench --animate $(rel "$long_scene") --json --reps $long_reps --threads $threads"
cmd+=" --width $width --height $height --fps $long_fps --frames $long_frames --series"
python3 "$root/bench/study_dynamic.py" "$data" "$out" --command "$cmd" --root "$root" \
    --shared "$shared" --threads $threads
