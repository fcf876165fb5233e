# SPDX-License-Identifier: Apache-2.0
# cli_opencl.sh - 'rtcl devices', render and trace with --backend opencl
# (byte-identical to the CPU oracle on PoCL), --device errors, and what
# happens without any OpenCL platform: explicit opencl fails with status 2 and
# a reason, auto falls back to the CPU with a notice.
source "$RT_SOURCE_DIR/tests/shell_check.sh"

if ! "$RTCL" devices --api opencl >"$tmp/devices.txt" 2>&1; then
    if grep -q "no OpenCL backend" "$tmp/devices.txt"; then
        echo "skipped: this build has no OpenCL backend"; exit 77
    fi
    if grep -q -E "no OpenCL (platform|device)" "$tmp/devices.txt"; then
        echo "skipped: no OpenCL device: $(cat "$tmp/devices.txt")"; exit 77
    fi
fi
expect 0 'device 0: .*' -- "$RTCL" devices --api opencl
expect 0 'exact +(yes|no): ' -- "$RTCL" devices --api opencl --device 0
expect 0 'kernels +(packet|one ray per work-item)' -- "$RTCL" devices --api opencl --device 0
# The packet kernel runs on CPU devices (the 'kernel path' line of --stats).
if "$RTCL" devices --api opencl --device 0 | grep -q 'kernels  *packet'; then path=packet; else path='one ray'; fi
expect 2 'no OpenCL device 99' -- "$RTCL" devices --api opencl --device 99
expect 2 "no OpenCL device named like 'no-such-gpu'" -- "$RTCL" devices --api opencl --device no-such-gpu

# Images: the PNG files are byte-identical.
for scene in builtin:cornell builtin:keyframes; do
    expect 0 'wrote' -- "$RTCL" render "$scene" --width 160 --height 90 -o "$tmp/cpu.png"
    expect 0 'specialisation +-DRT_STATIC_FLAGS' -- "$RTCL" render "$scene" --width 160 \
        --height 90 --backend opencl --device 0 --stats -o "$tmp/cl.png"
    checks=$((checks + 1))
    cmp -s "$tmp/cpu.png" "$tmp/cl.png" || { echo "FAIL: $scene: opencl PNG differs"; fails=$((fails + 1)); }
done
# Odd sizes (partial packet blocks), Whitted and direct, the packet kernel
# where the device is a CPU and the one-ray kernels forced: the same PNG.
for direct in "" --direct; do
    expect 0 'wrote' -- "$RTCL" render builtin:cornell --width 61 --height 37 $direct -o "$tmp/cpu.png"
    expect 0 "kernel path +$path" -- "$RTCL" render builtin:cornell --width 61 --height 37 $direct \
        --backend opencl --stats -o "$tmp/cl.png"
    expect 0 'kernel path +one ray per work-item' -- "$RTCL" render --cl-one-ray \
        builtin:cornell --width 61 --height 37 $direct --backend opencl --stats -o "$tmp/cl1.png"
    for f in cl cl1; do
        checks=$((checks + 1))
        cmp -s "$tmp/cpu.png" "$tmp/$f.png" || { echo "FAIL: cornell $direct 61x37: opencl $f PNG differs"; fails=$((fails + 1)); }
    done
done
# Reflection and refraction as wavefront passes (cornell has a mirror and a
# glass sphere; the one-ray kernels, as on a GPU), and with one-entry queues
# every tile redone in one kernel: the same PNG both ways.
expect 0 'wavefront +[1-9][0-9]* tiles \(0 redone' -- "$RTCL" render builtin:cornell --width 160 \
    --height 90 --backend opencl --cl-one-ray --stats -o "$tmp/wave.png"
expect 0 'wavefront +([0-9]+) tiles \(\1 redone' -- "$RTCL" render --cl-wave-cap 1 --cl-one-ray \
    builtin:cornell --width 160 --height 90 --backend opencl --stats -o "$tmp/wave1.png"
expect 0 'wrote' -- "$RTCL" render builtin:cornell --width 160 --height 90 -o "$tmp/cpu.png"
for f in wave wave1; do
    checks=$((checks + 1))
    cmp -s "$tmp/cpu.png" "$tmp/$f.png" || { echo "FAIL: cornell: opencl $f PNG differs"; fails=$((fails + 1)); }
done
# --cl-options (the speed-versus-error study's variants): appended to the
# kernels' build, said by --stats; the exact build after it is the oracle's.
expect 0 'extra options +-cl-fast-relaxed-math .*NOT the exact build' -- "$RTCL" render \
    builtin:cornell --width 64 --height 36 --backend opencl --cl-options -cl-fast-relaxed-math \
    --stats -o "$tmp/fast.png"
expect 0 'exactness with the CPU oracle NOT promised' -- "$RTCL" render builtin:cornell --width 64 \
    --height 36 --backend opencl --cl-options "-cl-mad-enable -DRT_NATIVE_MATH" --stats -o "$tmp/fast.png"
expect 0 'bit-exact with the CPU oracle promised' -- "$RTCL" render builtin:cornell --width 64 \
    --height 36 --backend opencl --stats -o "$tmp/fast.png"
expect 2 'kernel build failed.*-cl-no-such-option' -- "$RTCL" render builtin:cornell --width 32 \
    --height 18 --backend opencl --cl-options -cl-no-such-option -o "$tmp/x.png"
expect 2 'no OpenCL device 99' -- "$RTCL" render builtin:cornell --backend opencl --device 99 -o "$tmp/x.png"
expect 2 '--device applies to --backend opencl, vulkan or auto' -- "$RTCL" render builtin:cornell --device 0 -o "$tmp/x.png"

# Ray queries: the same hit lines, closest and any hit.
awk 'BEGIN { srand(5); for (i = 0; i < 3000; i++) printf "%f %f %f %f %f %f 0 inf\n",
     rand() * 4 - 2, rand() * 3, rand() * 6 - 1, rand() - 0.5, rand() - 0.5, rand() - 0.5 }' >"$tmp/rays.txt"
for any in "" --any-hit; do
    expect 0 '' -- "$RTCL" trace builtin:cornell --rays "$tmp/rays.txt" --out "$tmp/h_cpu.txt" $any
    expect 0 '' -- "$RTCL" trace builtin:cornell --rays "$tmp/rays.txt" --out "$tmp/h_cl.txt" --backend opencl $any
    checks=$((checks + 1))
    cmp -s "$tmp/h_cpu.txt" "$tmp/h_cl.txt" || { echo "FAIL: trace $any: opencl hits differ"; fails=$((fails + 1)); }
done

# --backend auto names what it chose in the result line, not a line of its
# own (issue 30, item 10): render's "wrote" line, trace's --stats and --json;
# with --verbose one line on stderr. With a device that is a device backend
# and its device; stdout stays the JSON alone.
expect 0 '^wrote .*x\.png \(32x18, backend (opencl|vulkan), .+\)$' -- "$RTCL" render builtin:cornell \
    --width 32 --height 18 --backend auto -o "$tmp/x.png"
expect 0 '^wrote .*x\.png \(32x18, backend opencl, .+\)$' -- "$RTCL" render builtin:cornell \
    --width 32 --height 18 --backend auto --device 0 -o "$tmp/x.png"
expect 0 '^rtcl render: backend: opencl \(.+\)$' -- "$RTCL" render builtin:cornell \
    --width 32 --height 18 --backend auto --device 0 --verbose -o "$tmp/x.png"
"$RTCL" trace builtin:cornell --rays "$tmp/rays.txt" --json --backend auto \
    >"$tmp/auto.json" 2>"$tmp/auto.err"
checks=$((checks + 1))
python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); assert d["backend"] in ("opencl", "vulkan") and d["device"], d' "$tmp/auto.json" ||
    { echo "FAIL: trace --json --backend auto: stdout is not JSON alone naming the backend and device"; fails=$((fails + 1)); }
checks=$((checks + 1))
[ ! -s "$tmp/auto.err" ] || { echo "FAIL: trace --backend auto printed on stderr: $(cat "$tmp/auto.err")"; fails=$((fails + 1)); }
expect 0 '^path: (opencl|vulkan) \(.+\)$' -- "$RTCL" trace builtin:cornell --rays "$tmp/rays.txt" \
    --stats --backend auto
# No backend line without --verbose, auto or not.
for b in opencl auto; do
    "$RTCL" render builtin:cornell --width 32 --height 18 --backend $b -o "$tmp/x.png" 2>"$tmp/e.txt"
    checks=$((checks + 1))
    ! grep -q 'backend:' "$tmp/e.txt" || { echo "FAIL: --backend $b printed: $(cat "$tmp/e.txt")"; fails=$((fails + 1)); }
done

# The completion check (docs/OPENCL.md, "Failures"): kernels built to leave
# every 4th work-item unfinished (RTCL_TEST_OPENCL_SKIP, fault injection)
# must fail the frame and the queries with status 2 and the reason, and write
# no file. The device's kernels as they run by default (one program); the
# other kernel paths are cut under Oclgrind in cli_oclgrind.sh.
miss='opencl: kernel rt_k_[a-z_]+ on .+ finished [0-9]+ of [0-9]+ work-items .* cut the launch short'
rm -f "$tmp/cut.png" "$tmp/cut.txt"
expect 2 "$miss" -- env RTCL_TEST_OPENCL_SKIP=4 "$RTCL" render builtin:cornell --width 24 --height 16 \
    --backend opencl -o "$tmp/cut.png"
for any in "" --any-hit; do
    expect 2 "$miss" -- env RTCL_TEST_OPENCL_SKIP=4 "$RTCL" trace builtin:cornell --rays "$tmp/rays.txt" \
        --out "$tmp/cut.txt" --backend opencl $any
done
checks=$((checks + 1))
[ ! -e "$tmp/cut.png" ] && [ ! -e "$tmp/cut.txt" ] ||
    { echo "FAIL: a launch cut short still wrote its result"; fails=$((fails + 1)); }
expect 2 'RTCL_TEST_OPENCL_SKIP must be a whole number' -- env RTCL_TEST_OPENCL_SKIP=x "$RTCL" render \
    builtin:cornell --width 8 --height 8 --backend opencl -o "$tmp/cut.png"

# No platform at all (the ICD loader reads no vendor file), and no Vulkan
# driver either (else auto would take Vulkan).
mkdir "$tmp/no_vendors"
export OCL_ICD_VENDORS="$tmp/no_vendors" VK_ICD_FILENAMES="$tmp/none.json" VK_DRIVER_FILES="$tmp/none.json"
expect 2 'no OpenCL platform' -- "$RTCL" devices --api opencl
expect 2 'opencl: no OpenCL platform' -- "$RTCL" render builtin:cornell --width 32 --height 18 --backend opencl -o "$tmp/x.png"
expect 2 'opencl: no OpenCL platform' -- "$RTCL" trace builtin:cornell --rays "$tmp/rays.txt" --out "$tmp/x.txt" --backend opencl
expect 0 'notice: opencl not available \(no OpenCL platform' -- "$RTCL" render builtin:cornell --width 32 --height 18 --backend auto -o "$tmp/x.png"
unset OCL_ICD_VENDORS VK_ICD_FILENAMES VK_DRIVER_FILES
finish
