# SPDX-License-Identifier: Apache-2.0
# cli_vulkan_validation.sh - the Vulkan backend under the Khronos validation
# layer (Debian's vulkan-validationlayers) with synchronization validation:
# renders (Whitted and direct, BVH and kd-tree meshes, instances) and
# closest and any-hit ray queries (the resumed items after lavapipe's loop
# budget: test_vulkan_resume, run the same way by hand, docs/VULKAN.md). Every run must leave the layer's log empty (no error, warning or
# performance warning) and give the oracle's bytes.
source "$RT_SOURCE_DIR/tests/shell_check.sh"

skip_without_vulkan
layer=
for d in /usr/share/vulkan/explicit_layer.d /usr/local/share/vulkan/explicit_layer.d; do
    [ -f "$d/VkLayer_khronos_validation.json" ] && layer=$d/VkLayer_khronos_validation.json
done
[ -n "$layer" ] || { echo "skipped: the Khronos validation layer is not installed (vulkan-validationlayers)"; exit 77; }

# The layer's settings (the loader reads vk_layer_settings.txt from
# VK_LAYER_SETTINGS_PATH): messages to a file, not stdout, of every severity
# that means a fault; synchronization validation on.
log=$tmp/validation.log
mkdir -p "$tmp/settings"
cat >"$tmp/settings/vk_layer_settings.txt" <<EOF
khronos_validation.debug_action = VK_DBG_LAYER_ACTION_LOG_MSG
khronos_validation.log_filename = $log
khronos_validation.report_flags = error,warn,perf
khronos_validation.enables = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT
EOF
# vv CMD...: CMD with the validation layer on.
vv() {
    rm -f "$log"
    VK_INSTANCE_LAYERS=VK_LAYER_KHRONOS_validation VK_LAYER_SETTINGS_PATH=$tmp/settings \
        no_leak_check "$@"
}
# quiet NAME: the layer logged nothing for the last vv command.
quiet() {
    checks=$((checks + 1))
    if [ -s "$log" ]; then
        echo "FAIL: $1: the validation layer reported:"; head -30 "$log"; fails=$((fails + 1))
    fi
}
# The layer must really be on and its log written: with info messages on it
# logs the instance's creation.
rm -f "$log"
printf 'khronos_validation.report_flags = error,warn,perf,info\n' >>"$tmp/settings/vk_layer_settings.txt"
VK_INSTANCE_LAYERS=VK_LAYER_KHRONOS_validation VK_LAYER_SETTINGS_PATH=$tmp/settings \
    no_leak_check "$RTCL" devices --api vulkan >/dev/null 2>&1 || true
checks=$((checks + 1))
[ -s "$log" ] || { echo "FAIL: the validation layer wrote no log with info messages on: not loaded?"; fails=$((fails + 1)); }
sed -i '$d' "$tmp/settings/vk_layer_settings.txt"

# same NAME A B: files A and B are byte-identical.
same() {
    checks=$((checks + 1))
    cmp -s "$2" "$3" || { echo "FAIL: $1: differs from the oracle's"; fails=$((fails + 1)); }
}

for args in "builtin:cornell" "builtin:keyframes --direct" "$RT_SOURCE_DIR/scenes/cornell.json --accel kd"; do
    expect 0 'wrote' -- "$RTCL" render $args --width 40 --height 24 -o "$tmp/cpu.pfm"
    expect 0 'wrote' -- vv "$RTCL" render $args --width 40 --height 24 --backend vulkan -o "$tmp/vk.pfm"
    quiet "render $args"
    same "render $args" "$tmp/cpu.pfm" "$tmp/vk.pfm"
done

cornell_rays 11 200 "$tmp/rays.txt"
for any in "" --any-hit; do
    expect 0 '' -- "$RTCL" trace "$RT_SOURCE_DIR/scenes/cornell.json" --rays "$tmp/rays.txt" \
        --out "$tmp/h_cpu.txt" $any
    expect 0 '' -- vv "$RTCL" trace "$RT_SOURCE_DIR/scenes/cornell.json" --rays "$tmp/rays.txt" \
        --out "$tmp/h_vk.txt" --backend vulkan $any
    quiet "trace $any"
    same "trace $any" "$tmp/h_cpu.txt" "$tmp/h_vk.txt"
done
finish
