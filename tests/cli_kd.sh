# SPDX-License-Identifier: Apache-2.0
# cli_kd.sh - SAH kd-trees (issue 18) against the BVH, bit for bit, through
# rtcl on every backend: the images of every shipped scene (scenes/*.json)
# and built-in scene, the robustness suite's hit files (tests/robust) and
# random rays, on the packet backend through each of its paths (packets, and
# the single-ray path over wide BVHs, which hands kd instances to the
# oracle's traversal); then the --accel and "accel" errors, rtcl info's
# report, deforming meshes keeping BVHs, and the Vulkan backend's
# specialisation (the kd traversal compiled in only for kd layouts).
# The kd images and closest hits must be the BVH oracle's (cpu, --accel bvh)
# exactly: the closest hit has a total order, so the structure cannot change
# it. Any-hit queries may report another hit in range and are held to the
# robustness suite's expectations instead.
source "$RT_SOURCE_DIR/tests/shell_check.sh"

BACKENDS=${RT_KD_BACKENDS:-"cpu packet opencl vulkan"}
ACCELS="kd kd-binned"
# Vulkan runs the exact trees only here: the binned trees go through the
# same GLSL traversal, and test_vulkan_oracle traces them on Vulkan too
# (images and random rays); lavapipe is slow and CI's time is bounded.
skip_binned_vulkan() { [ "$1" = kd-binned ] && [ "$2" = vulkan ]; }
if ! "$RTCL" devices > "$tmp/devices.txt" 2>&1; then
    # Only a build or machine without any OpenCL device gets here; CI has PoCL.
    echo "skipped backend opencl: $(head -1 "$tmp/devices.txt")"
    BACKENDS=${BACKENDS//opencl/}
fi
if ! "$RTCL" devices --api vulkan > "$tmp/vk_devices.txt" 2>&1; then
    # A build without the Vulkan backend or a machine without a Vulkan
    # device; CI has lavapipe.
    echo "skipped backend vulkan: $(head -1 "$tmp/vk_devices.txt")"
    BACKENDS=${BACKENDS//vulkan/}
fi

# ---- images: every shipped and built-in scene ---------------------------
# A smaller frame than the scenes' own keeps the test short; every pixel
# still goes through primary, shadow, reflection and refraction rays.
scenes="builtin:cornell builtin:keyframes"
for f in "$RT_SOURCE_DIR"/scenes/*.json; do scenes="$scenes $f"; done
for scene in $scenes; do
    name=$(basename "$scene" .json)
    name=${name#builtin:}
    expect 0 '' -- "$RTCL" render "$scene" -o "$tmp/$name-bvh.ppm" --width 256 --height 144 \
        --accel bvh
    for accel in $ACCELS; do
        for backend in $BACKENDS; do
            skip_binned_vulkan "$accel" "$backend" && continue
            expect 0 '' -- "$RTCL" render "$scene" -o "$tmp/$name-$accel-$backend.ppm" \
                --width 256 --height 144 --accel "$accel" --backend "$backend"
            checks=$((checks + 1))
            cmp -s "$tmp/$name-bvh.ppm" "$tmp/$name-$accel-$backend.ppm" ||
                { echo "FAIL: $name --accel $accel --backend $backend: image differs from the BVH's"
                  fails=$((fails + 1)); }
        done
    done
done
# The depth and primitive AOVs hold the hits themselves (EXR: raw floats).
for aov in depth primid; do
    expect 0 '' -- "$RTCL" render builtin:cornell -o "$tmp/aov-bvh.exr" --width 200 --height 120 \
        --aov $aov
    for backend in $BACKENDS; do
        expect 0 '' -- "$RTCL" render builtin:cornell -o "$tmp/aov-kd.exr" --width 200 \
            --height 120 --aov $aov --accel kd --backend "$backend"
        checks=$((checks + 1))
        # EXR files carry a time stamp: compare the pixels (exactly).
        "$RTCL" compare "$tmp/aov-bvh.exr" "$tmp/aov-kd.exr" > /dev/null ||
            { echo "FAIL: --aov $aov on $backend: kd differs from the BVH"; fails=$((fails + 1)); }
    done
done

# ---- the robustness suite ---------------------------------------------------
if command -v python3 > /dev/null; then
    cases=$tmp/robust_cases
    python3 "$RT_SOURCE_DIR/tests/robust/gen_cases.py" "$cases" || exit 1
    names=$(python3 -c 'import json, sys
for c in json.load(open(sys.argv[1]))["cases"]: print(c["name"], " ".join(c["flags"]))' "$cases/manifest.json")
    run_suite() { # accel backend tri
        local out=$tmp/robust-$1-$2-$3
        mkdir -p "$out"
        while read -r name flags; do
            # shellcheck disable=SC2086
            expect 0 '' -- "$RTCL" trace "$cases/$name.obj" --rays "$cases/$name.rays" \
                --out "$out/$name.hits" --backend "$2" --tri-test "$3" --accel "$1" $flags
        done <<< "$names"
    }
    for tri in watertight mt; do
        run_suite bvh cpu $tri
        for accel in $ACCELS; do
            for backend in $BACKENDS; do
                skip_binned_vulkan "$accel" "$backend" && continue
                # Each other triangle test on the oracle only (they share the
                # traversal); the watertight default on every backend.
                [ "$tri" != watertight ] && [ "$backend" != cpu ] && continue
                run_suite "$accel" "$backend" $tri
                out=$tmp/robust-$accel-$backend-$tri
                if [ "$tri" = watertight ]; then
                    checks=$((checks + 1))
                    python3 "$RT_SOURCE_DIR/tests/robust/check_hits.py" "$cases" "$out" \
                        "$accel/$backend/$tri" --strict > "$tmp/check.txt" ||
                        { cat "$tmp/check.txt"; echo "FAIL: robustness suite, $accel on $backend"
                          fails=$((fails + 1)); }
                fi
                while read -r name flags; do
                    case " $flags " in *" --any-hit "*) continue ;; esac
                    checks=$((checks + 1))
                    cmp -s "$tmp/robust-bvh-cpu-$tri/$name.hits" "$out/$name.hits" ||
                        { echo "FAIL: $accel/$backend/$tri $name: hits differ from the BVH's"
                          fails=$((fails + 1)); }
                done <<< "$names"
            done
        done
    done

    # ---- random rays ------------------------------------------------------------
    # From anywhere in and around the Cornell box towards anywhere in it, a
    # third with zero direction components from grid points (rays in the
    # walls' planes and along their edges).
    python3 - "$tmp/random.rays" << 'EOF'
import random, sys
random.seed(18)
with open(sys.argv[1], "w") as f:
    for i in range(20000):
        if i % 3 == 0:
            o = [random.choice([-1.0, -0.5, 0.0, 0.5, 1.0, 1.8]) for _ in range(3)]
            d = [random.choice([-1.0, 0.0, 0.0, 1.0]) for _ in range(3)]
            if d == [0.0, 0.0, 0.0]:
                d[2] = 1.0
        else:
            o = [random.uniform(-1.5, 1.5), random.uniform(-0.5, 2.3), random.uniform(-1.5, 3.0)]
            d = [random.uniform(-1.0, 1.0) - o[0] * 0.3 for _ in range(3)]
        f.write("%r %r %r %r %r %r 0 inf\n" % tuple(o + d))
EOF
    expect 0 '' -- "$RTCL" trace builtin:cornell --rays "$tmp/random.rays" --out "$tmp/random-bvh.hits"
    for accel in $ACCELS; do
        for backend in $BACKENDS; do
            skip_binned_vulkan "$accel" "$backend" && continue
            expect 0 '' -- "$RTCL" trace builtin:cornell --rays "$tmp/random.rays" \
                --out "$tmp/random-$accel-$backend.hits" --accel "$accel" --backend "$backend"
            checks=$((checks + 1))
            cmp -s "$tmp/random-bvh.hits" "$tmp/random-$accel-$backend.hits" ||
                { echo "FAIL: random rays, $accel on $backend: hits differ from the BVH's"
                  fails=$((fails + 1)); }
        done
    done
    # The packet backend's two paths forced: packets, and one ray at a time
    # through the wide BVHs (kd instances there go through the oracle's
    # traversal), for closest and any hits; the robustness suite through the
    # single-ray path too.
    if [[ " $BACKENDS " == *" packet "* ]]; then
        for any in "" --any-hit; do
            # shellcheck disable=SC2086
            expect 0 '' -- "$RTCL" trace builtin:cornell --rays "$tmp/random.rays" \
                --out "$tmp/random-bvh-cpu$any.hits" --backend cpu $any
            for accel in $ACCELS; do
                for path in packets single; do
                    # shellcheck disable=SC2086
                    expect 0 '' -- "$RTCL" trace builtin:cornell --rays "$tmp/random.rays" \
                        --out "$tmp/random-$accel-$path$any.hits" --accel "$accel" \
                        --backend packet --packet-path $path $any
                    # Closest hits exactly; any hit: whether the ray hits (which
                    # hit in range it reports may differ).
                    checks=$((checks + 1))
                    if [ -z "$any" ]; then
                        cmp -s "$tmp/random-bvh-cpu.hits" "$tmp/random-$accel-$path.hits"
                    else
                        [ "$(cut -d' ' -f1 "$tmp/random-bvh-cpu$any.hits")" = \
                            "$(cut -d' ' -f1 "$tmp/random-$accel-$path$any.hits")" ]
                    fi || { echo "FAIL: random rays$any, $accel on packet --packet-path $path:" \
                        "hits differ from the BVH oracle's"; fails=$((fails + 1)); }
                done
            done
        done
        for accel in $ACCELS; do
            out=$tmp/robust-$accel-single
            mkdir -p "$out"
            while read -r name flags; do
                # shellcheck disable=SC2086
                expect 0 '' -- "$RTCL" trace "$cases/$name.obj" --rays "$cases/$name.rays" \
                    --out "$out/$name.hits" --backend packet --packet-path single \
                    --accel "$accel" $flags
                case " $flags " in *" --any-hit "*) continue ;; esac
                checks=$((checks + 1))
                cmp -s "$tmp/robust-bvh-cpu-watertight/$name.hits" "$out/$name.hits" ||
                    { echo "FAIL: $accel/packet single path $name: hits differ from the BVH's"
                      fails=$((fails + 1)); }
            done <<< "$names"
            checks=$((checks + 1))
            python3 "$RT_SOURCE_DIR/tests/robust/check_hits.py" "$cases" "$out" \
                "$accel/packet-single" --strict > "$tmp/check.txt" ||
                { cat "$tmp/check.txt"; echo "FAIL: robustness suite, $accel on packet single path"
                  fails=$((fails + 1)); }
        done
    fi
else
    echo "skipped the robustness suite and random rays: python3 not found"
fi

# ---- choices, errors, info ---------------------------------------------------
expect 2 "--accel: 'octree' is not one of bvh, kd or kd-binned" -- "$RTCL" render builtin:cornell \
    -o "$tmp/x.png" --accel octree
sed 's|"room": {"file": "cornell_room.obj"}|"room": {"file": "cornell_room.obj", "accel": 3}|' \
    "$RT_SOURCE_DIR/scenes/cornell.json" > "$RT_SOURCE_DIR/scenes/.cli_kd_bad.json"
expect 2 'cli_kd_bad.json:[0-9]+:[0-9]+: meshes.room.accel: expected "bvh", "kd" or "kd-binned", found an? (integer|number)' \
    -- "$RTCL" info "$RT_SOURCE_DIR/scenes/.cli_kd_bad.json"
sed 's|"room": {"file": "cornell_room.obj"}|"room": {"file": "cornell_room.obj", "accel": "kd"}|' \
    "$RT_SOURCE_DIR/scenes/cornell.json" > "$RT_SOURCE_DIR/scenes/.cli_kd_good.json"
expect 0 'cornell_room.obj +6 triangles, 12 vertices, kd' -- "$RTCL" info \
    "$RT_SOURCE_DIR/scenes/.cli_kd_good.json"
expect 0 'cornell_left_wall.obj +2 triangles, 4 vertices, bvh' -- "$RTCL" info \
    "$RT_SOURCE_DIR/scenes/.cli_kd_good.json"
# A deforming mesh keeps a BVH: an update policy other than rebuild wins
# over "accel" (kd-trees are for static meshes; never refitted).
sed 's|"room": {"file": "cornell_room.obj"}|"room": {"file": "cornell_room.obj", "accel": "kd", "update": "refit"}|' \
    "$RT_SOURCE_DIR/scenes/cornell.json" > "$RT_SOURCE_DIR/scenes/.cli_kd_refit.json"
expect 0 'cornell_room.obj +6 triangles, 12 vertices, update refit, bvh' -- "$RTCL" info \
    "$RT_SOURCE_DIR/scenes/.cli_kd_refit.json"
rm -f "$RT_SOURCE_DIR/scenes/.cli_kd_bad.json" "$RT_SOURCE_DIR/scenes/.cli_kd_good.json" \
    "$RT_SOURCE_DIR/scenes/.cli_kd_refit.json"
# --accel changes the static meshes only: the columns are keyframes.
expect 0 'column_0 +100 triangles, 52 vertices, bvh' -- "$RTCL" info builtin:cornell \
    --accel kd
expect 0 'mirror_sphere +2208 triangles, 1225 vertices, normals, kd' -- "$RTCL" info \
    builtin:cornell --accel kd

# ---- the Vulkan backend: the kd traversal only where a kd mesh is --------
if [[ " $BACKENDS " == *" vulkan "* ]]; then
    expect 0 'specialisation +specialization constants: .*inst_mask=7 .*kd=yes' -- "$RTCL" \
        render builtin:cornell -o "$tmp/vk.png" --width 32 --height 18 --backend vulkan \
        --accel kd --stats
    expect 0 'specialisation +specialization constants: .*inst_mask=3 .*kd=no' -- "$RTCL" \
        render builtin:cornell -o "$tmp/vk.png" --width 32 --height 18 --backend vulkan \
        --accel bvh --stats
    expect 0 'vulkan +specialization constants: .*kd-tree traversal on' -- "$RTCL" info \
        builtin:cornell --accel kd
    expect 0 'vulkan +specialization constants: .*kd-tree traversal off' -- "$RTCL" info \
        builtin:cornell
fi
finish
