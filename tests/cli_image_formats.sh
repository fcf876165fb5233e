# SPDX-License-Identifier: Apache-2.0
# cli_image_formats.sh - rtcl writes every image format of the library's one
# table by extension (issue 30, item 9), and its help and its error for an
# unknown extension list the same set: 'rtcl render -o' and 'rtcl compare
# --diff' help, and the error's "(supported: ...)". Each is written by
# rtcl render and compared with the PPM of the same frame (8-bit lossless
# formats: equal; the others within their rounding or loss).
source "$RT_SOURCE_DIR/tests/shell_check.sh"
rtcl=${RTCL:?}
scene="builtin:cornell --width 24 --height 16"
# shellcheck disable=SC2086
"$rtcl" render $scene -o "$tmp/x.nosuch" >"$tmp/err.txt" 2>&1 && { echo "FAIL: .nosuch was written"; exit 1; }
listed=$(sed -n 's/.*(supported: \(.*\))$/\1/p' "$tmp/err.txt" | tr -d ',' | tr ' ' '\n' | sort -u)
checks=$((checks + 1))
[ "$(wc -l <<<"$listed")" -ge 10 ] || { echo "FAIL: the error lists '$listed':"; cat "$tmp/err.txt"; fails=$((fails + 1)); }
# help_exts CMD OPTION: the extensions in OPTION's paragraph of CMD --help
help_exts() {
    "$rtcl" "$1" --help | awk -v o="$2" 'index($0, o) && /^  -/ {on = 1; next} on && /^  -/ {on = 0} on' |
        grep -o -E '\.[a-z]+[a-z0-9]*' | sort -u
}
for pair in "render --output" "compare --diff"; do
    # shellcheck disable=SC2086
    got=$(help_exts $pair)
    checks=$((checks + 1))
    if [ "$got" != "$listed" ]; then
        echo "FAIL: 'rtcl ${pair% *} --help' (${pair#* }) lists other formats than the error:"
        diff <(echo "$listed") <(echo "$got"); fails=$((fails + 1))
    fi
done
# shellcheck disable=SC2086
expect 0 'wrote' -- "$rtcl" render $scene -o "$tmp/ref.ppm"
# shellcheck disable=SC2086
"$rtcl" render $scene -o "$tmp/probe.png" >"$tmp/probe.txt" 2>&1 || {
    grep -q -E 'image module|no PNG or EXR' "$tmp/probe.txt" || { echo "FAIL: PNG:"; cat "$tmp/probe.txt"; fails=$((fails + 1)); }
    echo "note: no image module: only the formats written in C are checked ($(head -1 "$tmp/probe.txt"))"
    listed=$(grep -E '^\.(ppm|pgm|pfm)$' <<<"$listed")
}
for ext in $listed; do
    # shellcheck disable=SC2086
    expect 0 'wrote' -- "$rtcl" render $scene -o "$tmp/f$ext"
    case $ext in
    .png | .bmp | .tga | .sgi | .ppm | .pgm) bound=0 ;;
    .tif | .tiff | .dpx | .exr | .fits | .pfm) bound=0.0021 ;; # the PPM's half level of 8 bits
    *) bound=0.25 ;;                                            # lossy: JPEG, WebP, HDR
    esac
    expect 0 '' -- "$rtcl" compare "$tmp/ref.ppm" "$tmp/f$ext" --max-diff $bound
done
finish
