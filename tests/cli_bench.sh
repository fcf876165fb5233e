#!/usr/bin/env bash
# cli_bench.sh - 'rtcl bench --json' on a small generated OBJ: one JSON object
# per scene with the documented keys, every builder named, sane numbers.
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

out=$("$RTCL" bench "$dir/grid.obj" --json --reps 2 --threads 2 2>"$dir/err") || {
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
for want in ["thesis-scalar", "thesis-neon", "thesis-mt", "fast"]:
    assert want in names, "builder %s missing from %s" % (want, names)
for b in obj["build"]:
    for key in ["builder", "threads", "ms_min", "ms_median", "sah", "nodes"]:
        assert key in b, "%s lacks %s" % (b["builder"], key)
    if "error" in b:
        continue
    assert 0 < b["ms_min"] <= b["ms_median"], b
    assert b["sah"] > 1.0 and 1 <= b["nodes"] <= 2 * 3200 - 1, b
fast = [b for b in obj["build"] if b["builder"] == "fast"][0]
assert "error" not in fast and fast["threads"] == 2, fast
print("builders:", ", ".join(names))
PY

# --help works; a bad option is a usage error (exit 2).
"$RTCL" bench --help | grep -q -- "--reps" || { echo "--help lacks --reps"; exit 1; }
"$RTCL" bench --bogus "$dir/grid.obj" 2>/dev/null
[ $? -eq 2 ] || { echo "a bad option must exit 2"; exit 1; }
echo "cli_bench: ok"
