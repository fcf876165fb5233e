# SPDX-License-Identifier: Apache-2.0
# cli_options.sh - rtcl's options follow the GNU conventions (issue 30, item
# 8) and its numbers parse strictly (issue 25, item 5): --opt=value as well
# as --opt value, a mistyped option answered in one line that names the
# help, 'rtcl help COMMAND', --json on info and devices, builtin: scenes in
# every command that takes a scene, generate making a missing folder,
# animate refusing a static scene, and number values refused with their
# fault named (never "not a finite number" for a finite one).
. "$(dirname "$0")/shell_check.sh"
: "${RTCL:?RTCL must name the rtcl binary}"
PY=/usr/bin/python3
[ -x "$PY" ] || PY=python3

# --opt=value and --opt value give the same image.
expect 0 "wrote" -- "$RTCL" render builtin:cornell --width=24 --height 16 -o "$tmp/eq.ppm"
expect 0 "wrote" -- "$RTCL" render builtin:cornell --width 24 --height=16 -o"$tmp/sp.ppm"
expect 0 "pass" -- "$RTCL" compare "$tmp/eq.ppm" "$tmp/sp.ppm"
expect 0 "wrote" -- "$RTCL" render --output="$tmp/long.ppm" --width=24 --height=16 builtin:cornell
expect 0 "pass" -- "$RTCL" compare --max-diff=0 "$tmp/eq.ppm" "$tmp/long.ppm"
expect 2 "option --stats takes no value \(found 'yes'\)" -- "$RTCL" render builtin:cornell --stats=yes
expect 2 "option --width needs a value" -- "$RTCL" render builtin:cornell --width
# "--" ends the options: what follows is an operand even if it looks like one.
expect 2 "cannot open|No such file" -- "$RTCL" info -- --not-an-option.obj

# A mistyped option: one line, the nearest name, and where the help is.
for typo in render:--widht:--width trace:--any-hti:--any-hit info:--jsno:--json \
    animate:--fsp:--fps view:--heigth:--height bench:--rpes:--reps; do
    IFS=: read -r c bad good <<<"$typo"
    out=$("$RTCL" $c builtin:cornell "$bad" 5 2>&1) && rc=0 || rc=$?
    checks=$((checks + 1))
    lines=$(printf '%s\n' "$out" | wc -l)
    if [ "$rc" != 2 ] || [ "$lines" != 1 ] ||
        ! grep -q -- "^rtcl $c: unknown option '$bad' (did you mean '$good'?); see 'rtcl $c --help'\$" <<<"$out"; then
        echo "FAIL: rtcl $c $bad: status $rc, $lines lines:"; printf '%s\n' "$out" | head -5
        fails=$((fails + 1))
    fi
done
expect 2 "^rtcl devices: unknown option '--frobnicate'; see 'rtcl devices --help'$" -- "$RTCL" devices --frobnicate
expect 2 "^rtcl render: no scene given; see 'rtcl render --help'$" -- "$RTCL" render

# rtcl help COMMAND is COMMAND --help; help --synopsis lists every command.
for c in render trace info compare devices bench generate animate view; do
    "$RTCL" help $c >"$tmp/help.txt" 2>&1 || { echo "FAIL: rtcl help $c"; fails=$((fails + 1)); }
    "$RTCL" $c --help >"$tmp/dash.txt" 2>&1
    checks=$((checks + 1))
    if ! cmp -s "$tmp/help.txt" "$tmp/dash.txt" || ! grep -q "^usage: rtcl $c" "$tmp/help.txt"; then
        echo "FAIL: 'rtcl help $c' differs from 'rtcl $c --help'"; fails=$((fails + 1))
    fi
done
expect 2 "rtcl help: unknown command 'frob'" -- "$RTCL" help frob
expect 0 "^rtcl view SCENE" -- "$RTCL" help --synopsis

# --json on info and devices: one JSON object each.
"$RTCL" info builtin:keyframes --json >"$tmp/info.json" 2>"$tmp/info.err"
no_leak_check "$RTCL" devices --json >"$tmp/devices.json" 2>"$tmp/devices.err" || true
checks=$((checks + 1))
if ! "$PY" - "$tmp/info.json" "$tmp/devices.json" <<'PY'; then
import json, sys
info = json.load(open(sys.argv[1]))
assert info["scene"] == "builtin:keyframes", info["scene"]
assert info["triangles"] > 0 and info["all_triangles"] >= info["triangles"], info
assert len(info["meshes"]) >= 1 and all(m["accel"] == "bvh" for m in info["meshes"]), info["meshes"]
assert info["features"]["keyframes"] is True, info["features"]
assert info["opencl"]["exact_build"] is True and info["device_math"] == "auto", info
devices = json.load(open(sys.argv[2]))
assert [b["backend"] for b in devices["backends"]] == ["opencl", "vulkan"], devices
for b in devices["backends"]:
    assert ("devices" in b) != ("error" in b), b
    for d in b.get("devices", []):
        assert isinstance(d["exact"], bool) and d["exact_note"], d
PY
    echo "FAIL: info/devices --json"; cat "$tmp/info.err" "$tmp/devices.err"; fails=$((fails + 1))
fi
expect 0 '"accel": "kd"' -- "$RTCL" info builtin:cornell --json --accel kd

# builtin: scenes in every command that takes one.
expect 0 "thesis-scalar" -- "$RTCL" bench builtin:cornell --no-render --reps 1 --threads 1
printf '0 0 5 0 0 -1 0 100\n' >"$tmp/one.txt"
expect 0 "" -- "$RTCL" trace builtin:cornell --rays "$tmp/one.txt" --out "$tmp/one_hits.txt"

# generate makes a missing folder (and the folders above it).
expect 0 "wrote .*/new/deeper/cornell.json" -- "$RTCL" generate "$tmp/new/deeper"
expect 0 "triangles" -- "$RTCL" info "$tmp/new/deeper/cornell.json"
: >"$tmp/afile"
expect 2 "afile: not a folder" -- "$RTCL" generate "$tmp/afile/sub"

# animate on a static scene says so.
expect 2 "has no animation .*every frame would be the same image" -- \
    "$RTCL" animate builtin:cornell --fps 10 --frames 2 -o "$tmp/f_%02d.ppm"

# Numbers: strict, the fault named, ranges stated.
expect 2 "--width: ' 64' has blank space around it \(give an integer 1..32768\)" -- \
    "$RTCL" render builtin:cornell --width ' 64'
expect 2 "--width: '64 ' has blank space around it \(give an integer 1..32768\)" -- \
    "$RTCL" render builtin:cornell --width '64 '
expect 2 "--width: '0x40' is not an integer" -- "$RTCL" render builtin:cornell --width 0x40
expect 2 "--width: '6.5' is not an integer" -- "$RTCL" render builtin:cornell --width 6.5
expect 2 "--width: '0' is out of range \(1..32768\)" -- "$RTCL" render builtin:cornell --width 0
expect 2 "--width: '' is empty" -- "$RTCL" render builtin:cornell --width=
expect 2 "--width: '99999999999999999999' is too large" -- \
    "$RTCL" render builtin:cornell --width 99999999999999999999
expect 0 "wrote" -- "$RTCL" render builtin:cornell --width 16 --height 8 --time 5e-324 -o "$tmp/t.ppm"
expect 0 "wrote" -- "$RTCL" render builtin:cornell --width 16 --height 8 --time=-1e-310 -o "$tmp/t.ppm"
expect 2 "--time: '1e999' is too large" -- "$RTCL" render builtin:cornell --time 1e999
expect 2 "--time: 'nan' is not a finite number" -- "$RTCL" render builtin:cornell --time nan
expect 2 "--time: '1,5' is not a number" -- "$RTCL" render builtin:cornell --time 1,5
expect 2 "--fps: '0' is out of range \(> 0\)" -- \
    "$RTCL" animate builtin:cornell --fps 0 --frames 2 -o "$tmp/f_%02d.ppm"
expect 2 "--max-diff: '-1' is out of range \(>= 0\)" -- "$RTCL" compare a b --max-diff -1

# Choices are listed from the same table as the help.
expect 2 "--update: 'lazy' is not one of sah, refit, lbvh or auto" -- \
    "$RTCL" render builtin:cornell --update lazy
expect 0 "wrote" -- "$RTCL" render builtin:cornell --update rebuild --width 8 --height 8 -o "$tmp/u.ppm"
expect 2 "--accel: 'octree' is not one of bvh, kd or kd-binned" -- \
    "$RTCL" info builtin:cornell --accel octree

# --device: which backends take one comes from the backend registry.
expect 2 "--device applies to --backend opencl, vulkan or auto, not 'packet'" -- \
    "$RTCL" render builtin:cornell --backend packet --device 0
expect 2 "both name a device" -- "$RTCL" render builtin:cornell --backend opencl:0 --device 0
finish
