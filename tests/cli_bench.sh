#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# cli_bench.sh - 'rtcl bench --json' on a small generated OBJ: one JSON object
# per scene with the documented keys, every builder and renderer named, sane
# numbers; the packet and OpenCL images equal the oracle's bit for bit and
# Embree's (which traces the same rays with its own triangle test) is within
# rounding of it but for a few grazing shadow rays.
set -u
command -v python3 >/dev/null || { echo "skipped: python3 is needed to parse JSON"; exit 77; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

# A 40 x 40 grid of quads (3,200 triangles) with a bumpy height.
python3 - "$dir/grid.obj" <<'PY'
import math, sys
n = 40
with open(sys.argv[1], "w") as f:
    for y in range(n + 1):
        for x in range(n + 1):
            f.write("v %d %.4f %d\n" % (x, math.sin(x * 0.3) * math.cos(y * 0.2), y))
    for y in range(n):
        for x in range(n):
            a = y * (n + 1) + x + 1
            f.write("f %d %d %d\nf %d %d %d\n" % (a, a + 1, a + n + 2, a, a + n + 2, a + n + 1))
PY

out=$("$RTCL" bench "$dir/grid.obj" --json --reps 2 --threads 2 --width 96 --height 54 2>"$dir/err") || {
    echo "rtcl bench failed:"; cat "$dir/err"; exit 1; }
[ -s "$dir/err" ] && { echo "unexpected stderr (not a terminal):"; cat "$dir/err"; exit 1; }

python3 - "$out" <<'PY' || exit 1
import json, sys
lines = sys.argv[1].strip().split("\n")
assert len(lines) == 1, "expected one line per scene, got %d" % len(lines)
obj = json.loads(lines[0])
assert obj["scene"].endswith("grid.obj"), obj["scene"]
assert obj["triangles"] == 3200, obj["triangles"]
names = [b["builder"] for b in obj["build"]]
for want in ["thesis-scalar", "thesis-neon", "thesis-mt", "sah"]:
    assert want in names, "builder %s missing from %s" % (want, names)
for b in obj["build"]:
    for key in ["builder", "threads", "ms_min", "ms_median", "sah", "nodes"]:
        assert key in b, "%s lacks %s" % (b["builder"], key)
    if "error" in b:
        continue
    assert 0 < b["ms_min"] <= b["ms_median"], b
    assert b["sah"] > 1.0 and 1 <= b["nodes"] <= 2 * 3200 - 1, b
fast = [b for b in obj["build"] if b["builder"] == "sah"][0]
assert "error" not in fast and fast["threads"] == 2, fast
print("builders:", ", ".join(names))

assert (obj["render_width"], obj["render_height"]) == (96, 54), obj
rows = {r["backend"]: r for r in obj["render"]}
for want in ["cpu", "packet", "opencl", "vulkan"]:
    assert want in rows, "renderer %s missing from %s" % (want, list(rows))
for name in ["cpu", "packet"]:
    assert "error" not in rows[name], rows[name]
for name in ["opencl", "vulkan"]:
    if "error" in rows[name]:
        print(name, "row: unavailable here:", rows[name]["error"])
oracle = rows["cpu"]
assert oracle["rays"] >= 96 * 54, oracle  # primary rays at least
assert oracle["box_tests"] > 0 and oracle["tri_tests"] > 0, oracle
for name, r in rows.items():
    if "error" in r:
        continue
    assert 0 < r["ms_min"] <= r["ms_median"] and r["mrays"] > 0, r
    if name in ("packet", "opencl", "vulkan"):
        assert r["rays"] == oracle["rays"], (name, r["rays"], oracle["rays"])
        assert r["pixels_differ_from_cpu"] == 0, (name, r)
has_embree = any(b["builder"] == "embree" and "error" not in b for b in obj["build"])
if has_embree:
    peer = rows.get("embree")
    assert peer and "error" not in peer, "the build has Embree but no render row: %s" % peer
    assert peer["lanes"] in (1, 4, 8, 16), peer
    best = min((r for n, r in rows.items() if n.startswith("embree-")), key=lambda r: r["ms_median"])
    assert best["ms_median"] == peer["ms_median"], (best, peer)
    # The same rays: equal counts; colours equal up to rounding of t except
    # where a grazing shadow ray decides differently (Embree's triangle test
    # is not ours): a few pixels of this bumpy, flat-shaded grid.
    assert peer["rays"] == oracle["rays"], (peer["rays"], oracle["rays"])
    assert peer["pixels_visibly_differ_from_cpu"] <= 0.03 * 96 * 54, peer
    print("embree render rows:", sorted(n for n in rows if n.startswith("embree")))
else:
    print("embree: not in this build (no render row expected)")
PY

# --help works; a bad option is a usage error (exit 2).
"$RTCL" bench --help | grep -q -- "--reps" || { echo "--help lacks --reps"; exit 1; }
"$RTCL" bench --bogus "$dir/grid.obj" 2>/dev/null
[ $? -eq 2 ] || { echo "a bad option must exit 2"; exit 1; }
echo "cli_bench: ok"
