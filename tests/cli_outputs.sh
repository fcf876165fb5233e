# SPDX-License-Identifier: Apache-2.0
# cli_outputs.sh - what rtcl writes is whole, checked up front and the same
# bytes for the same image (issue 31):
#  - output paths and formats are refused before any work: a missing folder
#    or an unknown extension fails at once for render, animate (frames and
#    videos), trace --out, generate and compare --diff, even where the work
#    would take minutes (8192x8192 frames, under a timeout) or where an input
#    is missing (the output is named, so it was checked first);
#  - SIGKILL while a file is written leaves the old file, whole, or the new
#    one, never a part; SIGINT, SIGTERM or SIGHUP also leaves no temporary
#    (of an image, or of a video ffmpeg writes); two writers of one path,
#    one stopped mid-write, both finish and the file is the whole image of
#    the last (tests/output_faults.py); no temporary is left by a finished
#    write;
#  - two renders of one image are identical files in every format (EXR has
#    no capDate unless --metadata asks for it);
#  - an existing file keeps its permission bits; /dev/null is written in
#    place (not replaced).
# The full-disk cases are tests/cli_outputs_full_disk.sh (they need root).
source "$RT_SOURCE_DIR/tests/shell_check.sh"
anim=$RT_SOURCE_DIR/scenes/keyframes_animated.json
py=/usr/bin/python3
[ -x "$py" ] || py=python3

T="timeout 20"
big=(--width 8192 --height 8192)
expect 2 'nodir/o.ppm: cannot write the image file: folder .*nodir: No such file' -- \
    $T "$RTCL" render builtin:cornell "${big[@]}" -o "$tmp/nodir/o.ppm"
expect 2 'o.gif: unknown image file extension' -- \
    $T "$RTCL" render builtin:cornell "${big[@]}" -o "$tmp/o.gif"
: > "$tmp/plainfile"
expect 2 'plainfile/o.png: cannot write the image file: .*plainfile is not a folder' -- \
    $T "$RTCL" render builtin:cornell "${big[@]}" -o "$tmp/plainfile/o.png"
mkdir "$tmp/adir.png"
expect 2 'adir.png: cannot write the image file: it is a folder' -- \
    $T "$RTCL" render builtin:cornell "${big[@]}" -o "$tmp/adir.png"
expect 2 'nodir/f_%04d.png: .*nodir/f_0000.png: cannot write the image file: folder' -- \
    $T "$RTCL" animate "$anim" --fps 1 --frames 3 "${big[@]}" -o "$tmp/nodir/f_%04d.png"
expect 2 'f_%04d.ico: .*f_0000.ico: unknown image file extension' -- \
    $T "$RTCL" animate "$anim" --fps 1 --frames 3 "${big[@]}" -o "$tmp/f_%04d.ico"
if command -v ffmpeg > /dev/null; then
    expect 2 'nodir/v.mp4: .*cannot write the video: folder' -- \
        $T "$RTCL" animate "$anim" --fps 1 --frames 3 "${big[@]}" -o "$tmp/nodir/v.mp4"
fi
expect 2 'nodir/hits.txt: cannot write the hit file: folder' -- \
    $T "$RTCL" trace builtin:cornell --rays "$tmp/missing.rays" --out "$tmp/nodir/hits.txt"
expect 2 'plainfile: not a folder' -- $T "$RTCL" generate "$tmp/plainfile/gen"
expect 2 'difference image: .*nodir/d.exr: cannot write the image file: folder' -- \
    $T "$RTCL" compare "$tmp/missing_a.png" "$tmp/missing_b.png" --diff "$tmp/nodir/d.exr"

# Identical renders to two names are identical files, in every format of the
# library's table (the list its unknown-extension error gives); no temporary
# stays. (SGI's header held stack bytes, DPX's the file's name.)
mkdir "$tmp/same"
formats=$("$RTCL" render builtin:cornell -o "$tmp/x.nosuch" 2>&1 |
    sed -n 's/.*(supported: \(.*\))$/\1/p' | tr -d ',.' | tr ' ' '\n' | sort -u)
checks=$((checks + 1))
for ext in ppm pgm pfm png exr tif sgi dpx; do
    grep -qx "$ext" <<<"$formats" ||
        { echo "FAIL: .$ext is not among the formats: $formats"; fails=$((fails + 1)); }
done
for ext in $formats; do
    for k in 1 2; do
        expect 0 "wrote $tmp/same/$k.$ext" -- "$RTCL" render builtin:cornell --width 48 \
            --height 32 -o "$tmp/same/$k.$ext"
    done
    checks=$((checks + 1))
    cmp -s "$tmp/same/1.$ext" "$tmp/same/2.$ext" ||
        { echo "FAIL: two renders to .$ext differ"; fails=$((fails + 1)); }
done
checks=$((checks + 1))
if grep -q capDate "$tmp/same/1.exr"; then echo "FAIL: an EXR with capDate"; fails=$((fails + 1)); fi
expect 0 'wrote' -- "$RTCL" render builtin:cornell --width 48 --height 32 --metadata \
    -o "$tmp/same/meta.exr"
checks=$((checks + 1))
grep -q capDate "$tmp/same/meta.exr" ||
    { echo "FAIL: --metadata wrote no capDate"; fails=$((fails + 1)); }
expect 0 '' -- "$RTCL" animate "$anim" --fps 2 --frames 2 --width 24 --height 16 \
    -o "$tmp/same/f_%d.exr"
expect 0 '' -- "$RTCL" animate "$anim" --fps 2 --frames 2 --width 24 --height 16 \
    -o "$tmp/same/g_%d.exr"
checks=$((checks + 1))
cmp -s "$tmp/same/f_1.exr" "$tmp/same/g_1.exr" ||
    { echo "FAIL: two animations gave different frames"; fails=$((fails + 1)); }
checks=$((checks + 1))
if [ -n "$(ls -A "$tmp/same" | grep '\.tmp-')" ]; then
    echo "FAIL: temporaries left: $(ls -A "$tmp/same")"; fails=$((fails + 1))
fi

# An existing file's permission bits stay; /dev/null is not replaced.
expect 0 'wrote' -- "$RTCL" render builtin:cornell --width 8 --height 8 -o "$tmp/mode.ppm"
chmod 640 "$tmp/mode.ppm"
expect 0 'wrote' -- "$RTCL" render builtin:cornell --width 16 --height 8 -o "$tmp/mode.ppm"
checks=$((checks + 1))
[ "$(stat -c %a "$tmp/mode.ppm")" = 640 ] ||
    { echo "FAIL: mode $(stat -c %a "$tmp/mode.ppm"), expected 640"; fails=$((fails + 1)); }
ln -s /dev/null "$tmp/null.ppm"
expect 0 'wrote' -- "$RTCL" render builtin:cornell --width 8 --height 8 -o "$tmp/null.ppm"
checks=$((checks + 1))
[ -c /dev/null ] && [ -L "$tmp/null.ppm" ] ||
    { echo "FAIL: /dev/null or the link to it was replaced"; fails=$((fails + 1)); }
# A symlink to a file: the file is replaced, the link stays.
expect 0 'wrote' -- "$RTCL" render builtin:cornell --width 8 --height 8 -o "$tmp/real.ppm"
ln -s real.ppm "$tmp/link.ppm"
expect 0 'wrote' -- "$RTCL" render builtin:cornell --width 16 --height 8 -o "$tmp/link.ppm"
checks=$((checks + 1))
[ -L "$tmp/link.ppm" ] && head -2 "$tmp/real.ppm" | grep -q '^16 8$' ||
    { echo "FAIL: writing through a symlink"; fails=$((fails + 1)); }

# SIGKILL during writes and interleaved writers.
for ext in pfm exr; do
    mkdir "$tmp/kill_$ext"
    checks=$((checks + 1))
    $py "$RT_SOURCE_DIR/tests/output_faults.py" kill "$RTCL" "$tmp/kill_$ext" 8 $ext ||
        fails=$((fails + 1))
done
# SIGINT, SIGTERM, SIGHUP during a write and during a video: no temporary.
mkdir "$tmp/interrupt"
checks=$((checks + 1))
$py "$RT_SOURCE_DIR/tests/output_faults.py" interrupt "$RTCL" "$tmp/interrupt" ||
    fails=$((fails + 1))
for ext in ppm pfm png exr; do
    mkdir "$tmp/both_$ext"
    checks=$((checks + 1))
    $py "$RT_SOURCE_DIR/tests/output_faults.py" interleave "$RTCL" "$tmp/both_$ext" $ext ||
        fails=$((fails + 1))
done
finish
