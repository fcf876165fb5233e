# SPDX-License-Identifier: Apache-2.0
# common_args.sh - sourced by the bench scripts (report.sh, kd_section.sh,
# common_study_args.sh) with their arguments: sets root (the repository),
# quick (1 when --quick is among them, else 0) and args (the others, in
# order).
root=$(cd "$(dirname "$0")/.." && pwd)
quick=0
args=()
for a in "$@"; do
    if [ "$a" = --quick ]; then quick=1; else args+=("$a"); fi
done
