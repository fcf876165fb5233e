# SPDX-License-Identifier: Apache-2.0
# robust_cases.sh - sourced: robust_cases BUILD_DIR ROOT sets $cases to the robustness
# suite's cases (tests/robust/gen_cases.py) in BUILD_DIR/study_tri_cases, generated again
# only when the generator changed (exact rational arithmetic: some seconds).
robust_cases() {
    cases=$1/study_tri_cases
    local stamp
    stamp=$(cat "$2/tests/robust/gen_cases.py" "$2/tests/robust/exact.py" | sha256sum | cut -c1-16)
    if [ "$(cat "$cases/stamp" 2>/dev/null)" != "$stamp" ]; then
        rm -rf "$cases"
        python3 "$2/tests/robust/gen_cases.py" "$cases" >&2
        echo "$stamp" >"$cases/stamp"
    fi
}
