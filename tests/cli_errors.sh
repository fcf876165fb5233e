# SPDX-License-Identifier: Apache-2.0
# cli_errors.sh - rtcl answers bad input with a clear message and status 2.
. "$(dirname "$0")/shell_check.sh"
: "${RTCL:?RTCL must name the rtcl binary}"

expect 2 "usage: rtcl COMMAND" -- "$RTCL"
expect 0 "commands:" -- "$RTCL" --help
expect 2 "unknown command 'frobnicate'" -- "$RTCL" frobnicate
for c in render trace info compare bench generate; do
    expect 0 "usage: rtcl $c" -- "$RTCL" "$c" --help
done

expect 2 "no scene given" -- "$RTCL" render
expect 2 "unknown option '--frob'" -- "$RTCL" render builtin:cornell --frob
expect 2 "--width: 'abc' is not an integer" -- "$RTCL" render builtin:cornell --width abc
expect 2 "option --height needs a value" -- "$RTCL" render builtin:cornell --height
expect 2 "--aov: 'colour' is not one of depth, primid, instid, normal, boxtests or tritests" -- "$RTCL" render --aov colour builtin:cornell
expect 2 "no built-in scene named 'nope'" -- "$RTCL" info builtin:nope
expect 2 "missing.obj.*(No such file|cannot open)" -- "$RTCL" info "$tmp/missing.obj"
expect 2 "missing.json.*(No such file|cannot open)" -- "$RTCL" render "$tmp/missing.json"
expect 2 "unknown scene type" -- "$RTCL" info "$tmp/scene.txt"

# A malformed OBJ names the file and the line.
printf 'v 0 0 0\nv 1 0 0\nv 0 1.2.3 0\nf 1 2 3\n' >"$tmp/badnum.obj"
expect 2 "badnum.obj:3(:[0-9]+)?: .*number" -- "$RTCL" info "$tmp/badnum.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n' >"$tmp/badidx.obj"
expect 2 "badidx.obj:4(:[0-9]+)?: .*index" -- "$RTCL" info "$tmp/badidx.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n' >"$tmp/short.obj"
expect 2 "short.obj:4(:[0-9]+)?: .*at least 3" -- "$RTCL" info "$tmp/short.obj"
printf 'v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n' >"$tmp/nan.obj"
expect 2 "nan.obj:2(:[0-9]+)?: .*(NaN|infinite)" -- "$RTCL" info "$tmp/nan.obj"
printf '# nothing here\n' >"$tmp/empty.obj"
expect 2 "empty.obj.*(no faces|empty)" -- "$RTCL" info "$tmp/empty.obj"

# A malformed JSON scene names the file, line and column.
printf '{\n  "camera": {"fov": 60,\n' >"$tmp/truncated.json"
expect 2 "truncated.json:[0-9]+:[0-9]+: " -- "$RTCL" info "$tmp/truncated.json"
printf '{\n  "objects": [],\n  "colour": 1\n}\n' >"$tmp/unknown.json"
expect 2 "unknown.json:3:[0-9]+: .*colour" -- "$RTCL" info "$tmp/unknown.json"

# A good bare OBJ loads and gets the default view.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$tmp/tri.obj"
expect 0 "triangles +1 " -- "$RTCL" info "$tmp/tri.obj"
# info says whether the OpenCL kernels would be the exact build (--cl-options:
# the study's variants are not).
expect 0 "opencl build exact \(no extra options\)" -- "$RTCL" info "$tmp/tri.obj"
expect 0 "opencl build NOT exact: extra options '-cl-mad-enable'" -- "$RTCL" info "$tmp/tri.obj" \
    --cl-options -cl-mad-enable
expect 2 "option --cl-options needs a value" -- "$RTCL" info "$tmp/tri.obj" --cl-options
# A camera whose up is exactly opposite the view direction (the float check
# of old passed it; the layout's frame was NaN): refused with file:line:column.
printf '{"camera": {"position": [0, 0, 0], "look_at": [-0.5, -1.5, -2.79999995],
 "up": [1, 3, 5.5999999], "fov": 60, "width": 32, "height": 32},
 "lights": [{"position": [0, 2, 0], "color": [1, 1, 1]}],
 "meshes": {"t": {"file": "tri.obj"}}, "objects": [{"mesh": "t"}]}\n' > "$tmp/upbad.json"
printf 'v -1 -1 -3\nv 1 -1 -3\nv 0 1 -3\nf 1 2 3\n' > "$tmp/tri.obj"
for b in cpu packet; do
    expect 2 'upbad.json:1:[0-9]+: .*up is zero or \(nearly\) parallel to the view direction' -- \
        "$RTCL" render "$tmp/upbad.json" -o "$tmp/upbad.png" --backend $b
done
# Messages that named the wrong fault (issue 31): a camera 1e38 away is a
# camera (it renders), equal points are named with their value; an object
# scaled by 1e30 in a file with no camera gets the default view; "0x5" is a
# malformed index, not index 0.
mesh_t='"meshes": {"t": {"positions": [0,0,0, 1,0,0, 0,1,0], "triangles": [0,1,2]}}'
printf '{"camera": {"position": [1e38, 0, 0], "look_at": [0, 0, 0], "width": 16, "height": 16},
 %s, "objects": [{"mesh": "t"}]}\n' "$mesh_t" > "$tmp/far.json"
expect 0 'wrote' -- "$RTCL" render "$tmp/far.json" -o "$tmp/far.ppm"
printf '{"camera": {"position": [2, 2, 2], "look_at": [2, 2, 2]},
 %s, "objects": [{"mesh": "t"}]}\n' "$mesh_t" > "$tmp/same.json"
expect 2 'same.json:1:12: camera: the look-at point equals the position \(2, 2, 2\)' -- \
    "$RTCL" render "$tmp/same.json" -o "$tmp/same.ppm"
printf '{%s, "objects": [{"mesh": "t", "transform": {"matrix": [1e30,0,0,0, 0,1e30,0,0,
 0,0,1e30,0, 0,0,0,1]}}]}\n' "$mesh_t" > "$tmp/huge.json"
expect 0 'wrote' -- "$RTCL" render "$tmp/huge.json" -o "$tmp/huge.ppm" --width 16 --height 16
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0x5\n' > "$tmp/hex.obj"
expect 2 'hex.obj:4:7: malformed vertex reference "0x5"' -- "$RTCL" info "$tmp/hex.obj"
finish
