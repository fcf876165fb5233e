#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# cli_compare.sh - 'rtcl compare': exit status, printed figures, --max-diff,
# --diff and the errors for missing files and bad usage. The images are small
# binary PPMs made here, so the test needs nothing but the rtcl binary.
set -u

RTCL=${RTCL:?RTCL must name the rtcl binary}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0

fail() {
    echo "FAIL: $*"
    failures=$((failures + 1))
}

# make_ppm FILE WIDTH HEIGHT GREY [X Y R G B]: a grey RGB image, optionally
# with one pixel set to R G B (bytes 0..255).
make_ppm() {
    local file=$1 width=$2 height=$3 grey=$4 px=${5:--1} py=${6:--1}
    local special
    special=$(printf '\\x%02x\\x%02x\\x%02x' "${7:-0}" "${8:-0}" "${9:-0}")
    local plain
    plain=$(printf '\\x%02x\\x%02x\\x%02x' "$grey" "$grey" "$grey")
    {
        printf 'P6\n%d %d\n255\n' "$width" "$height"
        for ((y = 0; y < height; y++)); do
            for ((x = 0; x < width; x++)); do
                if ((x == px && y == py)); then printf "$special"; else printf "$plain"; fi
            done
        done
    } >"$file"
}

# run_rtcl: runs rtcl with the arguments, leaving $status, $out and $err.
run_rtcl() {
    "$RTCL" "$@" >"$work/stdout" 2>"$work/stderr"
    status=$?
    out=$(cat "$work/stdout")
    err=$(cat "$work/stderr")
}

expect_status() {
    [ "$status" -eq "$1" ] || fail "$2: exit status $status, expected $1 (stdout: $out; stderr: $err)"
}

expect_in() {
    case "$1" in
    *"$2"*) ;;
    *) fail "$3: output does not contain '$2': $1" ;;
    esac
}

a=$work/a.ppm
b=$work/b.ppm
make_ppm "$a" 5 4 100
make_ppm "$b" 5 4 100 2 1 100 110 100 # pixel (2,1): green +10 levels

# Identical images pass.
run_rtcl compare "$a" "$a"
expect_status 0 "identical"
expect_in "$out" "max abs difference: 0" "identical"
expect_in "$out" "inf (identical)" "identical"
expect_in "$out" "differing pixels:   0 of 20" "identical"
expect_in "$out" "first difference:   none" "identical"

# Different images fail with the first differing pixel and both values.
run_rtcl compare "$a" "$b"
expect_status 1 "different"
expect_in "$out" "differing pixels:   1 of 20" "different"
expect_in "$out" "pixel (2, 1)" "different"
expect_in "$out" "A = (0.392156869, 0.392156869, 0.392156869)" "different"
expect_in "$out" "B = (0.392156869, 0.431372553, 0.392156869)" "different"
expect_in "$out" "max abs difference: 0.0392156" "different"
expect_in "$out" "FAIL" "different"

# --max-diff: 10 levels = 0.0392 pass under 0.05 (option first), fail under 0.03.
run_rtcl compare --max-diff 0.05 "$a" "$b"
expect_status 0 "--max-diff 0.05"
expect_in "$out" "pass" "--max-diff 0.05"
run_rtcl compare "$a" "$b" --max-diff=0.03
expect_status 1 "--max-diff=0.03"

# --diff writes |A - B|: black with the one pixel's green at 10 levels.
run_rtcl compare "$a" --diff "$work/diff.png" "$b"
expect_status 1 "--diff"
[ -s "$work/diff.png" ] || fail "--diff did not write $work/diff.png"
expect_in "$out" "difference image:   $work/diff.png" "--diff"
make_ppm "$work/expected_diff.ppm" 5 4 0 2 1 0 10 0
run_rtcl compare "$work/diff.png" "$work/expected_diff.ppm"
expect_status 0 "the difference image's content"
run_rtcl compare "$a" "$b" --diff="$work/diff.exr" --max-diff 1
expect_status 0 "--diff=FILE.exr"
[ -s "$work/diff.exr" ] || fail "--diff= did not write $work/diff.exr"

# Errors: exit 2 with a message that names the problem.
run_rtcl compare "$a" "$work/missing.png"
expect_status 2 "missing file"
expect_in "$err" "$work/missing.png" "missing file"
expect_in "$err" "No such file" "missing file"

echo "not an image" >"$work/text.png"
run_rtcl compare "$work/text.png" "$a"
expect_status 2 "not an image"
expect_in "$err" "text.png" "not an image"

make_ppm "$work/small.ppm" 4 4 100
run_rtcl compare "$a" "$work/small.ppm"
expect_status 2 "size mismatch"
expect_in "$err" "differ in size" "size mismatch"

run_rtcl compare "$a" "$b" --diff "$work/diff.bmpx"
expect_status 2 "bad --diff extension"
expect_in "$err" ".exr" "bad --diff extension"

run_rtcl compare "$a"
expect_status 2 "one image"
run_rtcl compare "$a" "$b" "$a"
expect_status 2 "three images"
run_rtcl compare "$a" "$b" --frobnicate
expect_status 2 "unknown option"
expect_in "$err" "--frobnicate" "unknown option"
run_rtcl compare "$a" "$b" --max-diff abc
expect_status 2 "bad --max-diff"
run_rtcl compare "$a" "$b" --max-diff
expect_status 2 "--max-diff without a value"

# --help: usage on stdout, exit 0, wherever it stands.
run_rtcl compare --help
expect_status 0 "--help"
expect_in "$out" "usage: rtcl compare A B" "--help"
expect_in "$out" "--max-diff X" "--help"
run_rtcl compare "$a" "$b" --help
expect_status 0 "--help after the images"

if [ "$failures" -ne 0 ]; then
    echo "cli_compare: $failures failed"
    exit 1
fi
echo "cli_compare: all passed"
