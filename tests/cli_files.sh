# SPDX-License-Identifier: Apache-2.0
# cli_files.sh - input files that are not regular files, or too large, are
# refused with the file name and the reason, never read without bound and
# never waited on: a FIFO as a scene, OBJ, MTL or ray file (open() used to
# block forever), an OBJ or scene symlinked to /dev/zero (used to grow a
# buffer until memory ran out), directories, and files beyond the documented
# size limits (docs/ROBUSTNESS.md, "Limits"; sparse files, nothing is read).
# Every command runs under a timeout so that a regression fails, not hangs.
source "$RT_SOURCE_DIR/tests/shell_check.sh"

T="timeout 20"
printf 'v -1 -1 -3\nv 1 -1 -3\nv 0 1 -3\nf 1 2 3\n' > "$tmp/tri.obj"
printf '0 0 0 0 0 -1 0 inf\n' > "$tmp/one.rays"

mkfifo "$tmp/fifo.json" "$tmp/fifo.obj" "$tmp/fifo.rays" "$tmp/fifo.mtl"
expect 2 'fifo.json: .*scene file: it is a FIFO' -- $T "$RTCL" info "$tmp/fifo.json"
expect 2 'fifo.obj: .*OBJ file: it is a FIFO' -- $T "$RTCL" info "$tmp/fifo.obj"
expect 2 'fifo.rays: .*ray file: it is a FIFO' -- $T "$RTCL" trace "$tmp/tri.obj" \
    --rays "$tmp/fifo.rays" --out "$tmp/hits.txt"
# An OBJ whose mtllib is a FIFO: the MTL is unreadable, the OBJ loads.
printf 'mtllib fifo.mtl\nv -1 -1 -3\nv 1 -1 -3\nv 0 1 -3\nf 1 2 3\n' > "$tmp/withmtl.obj"
expect 0 'triangles' -- $T "$RTCL" info "$tmp/withmtl.obj"
# A JSON scene naming a FIFO as its mesh.
printf '{"meshes": {"m": {"file": "fifo.obj"}}, "objects": [{"mesh": "m"}]}\n' > "$tmp/usesfifo.json"
expect 2 'fifo.obj: .*it is a FIFO' -- $T "$RTCL" info "$tmp/usesfifo.json"

# A regression here would read /dev/zero until memory runs out: cap the
# address space (not under AddressSanitizer, which reserves terabytes).
if ! ldd "$RTCL" 2> /dev/null | grep -q asan; then ulimit -v 4194304; fi
ln -s /dev/zero "$tmp/zero.obj"
ln -s /dev/zero "$tmp/zero.json"
ln -s /dev/zero "$tmp/zero.rays"
expect 2 'zero.obj: .*it is a character device' -- $T "$RTCL" info "$tmp/zero.obj"
expect 2 'zero.json: .*it is a character device' -- $T "$RTCL" info "$tmp/zero.json"
expect 2 'zero.rays: .*it is a character device' -- $T "$RTCL" trace "$tmp/tri.obj" \
    --rays "$tmp/zero.rays" --out "$tmp/hits.txt"

mkdir "$tmp/dir.obj" "$tmp/dir.json" "$tmp/dir.rays"
expect 2 'dir.obj: .*it is a directory' -- $T "$RTCL" info "$tmp/dir.obj"
expect 2 'dir.json: .*it is a directory' -- $T "$RTCL" info "$tmp/dir.json"
expect 2 'dir.rays: .*it is a directory' -- $T "$RTCL" trace "$tmp/tri.obj" \
    --rays "$tmp/dir.rays" --out "$tmp/hits.txt"

# One byte beyond each limit (64 MiB scene, 4 GiB OBJ and ray file), as
# sparse files: refused before any of it is read.
truncate -s $((64 * 1024 * 1024 + 1)) "$tmp/big.json"
truncate -s $((4 * 1024 * 1024 * 1024 + 1)) "$tmp/big.obj" "$tmp/big.rays"
expect 2 'big.json: the scene file is 67108865 bytes, more than the limit of 67108864' -- \
    $T "$RTCL" info "$tmp/big.json"
expect 2 'big.obj: the OBJ file is 4294967297 bytes, more than the limit of 4294967296' -- \
    $T "$RTCL" info "$tmp/big.obj"
expect 2 'big.rays: the ray file is 4294967297 bytes, more than the limit of 4294967296' -- \
    $T "$RTCL" trace "$tmp/tri.obj" --rays "$tmp/big.rays" --out "$tmp/hits.txt"
rm -f "$tmp/big.json" "$tmp/big.obj" "$tmp/big.rays"

# Limits before memory (issue 31). An OBJ one triangle past the limit (one
# fan face of 2^28 + 3 corners, 512 MiB of text) is refused from its counts
# before the parse allocates (it used to grow 3.7 GB first, and run out of
# the address space allowed here).
{ printf 'v 0 0 0\nf'; yes ' 1' | tr -d '\n' | head -c $((2 * (268435456 + 3))); echo; } > "$tmp/fan.obj"
expect 2 'fan.obj: the file.s faces make 268435457 triangles, more than the limit of 268435456' -- \
    timeout 120 "$RTCL" info "$tmp/fan.obj"
rm -f "$tmp/fan.obj"
# An inline JSON mesh of short numbers (20 MB) loads in a few times its
# size: its big arrays are read from the text, not as a jansson value per
# number (that took 25 times the file). Peak memory, not time, is measured.
if [ -x /usr/bin/time ] && ! ldd "$RTCL" 2> /dev/null | grep -q asan; then
    awk 'BEGIN { srand(5); n = 1100000; printf "{\"meshes\": {\"m\": {\"positions\": [";
         for (i = 0; i < 3 * n; i++) printf "%s%d", i ? "," : "", int(rand() * 10);
         printf "], \"triangles\": [";
         for (i = 0; i < 6 * n; i++) printf "%s%d", i ? "," : "", int(rand() * 10);
         printf "]}}, \"objects\": [{\"mesh\": \"m\"}]}\n" }' > "$tmp/inline.json"
    size_kb=$(($(stat -c %s "$tmp/inline.json") / 1024))
    expect 0 'triangles +2200000' -- /usr/bin/time -o "$tmp/rss.txt" -f %M "$RTCL" info "$tmp/inline.json"
    checks=$((checks + 1))
    rss_kb=$(tail -1 "$tmp/rss.txt")
    if [ "$rss_kb" -gt $((6 * size_kb)) ]; then
        echo "FAIL: an inline mesh of $size_kb KB took $rss_kb KB (more than 6 times)"
        fails=$((fails + 1))
    fi
    rm -f "$tmp/inline.json"
else
    echo "note: the inline mesh's peak memory is not measured (needs GNU time, not under ASan)"
fi
# Image reads check the header's size against the pixel limit before any
# pixel memory is taken: a 100000 x 100000 PNG (a few hundred bytes, valid
# chunks) asked for 120 GB; an ASCII PPM claiming 30000 x 30000 pixels with
# six of them is cut short, found before its 10 GB are allocated.
py=/usr/bin/python3
[ -x "$py" ] || py=python3
$py - "$tmp/huge.png" <<'PY'
import struct, sys, zlib
def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
ihdr = struct.pack(">IIBBBBB", 100000, 100000, 8, 2, 0, 0, 0)
with open(sys.argv[1], "wb") as f:
    f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(b"\0" * 64))
            + chunk(b"IEND", b""))
PY
printf 'P3\n30000 30000\n255\n1 2 3 4 5 6\n' > "$tmp/huge.ppm"
printf 'P6\n1 1\n255\nabc' > "$tmp/one.ppm"
expect 2 'huge.png: the image is 100000x100000 with 3 channels, beyond the limit of 1073741824 pixels' -- \
    $T "$RTCL" compare "$tmp/huge.png" "$tmp/one.ppm"
expect 2 'huge.ppm: PNM file cut short: fewer pixels than its size says' -- \
    $T "$RTCL" compare "$tmp/huge.ppm" "$tmp/one.ppm"
# A 2 GB sparse ray file is refused at its first line, without reading the
# rest (it was read whole first: 33 s and 2.1 GB).
truncate -s $((2 * 1024 * 1024 * 1024)) "$tmp/sparse.rays"
expect 2 'sparse.rays:1: a NUL byte in the line' -- \
    $T "$RTCL" trace "$tmp/tri.obj" --rays "$tmp/sparse.rays" --out "$tmp/hits.txt"
# A ray file line beyond 1 MiB is refused with its line.
{ printf '0 0 0 0 0 -1 0 inf\n'; head -c 1100000 /dev/zero | tr '\0' ' '; echo; } > "$tmp/longline.rays"
expect 2 'longline.rays:2: the line is longer than the limit of 1048576 bytes' -- \
    $T "$RTCL" trace "$tmp/tri.obj" --rays "$tmp/longline.rays" --out "$tmp/hits.txt"
finish
