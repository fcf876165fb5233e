#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# cli_bench_animate.sh - 'rtcl bench --animate --json' on the shipped keyframe
# scene at a tiny size: one JSON object with a "dynamic" array holding our
# four update policies (and Embree's three qualities where the build has
# Embree; otherwise no Embree rows and the object says why), every row with
# the documented fields and sane numbers, the SAH costs positive, and every
# policy's frames bit-identical to the sah policy's (the command compares each
# frame's image with sah's); a scene where nothing morphs is refused with
# a message.
set -u
command -v python3 >/dev/null || { echo "skipped: python3 is needed to parse JSON"; exit 77; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
scene=$RT_SOURCE_DIR/scenes/keyframes_animated.json

out=$("$RTCL" bench --animate "$scene" --json --reps 2 --threads 2 --width 48 --height 27 \
    --fps 6 --frames 7 --series 2>"$dir/err") || { echo "rtcl bench --animate failed:"; cat "$dir/err"; exit 1; }
[ -s "$dir/err" ] && { echo "unexpected stderr (not a terminal):"; cat "$dir/err"; exit 1; }

# Whether this build has Embree (the compile definition of the peer).
embree=unknown
if [ -f "$RT_BINARY_DIR/build.ninja" ]; then
    if grep -q "RT_HAVE_EMBREE=1" "$RT_BINARY_DIR/build.ninja"; then embree=yes; else embree=no; fi
fi

python3 - "$out" "$embree" <<'PY' || exit 1
import json, math, sys
lines = sys.argv[1].strip().split("\n")
assert len(lines) == 1, "expected one line per scene, got %d" % len(lines)
obj = json.loads(lines[0])
assert obj["scene"].endswith("keyframes_animated.json"), obj["scene"]
assert obj["frames"] == 7 and obj["runs"] == 2 and obj["keyframes"] == 4, obj
assert obj["width"] == 48 and obj["height"] == 27 and obj["threads"] == 2, obj
assert obj["morph_triangles"] > 0 and obj["triangles"] >= obj["morph_triangles"], obj
rows = obj["dynamic"]
keys = ["scene", "engine", "policy", "update_ms_min", "update_ms_median", "frame_ms_min",
        "frame_ms_median", "sah"]
ours = {r["policy"]: r for r in rows if r["engine"] == "rtcl"}
assert sorted(ours) == ["auto", "lbvh", "refit", "sah"], sorted(ours)
emb = {r["policy"]: r for r in rows if r["engine"] == "embree"}
assert all(r["engine"] in ("rtcl", "embree") for r in rows), rows
for r in rows:
    assert "error" not in r, "row failed: %s" % r
    for k in keys:
        assert k in r, "row %s %s lacks %s" % (r["engine"], r["policy"], k)
    assert r["scene"] == obj["scene"]
    for k in ("update_ms", "frame_ms"):
        lo, med = r[k + "_min"], r[k + "_median"]
        assert isinstance(lo, float) and 0 <= lo <= med < 60000, (r["policy"], k, lo, med)
    # The frame includes the update.
    assert r["frame_ms_min"] >= r["update_ms_min"] * 0.999, r
    s = r["series"]
    for k in ("update_ms", "trace_ms", "frame_ms", "sah"):
        assert len(s[k]) == 7, (k, len(s[k]))
for p, r in ours.items():
    assert isinstance(r["sah"], float) and r["sah"] > 0, (p, r["sah"])
    assert all(x > 0 for x in r["series"]["sah"]), (p, r["series"]["sah"])
    if p != "sah":
        assert r["images_match_rebuild"] is True, "%s frames differ from the sah policy's" % p
# refit keeps frame 0's tree: its SAH cost is never below a fresh SAH build's
# by much.
assert ours["refit"]["sah"] >= ours["sah"]["sah"] * 0.9, ours
has = sys.argv[2]
if emb:
    assert sorted(emb) == ["low", "medium", "refit"], sorted(emb)
    assert "embree_missing" not in obj
    for r in emb.values():
        assert r["lanes"] in (1, 4, 8, 16) and r["sah"] > 0 and r["sah_note"], r
    assert has != "no", "Embree rows from a build without Embree"
    print("embree rows:", sorted(emb), "lanes", emb["low"]["lanes"])
else:
    assert obj.get("embree_missing"), "no Embree rows and no reason given"
    assert has != "yes", "this build has Embree but no Embree rows: %s" % obj["embree_missing"]
    print("embree: not in this build:", obj["embree_missing"])
print("ok:", {p: round(r["sah"], 2) for p, r in ours.items()})
PY

# The table, and a clear refusal of a scene where nothing morphs.
"$RTCL" bench --animate "$scene" --reps 1 --threads 2 --width 32 --height 18 --frames 2 \
    >"$dir/text" 2>"$dir/err" || { echo "text mode failed:"; cat "$dir/err"; exit 1; }
grep -q "refit .*= sah" "$dir/text" || { echo "text mode: no refit row:"; cat "$dir/text"; exit 1; }
if "$RTCL" bench --animate "$RT_SOURCE_DIR/scenes/cornell.json" --reps 1 --width 16 --height 9 \
    >/dev/null 2>"$dir/err"; then
    echo "a scene without a morphing object was accepted"; exit 1
fi
grep -q "no object morphs between keyframes" "$dir/err" || { echo "unclear refusal:"; cat "$dir/err"; exit 1; }
# Options of the other mode are refused, not ignored.
for args in "--animate --accel kd" "--animate --no-render" "--animate --denormals flush" \
    "--frames 2" "--series"; do
    # shellcheck disable=SC2086
    if "$RTCL" bench $args "$scene" >/dev/null 2>"$dir/err"; then
        echo "rtcl bench $args was accepted"; exit 1
    fi
    grep -q "not apply\|need --animate" "$dir/err" || { echo "$args: unclear error:"; cat "$dir/err"; exit 1; }
done
echo "ok"
