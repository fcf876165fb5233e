# cli_install.sh - `cmake --install` gives a library others can use (issue 19,
# item 9): rt.h, librtcl.a and librtcl.so, rtcl, the image module, a CMake
# package and a pkg-config file. examples/orbit.c is built against the
# installed package with CMake (find_package(rtcl), rtcl::rtcl) and with
# pkg-config, shared and static, and run; neither it nor the library links
# Embree or TBB; the installed rtcl writes a PNG through the installed module.
source "$RT_SOURCE_DIR/tests/shell_check.sh"
build=${RT_BINARY_DIR:?}
unset LD_LIBRARY_PATH # the installed programs find the installed module, not the build's
prefix="$tmp/prefix"
# A sanitizer build's library needs the sanitizer runtime loaded first in
# the user's program; the example is an ordinary program.
if ldd "$build/librtcl.so" | grep -q -E 'libasan|libubsan|libtsan'; then
    echo "skipped: a sanitizer build's library is not for ordinary programs"; exit 77
fi

# ok NAME CMD...: CMD succeeds, else its output is shown.
ok() {
    local name=$1
    shift
    checks=$((checks + 1))
    if ! "$@" >"$tmp/log.txt" 2>&1; then
        echo "FAIL: $name: '$*':"; tail -20 "$tmp/log.txt"; fails=$((fails + 1)); return 1
    fi
}

ok "install" cmake --install "$build" --prefix "$prefix" || { finish; exit 1; }
libdir=$(cd "$prefix" && ls -d lib lib64 lib/*-linux-gnu 2>/dev/null | while read -r d; do
    [ -e "$prefix/$d/librtcl.so" ] && echo "$prefix/$d" && break; done)
for f in bin/rtcl include/rtcl/rt.h; do
    checks=$((checks + 1))
    [ -e "$prefix/$f" ] || { echo "FAIL: $f not installed"; fails=$((fails + 1)); }
done
for f in librtcl.a librtcl.so cmake/rtcl/rtclConfig.cmake cmake/rtcl/rtclTargets.cmake pkgconfig/rtcl.pc; do
    checks=$((checks + 1))
    [ -e "$libdir/$f" ] || { echo "FAIL: lib/$f not installed"; fails=$((fails + 1)); }
done
has_module=0
[ -e "$build/librtcl_image.so" ] && has_module=1
if [ $has_module = 1 ]; then
    checks=$((checks + 1))
    [ -e "$libdir/librtcl_image.so" ] || { echo "FAIL: the image module is not installed"; fails=$((fails + 1)); }
fi

# The example through the CMake package (shared library).
ok "example: cmake configure" cmake -S "$RT_SOURCE_DIR/examples" -B "$tmp/ex-cmake" \
    -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release &&
    ok "example: cmake build" cmake --build "$tmp/ex-cmake" &&
    ok "example (cmake) runs" "$tmp/ex-cmake/orbit" "$tmp"
# ... and through pkg-config, shared (with the library's folder as RUNPATH) and static.
export PKG_CONFIG_PATH="$libdir/pkgconfig"
if command -v pkg-config >/dev/null; then
    ok "example: pkg-config shared" sh -c "cc '$RT_SOURCE_DIR/examples/orbit.c' -o '$tmp/orbit-pc' \
        \$(pkg-config --cflags --libs rtcl) -lm -Wl,-rpath,'$libdir'" &&
        ok "example (pkg-config) runs" "$tmp/orbit-pc" "$tmp"
    ok "example: pkg-config static" sh -c "cc '$RT_SOURCE_DIR/examples/orbit.c' -o '$tmp/orbit-static' \
        \$(pkg-config --cflags rtcl) '$libdir/librtcl.a' \$(pkg-config --static --libs rtcl | sed 's/-lrtcl\\b//') -lm" &&
        ok "example (static) runs" "$tmp/orbit-static" "$tmp"
else
    echo "note: no pkg-config, the pkg-config builds are not checked"
fi

# No Embree, no TBB: not in what the programs or the library need, directly or not.
for bin in "$tmp/ex-cmake/orbit" "$tmp/orbit-pc" "$tmp/orbit-static" "$libdir/librtcl.so"; do
    [ -e "$bin" ] || continue
    checks=$((checks + 1))
    if ldd "$bin" | grep -i -E 'embree|tbb'; then
        echo "FAIL: $bin links Embree or TBB"; fails=$((fails + 1))
    fi
    checks=$((checks + 1))
    if ldd "$bin" | grep -q -i 'OpenImageIO'; then
        echo "FAIL: $bin links OpenImageIO (it belongs in the image module)"; fails=$((fails + 1))
    fi
done
checks=$((checks + 1))
readelf -d "$tmp/ex-cmake/orbit" 2>/dev/null | grep -q 'librtcl.so' ||
    { echo "FAIL: the CMake example does not link the shared librtcl"; fails=$((fails + 1)); }

# The installed rtcl finds the installed module (bin/../lib) for a PNG.
if [ $has_module = 1 ]; then
    expect 0 'wrote' -- "$prefix/bin/rtcl" render builtin:cornell --width 32 --height 24 -o "$tmp/x.png"
fi
expect 0 'wrote' -- "$prefix/bin/rtcl" render builtin:cornell --width 32 --height 24 -o "$tmp/x.ppm"
# Without the module a PNG is refused with the reason (unless the configured
# prefix holds an install of its own, which the library would find).
configured=$(sed -n 's/^CMAKE_INSTALL_PREFIX:PATH=//p' "$build/CMakeCache.txt")
rm -f "$libdir/librtcl_image.so"
ls "$configured"/lib*/librtcl_image.so "$configured"/lib/*/librtcl_image.so >/dev/null 2>&1 ||
    expect 2 'cannot write PNG: .*(image module librtcl_image.so .*not found|no PNG or EXR support)' -- \
    "$prefix/bin/rtcl" render builtin:cornell --width 32 --height 24 -o "$tmp/y.png"
finish
