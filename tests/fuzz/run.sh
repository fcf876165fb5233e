#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Runs the libFuzzer harnesses of an RT_FUZZ=ON build, one after another.
#   tests/fuzz/run.sh BUILD_DIR SECONDS [NAME...]   (NAMEs: obj json rays trace gltf)
# Each fuzzer starts from its seeds (tests/fuzz/corpus/NAME, read only) and
# writes the inputs it finds to BUILD_DIR/fuzz-corpus/NAME (kept between
# runs), a crash or hang to BUILD_DIR/fuzz-artifacts/, its log to
# BUILD_DIR/fuzz-logs/NAME.log. Extra libFuzzer flags: RT_FUZZ_FLAGS.
# Exit status: non-zero when any fuzzer found something.
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:?usage: run.sh BUILD_DIR SECONDS [NAME...]}"
seconds="${2:?usage: run.sh BUILD_DIR SECONDS [NAME...]}"
shift 2
names=("$@")
[ ${#names[@]} -gt 0 ] || names=(obj json rays trace gltf)
mkdir -p "$build/fuzz-artifacts" "$build/fuzz-logs"
failed=0
for name in "${names[@]}"; do
    fuzzer="$build/tests/fuzz/fuzz_$name"
    if [ ! -x "$fuzzer" ]; then
        echo "run.sh: $fuzzer missing (configure with CC=clang CXX=clang++ -DRT_FUZZ=ON)" >&2
        exit 2
    fi
    mkdir -p "$build/fuzz-corpus/$name"
    log="$build/fuzz-logs/$name.log"
    # -timeout: an input taking 30 s is a hang (each takes well under a second
    # unless the machine is starved); -rss_limit_mb: the loaders may allocate
    # what a file asks for (within the documented limits), 2 GB catches a
    # runaway allocation.
    # LD_LIBRARY_PATH: the glTF and image modules, which ASan's dlopen finds
    # through the library path, not the program's RUNPATH.
    # shellcheck disable=SC2086
    LD_LIBRARY_PATH="$build${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" \
    "$fuzzer" -max_total_time="$seconds" -timeout=30 -rss_limit_mb=2048 -print_final_stats=1 \
        -dict="$here/$name.dict" -artifact_prefix="$build/fuzz-artifacts/$name-" \
        ${RT_FUZZ_FLAGS:-} "$build/fuzz-corpus/$name" "$here/corpus/$name" > "$log" 2>&1
    status=$?
    # The final coverage and execution lines, for the CI log.
    summary=$(grep -E '^#[0-9]+.*(DONE|cov:)' "$log" | tail -1)
    runs=$(grep -E '^stat::number_of_executed_units' "$log" | awk '{print $2}')
    if [ $status -eq 0 ]; then
        echo "fuzz_$name: ${seconds}s, ${runs:-?} executions, no finding: $summary"
    else
        failed=1
        echo "fuzz_$name: FINDING (exit $status), log $log:"
        grep -E 'ERROR|fuzz finding|runtime error|differs|Test unit written|SUMMARY' "$log" | head -20
    fi
done
exit $failed
