# SPDX-License-Identifier: Apache-2.0
# cli_portable_ir.sh - the portable maths profile holds no float division, no
# square root and no double (docs/PORTABLE_MATH.md): the kernels are compiled
# to LLVM IR by clang with the options the OpenCL backend uses for the
# profile (-DRT_PORTABLE_MATH, with and without -DRT_FLUSH_DENORMALS; every
# feature path present, as without -DRT_STATIC_FLAGS) and the IR is searched.
# The same check on the native build must find divisions, so a search that
# could never match fails too. A change that brings back a '/', a sqrt() or a
# double in the shared maths fails here.
source "$RT_SOURCE_DIR/tests/shell_check.sh"

clang=${RT_CLANG:-}
for c in clang-15 clang-14 clang; do
    [ -n "$clang" ] && break
    command -v "$c" > /dev/null && clang=$c
done
if [ -z "$clang" ]; then
    echo "skipped: no clang to compile the OpenCL kernels to LLVM IR (apt-get install clang)"; exit 77
fi
ir() { # ir OUT SOURCE OPTIONS...: the kernel source's LLVM IR
    local out=$1 src=$2
    shift 2
    "$clang" -x cl -cl-std=CL1.2 -Xclang -finclude-default-header -target spir64 -O1 \
        -emit-llvm -S -I "$RT_SOURCE_DIR/kernels" "$@" -o "$out" "$RT_SOURCE_DIR/kernels/$src"
}
# Float division; sqrt, rsqrt and the native/half variants (OpenCL builtins
# are mangled _Z<len><name>) or LLVM's intrinsic; any double.
forbidden='fdiv |@(_Z[0-9]+(sqrt|rsqrt|native_sqrt|native_rsqrt|half_sqrt|half_rsqrt|native_divide|half_divide)[a-zA-Z0-9_]*|llvm\.sqrt\.[a-z0-9.]*)\(|\bdouble\b|fpext '

for src in rt_single_ray.cl rt_ray_packet.cl; do
    for flush in "" -DRT_FLUSH_DENORMALS; do
        name="$src portable ${flush:-preserve}"
        checks=$((checks + 1))
        if ! ir "$tmp/p.ll" "$src" -DRT_PORTABLE_MATH $flush -DRT_PK_LANES=16 2> "$tmp/err"; then
            echo "FAIL: $name: clang failed:"; head -20 "$tmp/err"; fails=$((fails + 1)); continue
        fi
        if grep -n -E "$forbidden" "$tmp/p.ll" > "$tmp/found"; then
            echo "FAIL: $name: the portable program divides, takes a square root or uses double:"
            head -5 "$tmp/found"; fails=$((fails + 1))
        fi
    done
    # The native build divides in hardware: the search must see it.
    checks=$((checks + 1))
    if ir "$tmp/n.ll" "$src" -DRT_PK_LANES=16 2> "$tmp/err" && ! grep -q -E "$forbidden" "$tmp/n.ll"; then
        echo "FAIL: $src native: no division found, so the search above proves nothing"
        fails=$((fails + 1))
    fi
    # No funnel shift in either build: Oclgrind cannot run llvm.fshl/fshr
    # ("Undefined external function"), which clang made of the soft maths'
    # (q << 1) | (~t >> 31) (cli_oclgrind.sh runs the kernels there).
    checks=$((checks + 1))
    if grep -n -E '@llvm\.fsh[lr]\.' "$tmp/p.ll" "$tmp/n.ll" > "$tmp/found"; then
        echo "FAIL: $src: a funnel-shift intrinsic in the kernels' IR:"; head -5 "$tmp/found"
        fails=$((fails + 1))
    fi
done
finish
