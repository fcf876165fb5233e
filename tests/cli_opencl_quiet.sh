# SPDX-License-Identifier: Apache-2.0
# cli_opencl_quiet.sh - nothing of the device compiler reaches the user's
# terminal (issue 19, fault 1): with an empty PoCL kernel cache, as on a
# fresh machine, OpenCL renders and ray queries print nothing on stderr but
# rtcl's own "wrote" line. A build that does warn (an option that redefines
# a kernel macro) stays quiet too: PoCL's clang prints "N warnings
# generated." on the process's stderr itself, which the library captures;
# --verbose shows it with the build log, and a failed build's error has it.
# (A run that loads a cached binary compiles nothing and has no log.)
source "$RT_SOURCE_DIR/tests/shell_check.sh"

if ! "$RTCL" devices >"$tmp/devices.txt" 2>&1; then
    echo "skipped: no OpenCL backend or device: $(head -1 "$tmp/devices.txt")"; exit 77
fi
# Empty kernel caches, PoCL's and ours (README, "Kernel cache"): every
# kernel is compiled afresh, and the cache's own writes must be quiet too.
export POCL_CACHE_DIR="$tmp/pocl-cache" RTCL_CACHE_DIR="$tmp/rtcl-cache"
mkdir -p "$POCL_CACHE_DIR"

# quiet NAME CMD...: CMD exits 0 and its stderr, less rtcl's "wrote" line, is empty.
quiet() {
    local name=$1
    shift
    checks=$((checks + 1))
    if ! "$@" >"$tmp/out.txt" 2>"$tmp/err.txt"; then
        echo "FAIL: $name: '$*' failed:"; head -20 "$tmp/err.txt"; fails=$((fails + 1)); return
    fi
    if grep -v -E '^wrote ' "$tmp/err.txt" | grep -q .; then
        echo "FAIL: $name: stderr on a cold kernel cache:"; head -20 "$tmp/err.txt"
        fails=$((fails + 1))
    fi
}

printf '0.2 0.5 3 0 0 -1 0 inf\n-0.3 0.4 3 0.1 0 -1 0 inf\n' >"$tmp/rays.txt"
quiet "devices" "$RTCL" devices
# The packet kernels (CPU devices), the one-ray and wavefront kernels, ray queries.
quiet "render" "$RTCL" render builtin:cornell --backend opencl --width 48 --height 32 -o "$tmp/a.ppm"
quiet "one-ray" "$RTCL" render builtin:keyframes --backend opencl --cl-one-ray --width 48 \
    --height 32 -o "$tmp/a.ppm"
quiet "trace" "$RTCL" trace builtin:cornell --backend opencl \
    --rays "$tmp/rays.txt" --out "$tmp/hits.txt"
[ -n "$(ls -A "$POCL_CACHE_DIR")" ] || echo "note: PoCL wrote no kernel cache (another driver?)"
checks=$((checks + 1))
ls "$RTCL_CACHE_DIR"/cl-*.bin >/dev/null 2>&1 || { echo "FAIL: no program binary cached"; fails=$((fails + 1)); }

# A build that warns: -DPK_W=3 is redefined by the packet kernel's own
# #define (to the 4 it always has), so the image is the same but clang warns
# "macro redefined" and prints "1 warning generated." on stderr itself.
rm -rf "${POCL_CACHE_DIR:?}"/* "${RTCL_CACHE_DIR:?}"
quiet "warning build" "$RTCL" render builtin:cornell --backend opencl --cl-options -DPK_W=3 \
    --width 48 --height 32 -o "$tmp/a.ppm"
# --verbose shows both: the log's warning and what PoCL printed.
rm -rf "${POCL_CACHE_DIR:?}"/* "${RTCL_CACHE_DIR:?}"
"$RTCL" render builtin:cornell --backend opencl --cl-options -DPK_W=3 --width 48 --height 32 \
    -o "$tmp/a.ppm" --verbose 2>"$tmp/verbose.txt"
for want in 'opencl build log:' 'redefined' 'warnings? generated'; do
    checks=$((checks + 1))
    grep -q -E "$want" "$tmp/verbose.txt" || {
        echo "FAIL: --verbose does not show /$want/:"; head -20 "$tmp/verbose.txt"; fails=$((fails + 1)); }
done
# A failed build says why.
expect 2 'Invalid build option' -- "$RTCL" render builtin:cornell --backend opencl \
    --cl-options -Wno-such-warning --width 48 --height 32 -o "$tmp/a.ppm"
finish
