# SPDX-License-Identifier: Apache-2.0
# cli_robust.sh - the numerical robustness suite (issue 6, docs/ROBUSTNESS.md):
# tests/robust/gen_cases.py writes hard cases with exact expectations, every
# backend traces them through 'rtcl trace' with every triangle test, and
# tests/robust/check_hits.py prints the per-category table. The watertight
# default must have no leak, false hit, wrong primitive or t out of bound on
# any backend; the other tests' failures are printed, not fatal.
source "$RT_SOURCE_DIR/tests/shell_check.sh"

# The backends that run the suite: a new backend is one more word here. A
# word BACKEND+portable runs the portable maths profile (--device-math
# portable), +flush the flushing denormal policy (--denormals flush); each
# is held to the oracle in its own denormal policy (cpu or cpu+flush);
# +packets and +single run the packet backend with --packet-path: every ray
# in packets, or every ray one at a time through the wide BVHs.
BACKENDS=${RT_ROBUST_BACKENDS:-"cpu packet+packets packet+single opencl opencl+portable cpu+flush packet+flush opencl+portable+flush vulkan vulkan+flush"}

# The rtcl options of a word, and the oracle it is compared with.
word_args() {
    local parts w
    IFS=+ read -r -a parts <<< "$1"
    echo -n "--backend ${parts[0]}"
    for w in "${parts[@]:1}"; do
        case $w in
            portable | native) echo -n " --device-math $w" ;;
            flush) echo -n " --denormals flush" ;;
            packets | single) echo -n " --packet-path $w" ;;
        esac
    done
}
word_oracle() { case $1 in *+flush*) echo cpu+flush ;; *) echo cpu ;; esac; }
# The triangle tests a word runs: all four on cpu, packet (both paths) and opencl (the
# speed-versus-error study's tests must hold the suite's expectations too),
# the default watertight test on the other words (profiles, policies, paths,
# vulkan), which is what they change; this keeps CI's time in bounds.
word_tris() { case $1 in cpu | packet | packet+packets | packet+single | opencl) echo "$TRI_TESTS" ;; *) echo watertight ;; esac; }
TRI_TESTS=${RT_ROBUST_TRI_TESTS:-"watertight mt pluecker badouel"}

if ! command -v python3 > /dev/null; then
    echo "python3 not found: the robustness suite needs it"; exit 77
fi
cases=${RT_BINARY_DIR:-$tmp}/robust_cases
python3 "$RT_SOURCE_DIR/tests/robust/gen_cases.py" "$cases" || exit 1
names=$(python3 -c 'import json, sys
for c in json.load(open(sys.argv[1]))["cases"]: print(c["name"], " ".join(c["flags"]))' "$cases/manifest.json")

for backend in $BACKENDS; do
    api=${backend%%+*}
    if { [ "$api" = opencl ] || [ "$api" = vulkan ]; } &&
        ! "$RTCL" devices --api "$api" > "$tmp/devices.txt" 2>&1; then
        # Only a build or machine without any such device gets here; CI has
        # PoCL and lavapipe.
        echo "skipped backend $backend: $(head -1 "$tmp/devices.txt")"
        continue
    fi
    for tri in $(word_tris "$backend"); do
        out=$tmp/$backend-$tri
        mkdir -p "$out"
        while read -r name flags; do
            # shellcheck disable=SC2086
            expect 0 '' -- "$RTCL" trace "$cases/$name.obj" --rays "$cases/$name.rays" \
                --out "$out/$name.hits" $(word_args "$backend") --tri-test "$tri" $flags
        done <<< "$names"
        strict=""
        [ "$tri" = watertight ] && strict=--strict
        checks=$((checks + 1))
        if ! python3 "$RT_SOURCE_DIR/tests/robust/check_hits.py" "$cases" "$out" "$backend/$tri" $strict; then
            echo "FAIL: $backend/$tri"; fails=$((fails + 1))
        fi
    done
done

# Every backend is bit-exact with the oracle: the same closest-hit files as
# cpu's in the same denormal policy (any-hit queries may report another hit
# in range; the check above holds them to the expectations).
for backend in $BACKENDS; do
    oracle=$(word_oracle "$backend")
    [ "$backend" = "$oracle" ] || [ ! -d "$tmp/$backend-watertight" ] || [ ! -d "$tmp/$oracle-watertight" ] && continue
    for tri in $(word_tris "$backend"); do
        while read -r name flags; do
            case " $flags " in *" --any-hit "*) continue ;; esac
            checks=$((checks + 1))
            cmp -s "$tmp/$oracle-$tri/$name.hits" "$tmp/$backend-$tri/$name.hits" ||
                { echo "FAIL: $backend/$tri $name: hits differ from $oracle's"; fails=$((fails + 1)); }
        done <<< "$names"
    done
done

# NaN and Inf in the input are refused at load, with the file and line.
printf '0 0 5 0 0 -1 0 inf\n' > "$tmp/one.rays"
for bad in 'v 1 inf 0' 'v -Infinity 0 0' 'v 0 0 1e39' 'v nan 0 0'; do
    printf 'v 0 0 0\nv 1 0 0\n%s\nf 1 2 3\n' "$bad" > "$tmp/bad.obj"
    expect 2 "bad.obj:3(:[0-9]+)?: .*(NaN|[Ii]nf|finite)" -- "$RTCL" trace "$tmp/bad.obj" \
        --rays "$tmp/one.rays" --out "$tmp/x.hits"
done
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 nan 1\nf 1//1 2//1 3//1\n' > "$tmp/badn.obj"
expect 2 "badn.obj:4(:[0-9]+)?: .*(NaN|[Ii]nf|finite)" -- "$RTCL" trace "$tmp/badn.obj" \
    --rays "$tmp/one.rays" --out "$tmp/x.hits"
expect 2 "--tri-test: 'fast' is not one of watertight, mt, pluecker or badouel" -- "$RTCL" trace "$tmp/badn.obj" --rays "$tmp/one.rays" \
    --out "$tmp/x.hits" --tri-test fast
finish
