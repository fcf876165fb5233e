# SPDX-License-Identifier: Apache-2.0
# cli_deb.sh - the Debian packages of the build (issue 30, item 4;
# cmake/package.cmake): cpack makes rtcl (runtime) and librtcl-dev, each
# holds its part and not the other's, the runtime has a manual page per
# command and the bash completion, and examples/ builds and runs against the
# packages' files (unpacked with dpkg-deb -x into a scratch root, so that the
# test installs nothing on the machine; CI's .ci/run installs them with dpkg -i).
source "$RT_SOURCE_DIR/tests/shell_check.sh"
build=${RT_BINARY_DIR:?}
unset LD_LIBRARY_PATH
for tool in cpack dpkg-deb; do
    command -v $tool >/dev/null || { echo "skipped: no $tool"; exit 77; }
done
if ldd "$build/librtcl.so" | grep -q -E 'libasan|libubsan|libtsan'; then
    echo "skipped: a sanitizer build's library is not for packages"; exit 77
fi
[ -e "$build/CPackConfig.cmake" ] || { echo "FAIL: no CPackConfig.cmake in $build"; exit 1; }

# ok NAME CMD...: CMD succeeds, else its output is shown.
ok() {
    local name=$1
    shift
    checks=$((checks + 1))
    if ! "$@" >"$tmp/log.txt" 2>&1; then
        echo "FAIL: $name: '$*':"; tail -20 "$tmp/log.txt"; fails=$((fails + 1)); return 1
    fi
}
ok "cpack" cpack -G DEB --config "$build/CPackConfig.cmake" -B "$tmp/pkg" || { finish; exit 1; }
version=$(sed -n 's/^CMAKE_PROJECT_VERSION:STATIC=//p' "$build/CMakeCache.txt")
runtime=$(ls "$tmp"/pkg/rtcl_"$version"_*.deb 2>/dev/null | head -1)
dev=$(ls "$tmp"/pkg/librtcl-dev_"$version"_*.deb 2>/dev/null | head -1)
checks=$((checks + 1))
if [ -z "$runtime" ] || [ -z "$dev" ]; then
    echo "FAIL: cpack made $(ls "$tmp/pkg"), not rtcl_${version}_ARCH.deb and librtcl-dev_${version}_ARCH.deb"
    fails=$((fails + 1)); finish; exit 1
fi
dpkg-deb -c "$runtime" | awk '{print $6}' | sed 's|^\./||' >"$tmp/runtime.txt"
dpkg-deb -c "$dev" | awk '{print $6}' | sed 's|^\./||' >"$tmp/dev.txt"
soname=$(readelf -d "$build/librtcl.so" | sed -n 's/.*Library soname: \[\(.*\)\]/\1/p')
# has LIST REGEX / lacks LIST REGEX: a file of the package matches, or none does.
has() {
    checks=$((checks + 1))
    grep -q -E "$2" "$tmp/$1.txt" || { echo "FAIL: the $1 package has no file matching $2"; fails=$((fails + 1)); }
}
lacks() {
    checks=$((checks + 1))
    ! grep -E "$2" "$tmp/$1.txt" || { echo "FAIL: the $1 package has the files above ($2)"; fails=$((fails + 1)); }
}
has runtime "^usr/bin/rtcl$"
has runtime "^usr/lib/(.*/)?$soname$"
has runtime "^usr/share/bash-completion/completions/rtcl$"
[ -e "$build/librtcl_image.so" ] && has runtime "^usr/lib/(.*/)?librtcl_image\.so$"
lacks runtime '^usr/include/|\.a$|pkgconfig|cmake/|librtcl\.so$'
has dev '^usr/include/rtcl/rt\.h$'
has dev '^usr/include/rtcl/rtcl_version\.h$'
has dev '^usr/lib/(.*/)?librtcl\.a$'
has dev '^usr/lib/(.*/)?librtcl\.so$'
has dev '^usr/lib/(.*/)?pkgconfig/rtcl\.pc$'
has dev '^usr/lib/(.*/)?cmake/rtcl/rtclConfig\.cmake$'
has dev '^usr/lib/(.*/)?cmake/rtcl/rtclConfigVersion\.cmake$'
has dev '^usr/share/doc/rtcl/examples/orbit\.c$'
lacks dev '^usr/bin/|\.so\.'
checks=$((checks + 1))
dpkg-deb -f "$dev" Depends | grep -q "rtcl (= $version)" ||
    { echo "FAIL: librtcl-dev does not depend on rtcl (= $version)"; fails=$((fails + 1)); }

# A manual page per command (where help2man is installed) and the completion.
commands=$("$build/rtcl" help --synopsis | awk '/^rtcl [a-z]/ {print $2}')
if command -v help2man >/dev/null; then
    has runtime "^usr/share/man/man1/rtcl\.1\.gz$"
    for c in $commands; do has runtime "^usr/share/man/man1/rtcl-$c\.1\.gz$"; done
else
    echo "note: no help2man, the manual pages are not checked"
fi

root="$tmp/root"
ok "unpack" dpkg-deb -x "$runtime" "$root" && ok "unpack dev" dpkg-deb -x "$dev" "$root"
usr="$root/usr"
if command -v help2man >/dev/null; then
    checks=$((checks + 1))
    gzip -dc "$usr/share/man/man1/rtcl-render.1.gz" | grep -q -- 'width' ||
        { echo "FAIL: rtcl-render.1 does not describe --width"; fails=$((fails + 1)); }
fi
# The completion: commands, then a command's options.
complete_words() { # WORDS...: what the completion offers for the last word
    bash -c 'source "$1"; shift; COMP_WORDS=("$@"); COMP_CWORD=$(($# - 1)); _rtcl; printf "%s\n" "${COMPREPLY[@]}"' \
        _ "$usr/share/bash-completion/completions/rtcl" "$@"
}
checks=$((checks + 1))
[ "$(complete_words rtcl ren)" = render ] ||
    { echo "FAIL: 'rtcl ren<TAB>' offers '$(complete_words rtcl ren)'"; fails=$((fails + 1)); }
checks=$((checks + 1))
complete_words rtcl render --wid | grep -q -x -- --width ||
    { echo "FAIL: 'rtcl render --wid<TAB>' offers '$(complete_words rtcl render --wid)'"; fails=$((fails + 1)); }
checks=$((checks + 1))
complete_words rtcl trace --ra | grep -q -x -- --rays ||
    { echo "FAIL: 'rtcl trace --ra<TAB>' offers '$(complete_words rtcl trace --ra)'"; fails=$((fails + 1)); }

# The example against the packages' files: CMake and pkg-config.
ex="$usr/share/doc/rtcl/examples"
ok "example: cmake configure" cmake -S "$ex" -B "$tmp/ex" -DCMAKE_PREFIX_PATH="$usr" -DCMAKE_BUILD_TYPE=Release &&
    ok "example: cmake build" cmake --build "$tmp/ex" && ok "example (cmake) runs" "$tmp/ex/orbit" "$tmp"
libdir=$(dirname "$(find "$usr/lib" -name librtcl.so | head -1)")
if command -v pkg-config >/dev/null; then
    ok "example: pkg-config" sh -c "PKG_CONFIG_PATH='$libdir/pkgconfig' && export PKG_CONFIG_PATH &&
        cc '$ex/orbit.c' -o '$tmp/orbit-pc' \$(pkg-config --cflags --libs rtcl) -lm -Wl,-rpath,'$libdir'" &&
        ok "example (pkg-config) runs" "$tmp/orbit-pc" "$tmp"
fi
expect 0 "^rtcl $version\$" -- "$usr/bin/rtcl" --version
expect 0 'wrote' -- "$usr/bin/rtcl" render builtin:cornell --width 32 --height 24 -o "$tmp/x.ppm"
finish
