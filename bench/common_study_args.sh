# SPDX-License-Identifier: Apache-2.0
# common_study_args.sh - sourced by bench/study_NAME.sh: reads "BUILD_DIR
# SHARED_SCENES OUT_DIR [--quick]" and sets root, quick, build, shared, out,
# data (OUT_DIR/data/NAME, emptied) and threads (bench/report.sh passes its
# thread count in RT_STUDY_THREADS). NAME is the sourcing script's study.
study_name=$(basename "$0" .sh)
study_name=${study_name#study_}
# shellcheck source=bench/common_args.sh
. "$(dirname "$0")/common_args.sh"
[ ${#args[@]} = 3 ] || { echo "usage: $(basename "$0") BUILD_DIR SHARED_SCENES OUT_DIR [--quick]" >&2; exit 2; }
build=$(cd "${args[0]}" && pwd)
shared=$(cd "${args[1]}" && pwd)
out=${args[2]}
mkdir -p "$out/plots"
data=$out/data/$study_name
rm -rf "$data"
mkdir -p "$data"
threads=${RT_STUDY_THREADS:-2}
