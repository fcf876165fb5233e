# SPDX-License-Identifier: Apache-2.0
# cli_outputs_full_disk.sh - writes onto a real full file system (a 256 KiB
# tmpfs mounted here, with all but one page taken by a filler file): every
# image format of the library's table, animation frames, a video, a hit
# file and generated scenes fail with exit status 2 and "No space left on
# device", the good file that was there before is byte for byte as it was,
# and no temporary is left (issue 31; before, each left a truncated file
# under its final name).
# Mounting needs root: CI runs as root; elsewhere the test says skipped.
source "$RT_SOURCE_DIR/tests/shell_check.sh"
anim=$RT_SOURCE_DIR/scenes/keyframes_animated.json

if [ "$(id -u)" != 0 ]; then
    echo "skipped: mounting a small tmpfs needs root"
    exit 77
fi
disk="$tmp/disk"
mkdir "$disk"
if ! mount -t tmpfs -o size=256k tmpfs "$disk" 2> "$tmp/mount.txt"; then
    echo "skipped: cannot mount a tmpfs here: $(cat "$tmp/mount.txt")"
    exit 77
fi
trap 'umount "$disk"; rm -rf "$tmp"' EXIT

# Every format of the library's table (the list its unknown-extension error
# gives).
formats=$("$RTCL" render builtin:cornell -o "$tmp/x.nosuch" 2>&1 |
    sed -n 's/.*(supported: \(.*\))$/\1/p' | tr -d ',.' | tr ' ' '\n' | sort -u)
checks=$((checks + 1))
[ "$(wc -w <<<"$formats")" -ge 10 ] || { echo "FAIL: the formats: $formats"; fails=$((fails + 1)); }
small=(--width 8 --height 8)
large=(--width 512 --height 512)
# The good files first, while there is room; their copies outside.
mkdir "$tmp/good"
for ext in $formats; do
    "$RTCL" render builtin:cornell "${small[@]}" -o "$disk/out.$ext" > /dev/null 2>&1
done
"$RTCL" animate "$anim" --fps 2 --frames 2 "${small[@]}" -o "$disk/f_%d.png" > /dev/null 2>&1
awk 'BEGIN { srand(3); for (i = 0; i < 4000; i++) printf "%f %f %f %f %f %f 0 inf\n",
     rand() * 3 - 1.5, rand() * 1.8, rand() * 4 - 1, rand() - 0.5, rand() - 0.5, rand() - 0.5 }' > "$tmp/rays.txt"
head -3 "$tmp/rays.txt" > "$tmp/few.txt"
"$RTCL" trace builtin:cornell --rays "$tmp/few.txt" --out "$disk/hits.txt" > /dev/null 2>&1
mkdir "$disk/gen"
"$RTCL" generate "$disk/gen" > /dev/null 2>&1
have_ffmpeg=0
if command -v ffmpeg > /dev/null; then
    have_ffmpeg=1
    "$RTCL" animate "$anim" --fps 2 --frames 2 "${small[@]}" -o "$disk/v.mp4" > /dev/null 2>&1
fi
cp -a "$disk/." "$tmp/good/"
for f in $(printf 'out.%s ' $formats) f_0.png f_1.png hits.txt; do
    checks=$((checks + 1))
    [ -s "$tmp/good/$f" ] || { echo "FAIL: the good file $f was not written"; fails=$((fails + 1)); }
done

# Fill the disk, then give one page back: writes start, then fail.
cat /dev/zero > "$disk/fill" 2> /dev/null
truncate -s -4096 "$disk/fill"

nospace='No space left on device'
for ext in $formats; do
    expect 2 "out.$ext: .*$nospace" -- "$RTCL" render builtin:cornell "${large[@]}" -o "$disk/out.$ext"
done
expect 2 "f_0.png: .*$nospace" -- "$RTCL" animate "$anim" --fps 2 --frames 2 \
    "${large[@]}" -o "$disk/f_%d.png"
expect 2 "hits.txt: .*$nospace" -- "$RTCL" trace builtin:cornell --rays "$tmp/rays.txt" \
    --out "$disk/hits.txt"
# A scene of several pages of OBJ: a mesh file fails.
expect 2 "$nospace" -- "$RTCL" generate "$disk/gen"
if [ $have_ffmpeg = 1 ]; then
    expect 2 'v.mp4: .*(No space left|ffmpeg)' -- "$RTCL" animate "$anim" --fps 8 \
        --frames 16 "${large[@]}" -o "$disk/v.mp4"
fi

rm "$disk/fill"
checks=$((checks + 1))
if ! diff -r "$tmp/good" "$disk" > "$tmp/diff.txt"; then
    echo "FAIL: the full disk's files changed:"; head -20 "$tmp/diff.txt"; fails=$((fails + 1))
fi
checks=$((checks + 1))
if ls -A "$disk" "$disk/gen" | grep -q '\.tmp-'; then
    echo "FAIL: temporaries left:"; ls -A "$disk" "$disk/gen"; fails=$((fails + 1))
fi
finish
