# SPDX-License-Identifier: Apache-2.0
# cli_stats.sh - 'rtcl render --stats' tells the truth (issue 30, item 7):
# on the CPU backends, the oracle itself and the packet tracer that gives its
# bits, the maths line names the profile (ieee) and the denormal mode and
# says the oracle's bits are promised, never "NOT promised"; the thread
# count is the one asked for, and never 0 on a device backend.
source "$RT_SOURCE_DIR/tests/shell_check.sh"
rtcl=${RTCL:?}
for b in cpu packet; do
    expect 0 "maths +ieee, denormals preserve: the CPU oracle's bits promised" -- \
        "$rtcl" render builtin:cornell --width 24 --height 16 --backend $b --threads 3 --stats -o "$tmp/$b.ppm"
    checks=$((checks + 1))
    out=$("$rtcl" render builtin:cornell --width 24 --height 16 --backend $b --threads 3 --stats -o "$tmp/$b.ppm" 2>&1)
    if grep -q 'NOT promised\|maths +?' <<<"$out"; then
        echo "FAIL: $b --stats:"; echo "$out" | head -5; fails=$((fails + 1))
    fi
    expect 0 "backend +$b, 3 threads" -- \
        "$rtcl" render builtin:cornell --width 24 --height 16 --backend $b --threads 3 --stats -o "$tmp/$b.ppm"
done
# The device backends, where this build and machine have one ('rtcl devices'
# says so); a device that is listed must render.
for b in opencl vulkan; do
    if ! "$rtcl" devices --api $b >"$tmp/devices.txt" 2>&1; then
        echo "skipped backend $b: $(head -1 "$tmp/devices.txt")"; continue
    fi
    out=$("$rtcl" render builtin:cornell --width 24 --height 16 --backend $b --stats -o "$tmp/$b.ppm" 2>&1) || {
        echo "FAIL: --backend $b --stats:"; echo "$out" | head -5; fails=$((fails + 1)); continue; }
    checks=$((checks + 1))
    if ! grep -q -E "^backend +$b, [1-9][0-9]* threads" <<<"$out"; then
        echo "FAIL: $b --stats gives no thread count:"; echo "$out" | head -3; fails=$((fails + 1))
    fi
done
finish
