# SPDX-License-Identifier: Apache-2.0
# shell_check.sh - helpers for the shell tests of rtcl (sourced, not run).
# expect STATUS PATTERN -- CMD...: runs CMD, checks its exit status and that
# its stdout+stderr match the extended regular expression PATTERN.
fails=0
checks=0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

expect() {
    local want=$1 pattern=$2
    shift 3
    local out rc
    out=$("$@" 2>&1) && rc=0 || rc=$?
    checks=$((checks + 1))
    if [ "$rc" != "$want" ]; then
        echo "FAIL: '$*' exited $rc, expected $want; output:"; echo "$out" | head -20
        fails=$((fails + 1))
    elif ! grep -q -E -- "$pattern" <<<"$out"; then
        echo "FAIL: '$*' output does not match /$pattern/; output:"; echo "$out" | head -20
        fails=$((fails + 1))
    fi
}

# Vulkan's driver (lavapipe) leaks 128 bytes at unload, where no suppression
# can name the frames (docs/VULKAN.md, "Sanitizer build"). A command that
# loads it runs as 'no_leak_check CMD...': the sanitizer build's leak check is
# off for that command alone, its other checks stay on; elsewhere a no-op.
no_leak_check() {
    ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" LSAN_OPTIONS=detect_leaks=0 "$@"
}

finish() {
    echo "$(basename "$0"): $checks checks, $fails failed"
    [ "$fails" = 0 ]
}
