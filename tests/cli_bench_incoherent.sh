#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# cli_bench_incoherent.sh - 'rtcl bench --incoherent' (issue 20) on the
# shipped Cornell box (or its room, without JSON) with few rays: one JSON object per scene whose
# "incoherent" array has a row per (rays, query, engine, path) with the
# documented fields and sane numbers, the packet rows' hits equal the
# oracle's bit for bit, and the Whitted rows are there. Where this build has
# Embree (RT_HAVE_EMBREE from CMake) its rtcIntersect1/16 and rtcOccluded1/16
# rows are there; where it has not, they are absent and both the JSON
# ("embree_absent") and the table say why.
source "$RT_SOURCE_DIR/tests/shell_check.sh"
command -v python3 >/dev/null || { echo "skipped: python3 is needed to parse JSON"; exit 77; }
scene=$RT_SOURCE_DIR/scenes/cornell.json
# A build without jansson (CI's minimal build, which also lacks Embree) reads
# the room of the box as a bare OBJ.
"$RTCL" info "$scene" >/dev/null 2>&1 || scene=$RT_SOURCE_DIR/scenes/cornell_room.obj
args=(--incoherent --rays 3000 --reps 2 --threads 2 --width 48 --height 27)

checks=$((checks + 1))
if ! "$RTCL" bench "$scene" "${args[@]}" --json >"$tmp/out.json" 2>"$tmp/err"; then
    echo "FAIL: rtcl bench --incoherent --json failed:"; cat "$tmp/err"; fails=$((fails + 1))
elif [ -s "$tmp/err" ]; then
    echo "FAIL: unexpected stderr (not a terminal):"; cat "$tmp/err"; fails=$((fails + 1))
elif ! python3 - "$tmp/out.json" "${RT_HAVE_EMBREE:-OFF}" <<'PY'; then
import json, sys
lines = [l for l in open(sys.argv[1]) if l.strip()]
assert len(lines) == 1, "one JSON object per scene, got %d lines" % len(lines)
obj = json.loads(lines[0])
embree = sys.argv[2] in ("ON", "1", "TRUE", "YES")
assert "cornell" in obj["scene"] and obj["triangles"] > 0, obj
assert obj["rays_per_set"] == 3000 and obj["reps"] == 2 and obj["threads"] == 2, obj
rows = obj["incoherent"]
keys = {"scene", "rays", "query", "engine", "path", "mrays_min", "mrays_median"}
paths = {("rtcl", "cpu"), ("rtcl", "packet-auto")}
if embree:
    paths |= {("embree", "rtcIntersect1"), ("embree", "rtcIntersect16"),
              ("embree", "rtcOccluded1"), ("embree", "rtcOccluded16")}
seen = set()
for r in rows:
    missing = keys - set(r)
    assert not missing, "row lacks %s: %s" % (missing, r)
    assert r["scene"] == obj["scene"], r
    assert r["rays"] in ("diffuse", "random") and r["query"] in ("closest", "any"), r
    assert (r["engine"], r["path"]) in paths, "unexpected engine/path: %s" % r
    if r["engine"] == "embree":
        assert ("Intersect" in r["path"]) == (r["query"] == "closest"), r
    assert 0 < r["mrays_median"] <= r["mrays_min"] < 1e5, r
    assert abs(r["mrays_min"] - 3000 / (r["ms_min"] * 1000)) < 1e-3 * r["mrays_min"] + 1e-3, r
    if r["path"] == "packet-auto":
        assert r["differ_from_oracle"] == 0, "packet hits unlike the oracle's: %s" % r
    if embree and r["engine"] == "rtcl":
        assert r["vs_embree1_min"] > 0 and r["vs_embree16_median"] > 0, r
    seen.add((r["rays"], r["query"], r["engine"], r["path"]))
want = 2 * 2 * (4 if embree else 2)
assert len(rows) == want and len(seen) == want, "expected %d distinct rows, got %d" % (want, len(seen))
if embree:
    assert "embree_absent" not in obj, obj.get("embree_absent")
else:
    assert obj.get("embree_absent"), "no Embree rows and no reason given"
    print("embree: not in this build:", obj["embree_absent"])
w = {x["backend"]: x for x in obj["whitted"]}
assert set(w) == {"packet", "cpu"}, obj["whitted"]
assert w["packet"]["secondary"] == "single-ray" and w["cpu"]["secondary"] == "oracle", w
assert w["packet"]["rays"] == w["cpu"]["rays"] >= 48 * 27, w
assert all(0 < x["ms_min"] <= x["ms_median"] for x in w.values()), w
assert "no longer selectable" in obj["whitted_packet_oracle_secondary"], obj
print("rows:", len(rows))
PY
    fails=$((fails + 1))
fi

# The table: the same rows, and the reason when Embree's are absent.
if [ "${RT_HAVE_EMBREE:-OFF}" = ON ]; then
    expect 0 'embree +rtcOccluded16' -- "$RTCL" bench "$scene" "${args[@]}" --no-render
else
    expect 0 'no Embree rows: .*(Embree|embree)' -- "$RTCL" bench "$scene" "${args[@]}" --no-render
fi
expect 0 'packet-auto' -- "$RTCL" bench "$scene" "${args[@]}" --no-render
# --no-render leaves the Whitted frames out.
checks=$((checks + 1))
"$RTCL" bench "$scene" "${args[@]}" --no-render --json | grep -q '"whitted"' &&
    { echo "FAIL: --no-render still timed Whitted frames"; fails=$((fails + 1)); }
expect 2 "--rays: '0' is out of range \\(1..100000000\\)" -- "$RTCL" bench "$scene" --incoherent --rays 0
expect 2 'applies to --incoherent only' -- "$RTCL" bench "$scene" --rays 10
expect 2 'one at a time' -- "$RTCL" bench "$scene" --incoherent --animate
expect 2 'accel does not apply to --incoherent' -- "$RTCL" bench "$scene" --incoherent --accel kd
finish
