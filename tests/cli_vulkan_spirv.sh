# SPDX-License-Identifier: Apache-2.0
# cli_vulkan_spirv.sh - the shipped SPIR-V modules of the Vulkan backend
# (build/spirv/*.spv, the bytes embedded in rtcl) are in the portable maths
# profile: spirv-dis shows no OpFDiv, no Sqrt or InverseSqrt, no Float64, and
# NoContraction on every float arithmetic instruction
# (tests/vulkan_spirv_check.py). The check is shown to fail where it must: on
# glslang's output before the NoContraction step, and on a shader with a
# division, a sqrt and a double.
source "$RT_SOURCE_DIR/tests/shell_check.sh"

spv=$RT_BINARY_DIR/spirv
if [ ! -f "$spv/rt_vk_main.spv" ]; then
    echo "skipped: this build has no Vulkan backend (no $spv/rt_vk_main.spv)"; exit 77
fi
if ! command -v spirv-dis >/dev/null; then
    echo "skipped: spirv-dis not found (install spirv-tools)"; exit 77
fi
check="python3 $RT_SOURCE_DIR/tests/vulkan_spirv_check.py"

for m in rt_vk_main rt_vk_soft_test rt_vk_interface_test; do
    checks=$((checks + 1))
    if ! out=$(spirv-dis --raw-id "$spv/$m.spv" | $check "$m"); then
        echo "FAIL: $m.spv:"; echo "$out"; fails=$((fails + 1))
    else
        echo "$out"
    fi
    # spirv-val accepts the module as it ships.
    if command -v spirv-val >/dev/null; then
        expect 0 '' -- spirv-val "$spv/$m.spv"
    fi
done

# glslang's own output (before kernels/vulkan/spv_precise.c) lacks the
# decorations: the check must reject it.
checks=$((checks + 1))
if spirv-dis --raw-id "$RT_BINARY_DIR/generated/rt_vk_main.glslang.spv" | $check raw >/dev/null; then
    echo "FAIL: the check accepts glslang's undecorated output"; fails=$((fails + 1))
fi
# A shader with a division, a sqrt and a double is rejected for each.
if command -v glslangValidator >/dev/null; then
    cat >"$tmp/bad.comp" <<'GLSL'
#version 450
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer B { float x[]; double y[]; };
void main() { x[0] = x[1] / x[2] + sqrt(x[3]) + inversesqrt(x[4]); y[0] = y[1] * y[2]; }
GLSL
    glslangValidator -V --quiet -o "$tmp/bad.spv" "$tmp/bad.comp" >/dev/null
    out=$(spirv-dis --raw-id "$tmp/bad.spv" | $check bad) && rc=0 || rc=$?
    for what in 'a float division' 'a square root' 'Float64' 'no NoContraction'; do
        checks=$((checks + 1))
        if [ "$rc" = 0 ] || ! grep -q "$what" <<<"$out"; then
            echo "FAIL: the check misses '$what' in a bad shader:"; echo "$out"; fails=$((fails + 1))
        fi
    done
fi

finish
