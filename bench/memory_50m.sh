#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# memory_50m.sh [BUILD_DIR] - renders a 50-million-triangle height field
# with the packet backend (one frame, direct rays) and checks that the
# process's peak resident memory stays under 8 GiB (issue 31). Needs about
# 8 GB free and a few minutes; it measures memory, not time. Exit 1 when the
# peak is 8 GiB or more.
set -euo pipefail
build=${1:-$(dirname "$0")/../build}
bench=$build/bench/bench_memory
[ -x "$bench" ] || { echo "memory_50m.sh: no $bench (build first)" >&2; exit 2; }
out=$(mktemp)
trap 'rm -f "$out"' EXIT
/usr/bin/time -v "$bench" --grid 50000000 --backend packet --threads "${THREADS:-2}" --no-rays \
    --no-embree 2> "$out"
peak_kb=$(awk -F: '/Maximum resident set size/ { gsub(/ /, "", $2); print $2 }' "$out")
echo "peak resident: $peak_kb kB ($(awk -v k="$peak_kb" 'BEGIN { printf "%.2f", k / 1048576 }') GiB)"
[ "$peak_kb" -lt $((8 * 1024 * 1024)) ]
