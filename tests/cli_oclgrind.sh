# SPDX-License-Identifier: Apache-2.0
# cli_oclgrind.sh - the OpenCL kernels under Oclgrind (an OpenCL simulator
# that checks every memory access of every work-item, and here also data
# races and API use): small frames of two shipped scenes through
# 'rtcl render --backend opencl' on Oclgrind's device, in every kernel
# variant (maths native, portable, and portable with flushed denormals;
# packet and one-ray kernels, the wavefront and rt_k_shade's stack; BVH and
# kd-tree meshes), and ray queries (closest and any hit). Each run must leave
# Oclgrind's log empty (no error or warning report) and give the CPU
# oracle's image (the PFM files, raw floats, byte for byte) or hits. Then the
# completion check (docs/OPENCL.md, "Failures"): kernels built to leave
# work-items unfinished (RTCL_TEST_OPENCL_SKIP) must fail the frame or the
# query with the reason, and write no file.
# Oclgrind is selected through the ICD loader (OCL_ICD_VENDORS: a folder with
# an .icd file naming its liboclgrind-rt-icd.so), its checks through the
# variables its 'oclgrind' wrapper sets. Skipped (77) without oclgrind.
source "$RT_SOURCE_DIR/tests/shell_check.sh"

if ! command -v oclgrind > /dev/null; then
    echo "skipped: oclgrind not installed (apt-get install oclgrind)"; exit 77
fi
if "$RTCL" devices --api opencl 2>&1 | grep -q "no OpenCL backend"; then
    echo "skipped: this build has no OpenCL backend"; exit 77
fi
lib=
bin=$(dirname "$(readlink -f "$(command -v oclgrind)")")
for d in "$bin/../lib/oclgrind" "$bin/../lib64/oclgrind" /usr/lib/oclgrind /usr/lib64/oclgrind \
    /usr/lib/*-linux-gnu/oclgrind /usr/local/lib/oclgrind; do
    [ -f "$d/liboclgrind-rt-icd.so" ] && { lib=$(readlink -f "$d/liboclgrind-rt-icd.so"); break; }
done
if [ -z "$lib" ]; then
    echo "FAIL: oclgrind is installed but its ICD library liboclgrind-rt-icd.so was not found"; exit 1
fi
mkdir "$tmp/icd"
echo "$lib" > "$tmp/icd/oclgrind.icd"
log=$tmp/oclgrind.log
# og CMD...: CMD with Oclgrind as the only OpenCL driver, its memory checks
# (always on), data-race and API checks, and its reports in $log. Oclgrind
# holds on to some of its memory at exit: no leak check in the sanitizer
# build (its other checks stay on).
og() {
    rm -f "$log"
    OCL_ICD_VENDORS=$tmp/icd OCLGRIND_CHECK_API=1 OCLGRIND_DATA_RACES=1 OCLGRIND_LOG=$log \
        no_leak_check "$@"
}
# clean NAME: Oclgrind reported nothing for the last og command.
clean() {
    checks=$((checks + 1))
    if [ -s "$log" ]; then
        echo "FAIL: $1: Oclgrind reported:"; head -30 "$log"; fails=$((fails + 1))
    fi
}

expect 0 'device 0: Oclgrind' -- og "$RTCL" devices --api opencl
clean "rtcl devices"

# case SCENE WIDTH HEIGHT PATH ORACLE-OPTIONS -- OPENCL-OPTIONS: the frame on
# the CPU oracle and on Oclgrind; PATH is what --stats must name as the
# kernel path.
case_() {
    local scene=$1 w=$2 h=$3 path=$4 cpu=() cl=()
    shift 4
    while [ "$1" != -- ]; do cpu+=("$1"); shift; done
    shift
    cl=("$@")
    local name="$scene ${w}x$h ${cpu[*]} ${cl[*]}"
    expect 0 'wrote' -- "$RTCL" render "$RT_SOURCE_DIR/scenes/$scene" --width $w --height $h \
        "${cpu[@]}" -o "$tmp/cpu.pfm"
    rm -f "$tmp/cl.pfm"
    expect 0 "kernel path +$path" -- og "$RTCL" render "$RT_SOURCE_DIR/scenes/$scene" \
        --width $w --height $h --backend opencl --stats "${cpu[@]}" "${cl[@]}" -o "$tmp/cl.pfm"
    clean "$name"
    checks=$((checks + 1))
    if ! cmp -s "$tmp/cpu.pfm" "$tmp/cl.pfm"; then
        echo "FAIL: $name: the image differs from the oracle's:"
        "$RTCL" compare "$tmp/cpu.pfm" "$tmp/cl.pfm" 2>&1 | head -5
        fails=$((fails + 1))
    fi
}

# cornell: a mirror and a glass sphere (Whitted: the one-ray kernels go
# through the wavefront, or rt_k_shade's stack with --cl-no-wavefront),
# vertex normals: every maths profile on every kernel path, BVH and kd-tree
# meshes in turn. keyframes (meshes, instances with transforms; 21x13: packet
# blocks cut at the right and bottom edges): each profile once.
packet='packet'
wave='one ray per work-item \(wavefront\)'
stack='one ray per work-item$'
accel=bvh
for math in "--device-math native" "--device-math portable" "--denormals flush --device-math portable"; do
    for path in packet wave stack; do
        case $path in
            packet) opts=() ;;
            wave) opts=(--cl-one-ray) ;;
            stack) opts=(--cl-one-ray --cl-no-wavefront) ;;
        esac
        flush=()
        [[ $math == --denormals* ]] && flush=(--denormals flush)
        case_ cornell.json 24 16 "${!path}" "${flush[@]}" --accel $accel -- ${math#--denormals flush } \
            "${opts[@]}"
        [ $accel = bvh ] && accel=kd || accel=bvh
    done
done
case_ keyframes.json 21 13 "$packet" -- --device-math native
case_ keyframes.json 21 13 "$wave" --accel kd -- --device-math portable --cl-one-ray
case_ keyframes.json 21 13 "$packet" --denormals flush --accel kd -- --device-math portable

# Ray queries: closest hits through rt_k_packet_trace, any hits through
# rt_k_trace, the oracle's hit lines.
cornell_rays 7 100 "$tmp/rays.txt"
for any in "" --any-hit; do
    expect 0 '' -- "$RTCL" trace "$RT_SOURCE_DIR/scenes/cornell.json" --rays "$tmp/rays.txt" \
        --out "$tmp/h_cpu.txt" $any
    expect 0 '' -- og "$RTCL" trace "$RT_SOURCE_DIR/scenes/cornell.json" --rays "$tmp/rays.txt" \
        --out "$tmp/h_cl.txt" --backend opencl --device-math native $any
    clean "trace $any"
    checks=$((checks + 1))
    cmp -s "$tmp/h_cpu.txt" "$tmp/h_cl.txt" ||
        { echo "FAIL: trace $any: the hits differ from the oracle's"; fails=$((fails + 1)); }
done

# The completion check: every 4th work-item left unfinished. Packet kernel,
# the one-ray kernels (the wavefront's first kernel, and rt_k_camera), both
# ray queries: status 2, the kernel and its count named, no file.
cut() { RTCL_TEST_OPENCL_SKIP=4 og "$@"; }
miss='kernel rt_k_[a-z_]+ on .Oclgrind Simulator. finished [0-9]+ of [0-9]+ work-items .* cut the launch short'
for opts in "" "--cl-one-ray" "--cl-one-ray --cl-no-wavefront"; do
    rm -f "$tmp/cut.png"
    expect 2 "$miss" -- cut "$RTCL" render \
        "$RT_SOURCE_DIR/scenes/cornell.json" --width 8 --height 8 --backend opencl \
        --device-math native $opts -o "$tmp/cut.png"
    checks=$((checks + 1))
    [ ! -e "$tmp/cut.png" ] || { echo "FAIL: cut short ($opts): an image was written"; fails=$((fails + 1)); }
done
for any in "" --any-hit; do
    rm -f "$tmp/cut.txt"
    expect 2 "$miss" -- cut "$RTCL" trace \
        "$RT_SOURCE_DIR/scenes/cornell.json" --rays "$tmp/rays.txt" --out "$tmp/cut.txt" \
        --backend opencl --device-math native $any
    checks=$((checks + 1))
    [ ! -e "$tmp/cut.txt" ] || { echo "FAIL: cut short (trace $any): a hit file was written"; fails=$((fails + 1)); }
done
finish
