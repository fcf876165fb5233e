# SPDX-License-Identifier: Apache-2.0
# cli_startup.sh - commands that read or write no image never load
# OpenImageIO (issue 19, item 8: rtcl mapped ~260 libraries, 0.25 s before
# doing anything). The image module (librtcl_image.so) is loaded on the first
# PNG or EXR only. Checked with the dynamic loader's own account
# (LD_DEBUG=libs names every library it loads), so the test says what was
# loaded, not how long it took; the times are in docs/BENCHMARKS.md.
source "$RT_SOURCE_DIR/tests/shell_check.sh"

# Nothing of OpenImageIO in what rtcl links.
checks=$((checks + 1))
if ldd "$RTCL" | grep -i -E 'OpenImageIO|rtcl_image'; then
    echo "FAIL: rtcl links OpenImageIO"; fails=$((fails + 1))
fi
# ... nor SDL2 (about 50 libraries: X11, Wayland, PulseAudio): the viewer
# opens it when it starts (host/cli/view/view_sdl_load.c).
checks=$((checks + 1))
if ldd "$RTCL" | grep -E 'libSDL2'; then
    echo "FAIL: rtcl links SDL2"; fails=$((fails + 1))
fi

# loads CMD...: the libraries the dynamic loader loaded while CMD ran.
loads() {
    LD_DEBUG=libs LD_DEBUG_OUTPUT="$tmp/ld" "$@" >/dev/null 2>&1
    cat "$tmp"/ld.* 2>/dev/null | grep -o -E 'calling init: [^ ]+' | sed 's/calling init: //'
    rm -f "$tmp"/ld.*
}

printf '0 0.5 3 0 0 -1 0 inf\n' >"$tmp/rays.txt"
cornell="$RT_SOURCE_DIR/scenes/cornell.json"
for cmd in "--help" "info $cornell" "info builtin:keyframes" "render --help" \
    "trace $cornell --rays $tmp/rays.txt --out $tmp/hits.txt" "devices" \
    "render builtin:cornell --width 32 --height 24 -o $tmp/a.ppm" \
    "render builtin:cornell --width 32 --height 24 -o $tmp/a.pfm"; do
    # shellcheck disable=SC2086
    loaded=$(loads "$RTCL" $cmd)
    checks=$((checks + 1))
    if [ -z "$loaded" ]; then
        echo "FAIL: rtcl $cmd: LD_DEBUG reported no library at all (is it honoured here?)"
        fails=$((fails + 1))
    elif grep -q -i -E 'OpenImageIO|rtcl_image' <<<"$loaded"; then
        echo "FAIL: rtcl $cmd loads the image layer:"; grep -i -E 'OpenImageIO|rtcl_image' <<<"$loaded"
        fails=$((fails + 1))
    elif grep -q -E 'libSDL2' <<<"$loaded"; then
        echo "FAIL: rtcl $cmd loads SDL2"; fails=$((fails + 1))
    fi
done

# The control: a PNG does load the module, and so OpenImageIO (where built).
if [ -e "${RT_BINARY_DIR:-}/librtcl_image.so" ]; then
    loaded=$(loads "$RTCL" render builtin:cornell --width 32 --height 24 -o "$tmp/a.png")
    checks=$((checks + 1))
    grep -q 'rtcl_image' <<<"$loaded" && grep -q 'OpenImageIO' <<<"$loaded" ||
        { echo "FAIL: a PNG render did not load the image module and OpenImageIO"; fails=$((fails + 1)); }
    expect 0 'wrote' -- "$RTCL" render builtin:cornell --width 32 --height 24 -o "$tmp/a.png"
fi
finish
