# SPDX-License-Identifier: Apache-2.0
# cli_animate_video.sh - 'rtcl animate -o out.mp4' (and .mkv, .webm) through
# ffmpeg: the video has the frames asked for, the size and the codec
# (ffprobe), and its frame k, decoded by ffmpeg, is the image 'rtcl render
# --time k/F' gives. The codec is lossy (H.264 at CRF 18, 4:2:0 chroma,
# limited-range YUV), so the check is a PSNR bound, not bit equality: at
# least 30 dB against frame k's render (the shipped scene gives 33-37), and
# more than against the neighbouring frames' renders (so frames are neither
# dropped nor reordered). Also: odd sizes are padded to even ones, frame
# ranges, paths that a shell or ffmpeg would misread reach ffmpeg as they
# are, and ffmpeg's failures (no such folder, a full disk) exit non-zero with
# ffmpeg's reason; nothing reaches stderr on success; equal clips are equal
# files unless --metadata. Without ffmpeg and
# ffprobe (Debian package ffmpeg) this test is skipped; the error without
# ffmpeg is tested in cli_animate.sh.
. "$(dirname "$0")/shell_check.sh"
: "${RTCL:?RTCL must name the rtcl binary}"
: "${RT_SOURCE_DIR:?RT_SOURCE_DIR must name the repository}"
if ! command -v ffmpeg >/dev/null || ! command -v ffprobe >/dev/null; then
    echo "skipped: ffmpeg not installed"
    exit 77
fi
scene="$RT_SOURCE_DIR/scenes/keyframes_animated.json"
size=(--width 160 --height 90)

probe() { # probe FILE: "codec width height frames pix_fmt"
    ffprobe -v error -select_streams v:0 -count_frames \
        -show_entries stream=codec_name,width,height,nb_read_frames,pix_fmt -of csv=p=0 "$1" |
        awk -F, '{ print $1, $2, $3, $5, $4 }'
}

check_probe() { # check_probe FILE "codec width height frames pix_fmt"
    checks=$((checks + 1))
    local got
    got=$(probe "$1")
    if [ "$got" != "$2" ]; then
        echo "FAIL: $1: ffprobe says '$got', expected '$2'"; fails=$((fails + 1))
    fi
}

psnr() { # psnr A B: the PSNR in dB that 'rtcl compare' prints
    "$RTCL" compare "$1" "$2" 2>&1 | awk '/^PSNR:/ { print $2 }'
}

codec=h264
ffmpeg -hide_banner -loglevel error -encoders | grep -q ' libx264 ' || codec=mpeg4

out="$tmp/a.mp4"
"$RTCL" animate "$scene" --fps 8 --frames 12 "${size[@]}" -o "$out" >"$tmp/out" 2>"$tmp/err"
rc=$?
checks=$((checks + 1))
if [ "$rc" != 0 ] || [ -s "$tmp/err" ] || [ -s "$tmp/out" ]; then
    echo "FAIL: animate -o a.mp4: status $rc, output:"; cat "$tmp/out" "$tmp/err"
    fails=$((fails + 1))
fi
check_probe "$out" "$codec 160 90 12 yuv420p"

# Frame k of the video against 'rtcl render --time k/8'.
for k in 0 4 5 11; do
    t=$(awk "BEGIN { printf \"%.17g\", $k / 8 }")
    expect 0 "" -- "$RTCL" render "$scene" "${size[@]}" --time "$t" -o "$tmp/ref_$k.ppm"
done
for k in 4 5 11; do
    ffmpeg -v error -nostdin -i "$out" -vf "select=eq(n\\,$k)" -frames:v 1 -c:v ppm -y \
        "$tmp/dec_$k.ppm"
    p=$(psnr "$tmp/ref_$k.ppm" "$tmp/dec_$k.ppm")
    checks=$((checks + 1))
    if ! awk "BEGIN { exit !($p >= 30) }" 2>/dev/null; then
        echo "FAIL: video frame $k: PSNR '$p' dB against 'render --time', expected >= 30"
        fails=$((fails + 1))
    fi
    case $k in 4) other=5 ;; 5) other=4 ;; *) other=0 ;; esac
    q=$(psnr "$tmp/ref_$other.ppm" "$tmp/dec_$k.ppm")
    checks=$((checks + 1))
    if ! awk "BEGIN { exit !($p > $q) }" 2>/dev/null; then
        echo "FAIL: video frame $k is closer to frame $other ($q dB) than to itself ($p dB)"
        fails=$((fails + 1))
    fi
done

# Matroska and WebM; an odd size gets one black column; a frame range.
expect 0 "" -- "$RTCL" animate "$scene" --fps 8 --frames 3 "${size[@]}" -o "$tmp/b.MKV"
check_probe "$tmp/b.MKV" "$codec 160 90 3 yuv420p"
if ffmpeg -hide_banner -loglevel error -encoders | grep -q ' libvpx-vp9 '; then
    expect 0 "" -- "$RTCL" animate "$scene" --fps 8 --frames 3 --width 81 --height 46 \
        -o "$tmp/c.webm"
    check_probe "$tmp/c.webm" "vp9 82 46 3 yuv420p"
fi
expect 0 "" -- "$RTCL" animate "$scene" --fps 8 --frames 12 --frame-range 4:7 "${size[@]}" \
    -o "$tmp/range.mp4"
check_probe "$tmp/range.mp4" "$codec 160 90 4 yuv420p"

# Equal clips are equal files in every container (issue 31): Matroska and
# WebM held the date and a random segment id; --metadata keeps them.
exts="mp4 mkv"
ffmpeg -hide_banner -loglevel error -encoders | grep -q ' libvpx' && exts="$exts webm"
for ext in $exts; do
    for k in 1 2; do
        expect 0 "" -- "$RTCL" animate "$scene" --fps 8 --frames 3 --width 32 --height 24 \
            -o "$tmp/same$k.$ext"
    done
    checks=$((checks + 1))
    cmp -s "$tmp/same1.$ext" "$tmp/same2.$ext" ||
        { echo "FAIL: two equal clips to .$ext differ"; fails=$((fails + 1)); }
done
for k in 1 2; do
    expect 0 "" -- "$RTCL" animate "$scene" --fps 8 --frames 3 --width 32 --height 24 \
        --metadata -o "$tmp/meta$k.mkv"
done
checks=$((checks + 1))
if cmp -s "$tmp/meta1.mkv" "$tmp/meta2.mkv"; then
    echo "FAIL: --metadata: two .mkv files without their segment ids"; fails=$((fails + 1))
fi

# The path reaches ffmpeg as one argument: no shell runs it, and ffmpeg takes
# neither a leading '-' for an option nor 'x:' for a protocol.
odd='-x:$(touch pwned);y.mp4'
(cd "$tmp" && "$RTCL" animate "$scene" --fps 8 --frames 2 "${size[@]}" -o "$odd" 2>&1)
checks=$((checks + 1))
if [ ! -s "$tmp/$odd" ] || [ -e "$tmp/pwned" ]; then
    echo "FAIL: -o '$odd': $(ls "$tmp")"; fails=$((fails + 1))
fi

# A missing folder is found before any frame is made (issue 31); ffmpeg's
# own failures: the reason, a non-zero status.
expect 2 "v.mp4: cannot write the video: folder .*dir: No such file or directory" -- \
    "$RTCL" animate "$scene" --fps 8 --frames 3 "${size[@]}" -o "$tmp/no/such/dir/v.mp4"
if [ -w /dev/full ]; then
    ln -s /dev/full "$tmp/full.mkv"
    expect 2 "could not be written: .*No space left on device" -- \
        "$RTCL" animate "$scene" --fps 8 --frames 6 "${size[@]}" -o "$tmp/full.mkv"
fi
finish
