# SPDX-License-Identifier: Apache-2.0
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
for f in bin/rtcl include/rtcl/rt.h include/rtcl/rtcl_version.h; do
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

# Symbol tables (issue 30, item 3): the static archive defines no global
# symbol without the rt_ prefix (the library's inside included), and the
# shared library exports only rt_ functions (cli_shared_symbols.sh holds
# them to rt.h).
checks=$((checks + 1))
bad=$(nm -g --defined-only "$libdir/librtcl.a" 2>/dev/null | awk 'NF == 3 && $3 !~ /^rt_/ {print $3}' | sort -u)
[ -z "$bad" ] || { echo "FAIL: librtcl.a defines unprefixed global symbols:" $bad; fails=$((fails + 1)); }
checks=$((checks + 1))
bad=$(nm -D --defined-only "$libdir/librtcl.so" | awk 'NF == 3 && $2 != "A" && $3 !~ /^rt_/ {print $3}' | sort -u)
[ -z "$bad" ] || { echo "FAIL: librtcl.so exports unprefixed symbols:" $bad; fails=$((fails + 1)); }
checks=$((checks + 1))
grep -q '^#ifndef RTCL_RT_H' "$prefix/include/rtcl/rt.h" ||
    { echo "FAIL: rt.h's include guard is not RTCL_RT_H"; fails=$((fails + 1)); }

# Version (item 2): one version, from CMake's project(); the SONAME follows
# the policy of CMakeLists.txt and agrees with the package's version file:
# 0.MINOR.PATCH: SONAME librtcl.so.0.MINOR, only 0.MINOR.* compatible;
# MAJOR >= 1: SONAME librtcl.so.MAJOR, every MAJOR.* compatible.
version=$(sed -n 's/^set(PACKAGE_VERSION "\(.*\)")$/\1/p' "$libdir/cmake/rtcl/rtclConfigVersion.cmake")
soname=$(readelf -d "$libdir/librtcl.so" | sed -n 's/.*Library soname: \[\(.*\)\]/\1/p')
IFS=. read -r major minor patch <<<"$version"
checks=$((checks + 1))
if [ -z "$version" ] || [ -z "$patch" ]; then
    echo "FAIL: rtclConfigVersion.cmake gives no MAJOR.MINOR.PATCH version ('$version')"; fails=$((fails + 1))
else
    if [ "$major" = 0 ]; then
        # an older minor is another ABI (a SameMajorVersion file would take it)
        want_soname="librtcl.so.0.$minor" pairs="0.$minor.0:TRUE 0.$((minor + 1)).0:FALSE"
        [ "$minor" = 0 ] || pairs="$pairs 0.$((minor - 1)).0:FALSE"
    else
        want_soname="librtcl.so.$major" pairs="$major.0.0:TRUE $((major + 1)).0.0:FALSE"
    fi
    [ "$soname" = "$want_soname" ] ||
        { echo "FAIL: SONAME '$soname' for version $version, the policy says $want_soname"; fails=$((fails + 1)); }
    checks=$((checks + 1))
    [ -e "$libdir/$soname" ] || { echo "FAIL: $soname is not installed"; fails=$((fails + 1)); }
    # compatible VERSION: what the installed version file answers for find_package(rtcl VERSION)
    compatible() {
        printf 'set(PACKAGE_FIND_VERSION %s)\nstring(REPLACE . ";" v %s)\nlist(GET v 0 PACKAGE_FIND_VERSION_MAJOR)\nlist(GET v 1 PACKAGE_FIND_VERSION_MINOR)\nset(CMAKE_SIZEOF_VOID_P 8)\ninclude(%s)\nmessage("${PACKAGE_VERSION_COMPATIBLE}")\n' \
            "$1" "$1" "$libdir/cmake/rtcl/rtclConfigVersion.cmake" >"$tmp/compat.cmake"
        cmake -P "$tmp/compat.cmake" 2>&1
    }
    for pair in $pairs; do
        checks=$((checks + 1))
        got=$(compatible "${pair%%:*}")
        [ "$got" = "${pair#*:}" ] || { echo "FAIL: the package $version says compatible=$got for" \
            "find_package(rtcl ${pair%%:*}), the SONAME policy says ${pair#*:}"; fails=$((fails + 1)); }
    done
    checks=$((checks + 1))
    cmake_version=$(sed -n 's/^CMAKE_PROJECT_VERSION:STATIC=//p' "$build/CMakeCache.txt")
    [ "$version" = "$cmake_version" ] ||
        { echo "FAIL: the package says $version, CMake's project() $cmake_version"; fails=$((fails + 1)); }
    expect 0 "^rtcl $version\$" -- "$prefix/bin/rtcl" --version
    expect 0 "^rtcl $version\$" -- "$prefix/bin/rtcl" version
    checks=$((checks + 1))
    grep -q "^Version: $version\$" "$libdir/pkgconfig/rtcl.pc" ||
        { echo "FAIL: rtcl.pc's Version is not $version"; fails=$((fails + 1)); }
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
    # <rtcl/rt.h> from pkg-config's flags, and its version is the library's; the
    # include folder is include/, not include/rtcl (so <rt.h> is not found).
    checks=$((checks + 1))
    pkg-config --cflags rtcl | grep -q -E -- "-I[^ ]*/include( |\$)" ||
        { echo "FAIL: pkg-config --cflags rtcl is '$(pkg-config --cflags rtcl)'"; fails=$((fails + 1)); }
    printf '#include <stdio.h>\n#include <string.h>\n#include <rtcl/rt.h>\nint main(void) {\n printf("%%d.%%d.%%d %%s\\n", RTCL_VERSION_MAJOR, RTCL_VERSION_MINOR, RTCL_VERSION_PATCH, rt_version());\n return strcmp(RTCL_VERSION_STRING, rt_version()) != 0;\n}\n' >"$tmp/ver.c"
    ok "<rtcl/rt.h> through pkg-config" sh -c "cc -std=c11 -Wall -Werror '$tmp/ver.c' -o '$tmp/ver' \
        \$(pkg-config --cflags --libs rtcl) -Wl,-rpath,'$libdir'" &&
        expect 0 "^$version $version\$" -- "$tmp/ver"
    printf '#include <rt.h>\n' >"$tmp/bare.c"
    checks=$((checks + 1))
    if sh -c "cc -c '$tmp/bare.c' -o '$tmp/bare.o' \$(pkg-config --cflags rtcl)" 2>/dev/null; then
        echo "FAIL: <rt.h> is on pkg-config's include path (include/rtcl)"; fails=$((fails + 1))
    fi
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
