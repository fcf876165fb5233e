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

# skip_without_vulkan: exits 77 (skipped) with the reason where this build
# has no Vulkan backend or the loader finds no Vulkan device.
skip_without_vulkan() {
    "$RTCL" devices --api vulkan >"$tmp/devices.txt" 2>&1 && return 0
    if grep -q "no Vulkan backend" "$tmp/devices.txt"; then
        echo "skipped: this build has no Vulkan backend"; exit 77
    fi
    if grep -q -E "no Vulkan (driver|device)|finds no device" "$tmp/devices.txt"; then
        echo "skipped: no Vulkan device: $(cat "$tmp/devices.txt")"; exit 77
    fi
}

# cornell_rays SEED N FILE: N rays from the Cornell box's room (rtcl trace's
# ray lines: origin, direction, tmin 0, tmax inf), the same for a seed.
cornell_rays() {
    awk -v seed="$1" -v n="$2" 'BEGIN { srand(seed); for (i = 0; i < n; i++)
        printf "%f %f %f %f %f %f 0 inf\n", rand() * 4 - 2, rand() * 3, rand() * 6 - 1,
        rand() - 0.5, rand() - 0.5, rand() - 0.5 }' >"$3"
}

finish() {
    echo "$(basename "$0"): $checks checks, $fails failed"
    [ "$fails" = 0 ]
}
