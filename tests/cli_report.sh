#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# cli_report.sh - the single command that regenerates docs/BENCHMARKS_REPORT.md
# (bench/report.sh) runs end to end in its quick mode and prints every section:
# the build, thesis, render and Whitted tables with real rows, the targets
# judged, and one section with a PNG plot per speed-against-error study, whose
# tables have real rows and whose checks hold.
set -u
[ -d "${RT_SHARED_SCENES:-}" ] || { echo "skipped: no shared scenes at '${RT_SHARED_SCENES:-}'"; exit 77; }
command -v python3 >/dev/null || { echo "skipped: python3 is needed"; exit 77; }
if [ -n "${LSAN_OPTIONS:-}" ]; then
    echo "skipped: the report measures speed; in the sanitizer build it only runs slower (the Release build's ctest runs it)"
    exit 77
fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
REPORT_OUT=$out bash "$RT_SOURCE_DIR/bench/report.sh" "$RT_BINARY_DIR" "$RT_SHARED_SCENES" --quick \
    >"$out/log" 2>&1 || { echo "report.sh failed:"; tail -30 "$out/log"; exit 1; }
md=$out/BENCHMARKS_REPORT.md
fails=0
need() {
    grep -q -E -- "$1" "$md" || { echo "FAIL: BENCHMARKS_REPORT.md lacks /$1/"; fails=$((fails + 1)); }
}
need '^## OBJ parsing'
need '^robot_walk_00.obj +3237 '
need '^## BVH build'
need '^\| robot_walk_anim/robot_walk_00.obj \| 3,237 \| [0-9.]+ / [0-9.]+ \|'
need '^\| Sponza \| 66,450 \| 113.7 \|'
need '^## Rendering, the thesis'
need '^\| scenes/cornell.json \| [0-9,]+ \| [0-9.]+ / [0-9.]+ \| [0-9.]+ / [0-9.]+ \|'
need '^- packet rate / Embree'
need '^- OpenCL \(PoCL\) rate'
need '^## Rendering, Whitted'
need '^\| cornell.json \| [0-9]+ \| [0-9.]+ / [0-9.]+ \|'
need '^## Incoherent rays'
need '^\| stanford-bunny.obj \| 69451 \| random \| any \| [0-9.]+ / [0-9.]+ \| [0-9.]+ / [0-9.]+ \|'
need '^\| packet \| single-ray \| [0-9.]+ / [0-9.]+ \|'
for script in "$RT_SOURCE_DIR"/bench/study_*.sh; do
    [ -f "$script" ] || continue
    name=$(basename "$script" .sh)
    name=${name#study_}
    need "^## Speed against error"
    need "\(plots/$name.png\)"
    head -c 8 "$out/plots/$name.png" 2>/dev/null | od -An -tx1 | grep -q "89 50 4e 47" ||
        { echo "FAIL: plots/$name.png is missing or not a PNG"; fails=$((fails + 1)); }
done
# The studies' tables have real rows, and what must hold does: the watertight
# test has no leak, every builder's tree gives the default image, the exact
# OpenCL build is the oracle's image (or the section says there is no device).
if [ -f "$RT_SOURCE_DIR/bench/study_tri_tests.sh" ]; then
    need '^## Speed against error: triangle tests'
    need '^\| watertight \| 0 \| [0-9.]+ / [0-9.]+ \| [0-9.e+-]+ \|'
    need '^\| Moller-Trumbore \| [0-9]+ \|'
fi
if [ -f "$RT_SOURCE_DIR/bench/study_builders.sh" ]; then
    need '^## Speed against error: BVH builders'
    need '^\| sah, 16 bins, leaf 10 \(default\) \| 2 \| [0-9.]+ / [0-9.]+ \| [0-9.]+ \|'
    need '^\| sah, 64 bins, leaf 10 \|'
    need '^\| sah, 16 bins, leaf 1 \|'
    need 'Every tree gave the default image bit for bit\.'
    ! grep -q 'NOT the default image' "$md" || { echo "FAIL: a tree changed the image"; fails=$((fails + 1)); }
fi
if [ -f "$RT_SOURCE_DIR/bench/study_opencl_options.sh" ]; then
    need '^## Speed against error: OpenCL kernel build options'
    need '^\| none \(exact build\) \| yes \| [0-9.]+ / [0-9.]+ \| \+0\.0% \| 0 \| inf \| 0 \(0\.00%\) \| 0 \||No OpenCL device on this machine'
    need '^\| `-cl-fast-relaxed-math` \| no \||No OpenCL device on this machine'
fi
if [ -f "$RT_SOURCE_DIR/bench/study_dynamic.sh" ]; then
    need '^## Dynamic scenes \(issue 16\): update policies beside Embree'
    need '^\| rtcl \| refit \| [0-9.]+ \| [0-9.]+ \| [0-9.]+ \| [0-9.]+ \| [0-9.]+ \| [0-9.]+ \| [0-9.]+ \| yes \|'
    need '^### A long morph'
    ! grep -q -E '^\| rtcl \| [a-z]+ \|.*\| NO \|' "$md" || { echo "FAIL: a policy changed the frames"; fails=$((fails + 1)); }
fi
# The kd-tree section (bench/kd_section.sh): build rows, kd frames, the
# incoherent queries with the kd hits equal to the BVH's, the thesis's figures.
need '^## SAH kd-trees against the BVH in one run'
need '^\| kd-exact \| 2 \| [0-9.]+ \| [0-9.]+ \|'
need '^\| cpu \| kd \| [0-9.]+ \| [0-9.]+ \|'
need '^\| cornell.json \| random \| closest \| cpu \| [0-9.]+ / [0-9.]+ \| [0-9.]+ / [0-9.]+ \| .* \| 0 \|$'
need '^\| Wald and Havran 2006 \| .* \| 3200 \|'
! grep -E '^\| [a-z_.]+ \| (diffuse|random) \| closest \|.* \| [1-9][0-9]* \|$' "$md" ||
    { echo "FAIL: kd closest hits differ from the BVH's"; fails=$((fails + 1)); }
[ $fails = 0 ] || { echo "--- report:"; head -c 6000 "$md"; exit 1; }
echo "cli_report: ok"
