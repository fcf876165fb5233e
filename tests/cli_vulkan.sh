# SPDX-License-Identifier: Apache-2.0
# cli_vulkan.sh - 'rtcl devices --api vulkan', render and trace with
# --backend vulkan (byte-identical to the CPU oracle on lavapipe), --stats,
# device errors, and what happens without a Vulkan driver: explicit vulkan
# fails with status 2 and a reason, auto falls back to the CPU with a notice.
source "$RT_SOURCE_DIR/tests/shell_check.sh"

skip_without_vulkan
expect 0 'device 0: .*' -- "$RTCL" devices --api vulkan
expect 0 'float controls +round to nearest even (yes|no), denormals kept (yes|no)' -- \
    "$RTCL" devices --api vulkan --device 0
expect 0 'exact +(yes|no): ' -- "$RTCL" devices --api vulkan --device 0
expect 2 'no Vulkan device 99' -- "$RTCL" devices --api vulkan --device 99
expect 2 "no Vulkan device named like 'no-such-gpu'" -- "$RTCL" devices --api vulkan --device no-such-gpu
expect 2 "--api: 'metal' is not one of opencl or vulkan" -- "$RTCL" devices --api metal

# Images: the PNG files are byte-identical, Whitted and direct, at an odd
# size (a partial work group).
for scene in builtin:cornell builtin:keyframes; do
    for direct in "" --direct; do
        expect 0 'wrote' -- "$RTCL" render "$scene" --width 61 --height 37 $direct -o "$tmp/cpu.png"
        expect 0 'specialisation +specialization constants: flags=' -- "$RTCL" render "$scene" \
            --width 61 --height 37 $direct --backend vulkan:0 --stats -o "$tmp/vk.png"
        checks=$((checks + 1))
        cmp -s "$tmp/cpu.png" "$tmp/vk.png" ||
            { echo "FAIL: $scene $direct: vulkan PNG differs"; fails=$((fails + 1)); }
    done
done
expect 0 'kernels +[0-9.]+ ms by timestamp queries \([0-9]+ dispatches' -- "$RTCL" render \
    builtin:cornell --width 32 --height 18 --backend vulkan --device 0 --stats -o "$tmp/vk.png"
expect 0 'kernel path +vulkan rt_vk_main, portable maths' -- "$RTCL" render builtin:cornell \
    --width 32 --height 18 --backend vulkan --stats -o "$tmp/vk.png"

# Ray queries: the same hit file as the oracle, closest and any hit.
awk 'BEGIN { srand(5); for (i = 0; i < 3000; i++) printf "%f %f %f %f %f %f 0 inf\n",
     rand() * 4 - 2, rand() * 3, rand() * 6 - 1, rand() - 0.5, rand() - 0.5, rand() - 0.5 }' >"$tmp/rays.txt"
for any in "" --any-hit; do
    expect 0 '' -- "$RTCL" trace builtin:cornell --rays "$tmp/rays.txt" --out "$tmp/cpu.hits" $any
    expect 0 '' -- "$RTCL" trace builtin:cornell --rays "$tmp/rays.txt" --out "$tmp/vk.hits" \
        --backend vulkan $any
    checks=$((checks + 1))
    [ "$(grep -c -v -E ' -1 -1$|^#' "$tmp/cpu.hits")" -gt 100 ] ||
        { echo "FAIL: trace $any: fewer than 100 hits, a weak test"; fails=$((fails + 1)); }
    checks=$((checks + 1))
    cmp -s "$tmp/cpu.hits" "$tmp/vk.hits" ||
        { echo "FAIL: trace $any: vulkan hits differ"; fails=$((fails + 1)); }
done

expect 2 'vulkan: no Vulkan device 99' -- "$RTCL" render builtin:cornell --width 32 --height 18 \
    --backend vulkan:99 -o "$tmp/x.png"
expect 2 'vulkan: no Vulkan device 99' -- "$RTCL" trace builtin:cornell --rays "$tmp/rays.txt" \
    --out "$tmp/x.hits" --backend vulkan --device 99

# No Vulkan driver: explicit vulkan fails with the reason, auto (with no
# OpenCL either) falls back to the CPU with a notice.
export VK_ICD_FILENAMES=$tmp/none.json VK_DRIVER_FILES=$tmp/none.json OCL_ICD_VENDORS=$tmp/none
expect 2 'no Vulkan driver found' -- "$RTCL" devices --api vulkan
expect 2 'vulkan: no Vulkan driver found' -- "$RTCL" render builtin:cornell --width 32 --height 18 \
    --backend vulkan -o "$tmp/x.png"
expect 0 'notice: .*vulkan not available \(no Vulkan driver found' -- "$RTCL" render \
    builtin:cornell --width 32 --height 18 --backend auto -o "$tmp/x.png"
unset VK_ICD_FILENAMES VK_DRIVER_FILES OCL_ICD_VENDORS
finish
