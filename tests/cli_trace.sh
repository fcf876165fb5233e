# SPDX-License-Identifier: Apache-2.0
# cli_trace.sh - 'rtcl trace': hit lines, misses, tmin/tmax, backends agree,
# any-hit, bad ray lines reported with file:line; --packet-path, --stats,
# --json and --reps (issue 20).
source "$RT_SOURCE_DIR/tests/shell_check.sh"

rays=$tmp/rays.txt
cat > "$rays" <<'R'
# the back wall of the Cornell room, straight ahead
0 1.5 3 0 0 -1 0 inf
# the same with a direction of length 2: t halves
0 1.5 3 0 0 -2 0 inf
# out of the open front: a miss
0 1.5 3 0 0 1 0 inf
# tmax short of the wall: a miss; tmax exactly at the wall: a hit
0 1.5 3 0 0 -1 0 3.5
0 1.5 3 0 0 -1 0 4

# NaN and zero directions are misses
0 1.5 3 nan 0 -1 0 inf
0 1.5 3 0 0 0 0 inf
R
expect 0 '' -- "$RTCL" trace builtin:cornell --rays "$rays" --out "$tmp/hits.txt"
checks=$((checks + 1))
want=$'1 4 U V P 0\n1 2 U V P 0\n0 inf 0 0 -1 -1\n0 inf 0 0 -1 -1\n1 4 U V P 0\n0 inf 0 0 -1 -1\n0 inf 0 0 -1 -1'
got=$(awk '{ if ($1 == 1) { $3 = "U"; $4 = "V"; $5 = "P" } print }' "$tmp/hits.txt")
if [ "$got" != "$want" ]; then
    echo "FAIL: hits:"; cat "$tmp/hits.txt"; fails=$((fails + 1))
fi

# Random rays: the packet backend gives the same lines as the scalar one.
awk 'BEGIN { srand(3); for (i = 0; i < 2000; i++) printf "%f %f %f %f %f %f 0 inf\n",
     rand() * 3 - 1.5, rand() * 1.8, rand() * 4 - 1, rand() - 0.5, rand() - 0.5, rand() - 0.5 }' > "$tmp/random.txt"
expect 0 '' -- "$RTCL" trace builtin:cornell --rays "$tmp/random.txt" --out "$tmp/cpu.txt"
expect 0 '' -- "$RTCL" trace builtin:cornell --rays "$tmp/random.txt" --out "$tmp/packet.txt" --backend packet
checks=$((checks + 1))
if ! cmp -s "$tmp/cpu.txt" "$tmp/packet.txt"; then
    echo "FAIL: packet and cpu hits differ"; fails=$((fails + 1))
fi
# A ray with tmax = -inf (or NaN, or an inverted range) in the packet of
# valid ones (one origin, directions of one sign: the packet-wide interval
# test runs) must not hide their hits, at t = 0 or beyond; in each
# instruction-set build of the packet tracer.
{
    printf '0 1.5 -1 0.001 0.001 -1 0 -inf\n0 1.5 -1 0.001 0.001 -1 0 inf\n'
    printf '0.2 1.0 -1 0.1 0.1 -1 0 inf\n0 1.5 3 0.001 0.001 -1 5 1\n'
    for i in $(seq 60); do printf '0 1.5 3 0.00%d 0.001 -1 0 inf\n' $((i % 9 + 1)); done
    # a second packet: NaN and -inf range ends
    printf '0 1.5 3 0.001 0.001 -1 0 nan\n0 1.5 3 0.002 0.001 -1 -inf -inf\n'
    printf '0 1.5 3 0.001 0.002 -1 0 inf\n'
} > "$tmp/odd.txt"
expect 0 '' -- "$RTCL" trace builtin:cornell --rays "$tmp/odd.txt" --out "$tmp/odd_cpu.txt"
for isa in generic avx2 avx512; do
    RTCL_PACKET_ISA=$isa expect 0 '' -- "$RTCL" trace builtin:cornell --rays "$tmp/odd.txt" \
        --out "$tmp/odd_packet.txt" --backend packet
    checks=$((checks + 1))
    if ! cmp -s "$tmp/odd_cpu.txt" "$tmp/odd_packet.txt"; then
        echo "FAIL: packet ($isa) differs from cpu with odd rays in the packet:"
        paste "$tmp/odd_cpu.txt" "$tmp/odd_packet.txt"; fails=$((fails + 1))
    fi
done
if [ "$(grep -c '^1 ' "$tmp/odd_cpu.txt")" != 63 ]; then
    echo "FAIL: expected 63 hits among the odd rays:"; cat "$tmp/odd_cpu.txt"; fails=$((fails + 1))
fi

# Any-hit agrees with closest hit on whether a ray hits.
expect 0 '' -- "$RTCL" trace builtin:cornell --rays "$tmp/random.txt" --out "$tmp/any.txt" --any-hit
checks=$((checks + 1))
if [ "$(cut -d' ' -f1 "$tmp/cpu.txt")" != "$(cut -d' ' -f1 "$tmp/any.txt")" ]; then
    echo "FAIL: any-hit and closest-hit disagree on hits"; fails=$((fails + 1))
fi

printf '0 0 0 1 0 0 0 inf\n0 0 0 1 0\n' > "$tmp/bad.txt"
expect 2 'bad.txt:2: expected 8 numbers' -- "$RTCL" trace builtin:cornell --rays "$tmp/bad.txt" --out "$tmp/x.txt"
printf '0 0 0 1 0 0 0 inf x\n' > "$tmp/bad2.txt"
expect 2 'bad2.txt:1: .*found: x' -- "$RTCL" trace builtin:cornell --rays "$tmp/bad2.txt" --out "$tmp/x.txt"
expect 2 'cannot open' -- "$RTCL" trace builtin:cornell --rays "$tmp/missing.txt" --out "$tmp/x.txt"
# NUL bytes (a file of them, one inside a line, a binary file) are errors
# with file:line, not blank lines; a directory is a read error, not zero
# rays. Under a timeout: a file of NULs used to hang.
head -c 100000 /dev/zero > "$tmp/nul.txt"
expect 2 'nul.txt:1: a NUL byte' -- timeout 20 "$RTCL" trace builtin:cornell --rays "$tmp/nul.txt" --out "$tmp/x.txt"
printf '0 1.5 3 0 0 -1 0 inf\n0 1.5 3 0 0\000 -1 0 inf\n' > "$tmp/nul2.txt"
expect 2 'nul2.txt:2: a NUL byte' -- timeout 20 "$RTCL" trace builtin:cornell --rays "$tmp/nul2.txt" --out "$tmp/x.txt"
expect 2 'rtcl:1: a NUL byte' -- timeout 20 "$RTCL" trace builtin:cornell --rays "$RTCL" --out "$tmp/x.txt"
mkdir "$tmp/raydir"
expect 2 'raydir: .*directory' -- timeout 20 "$RTCL" trace builtin:cornell --rays "$tmp/raydir" --out "$tmp/x.txt"
# Lines longer than any buffer: one line is one ray, whatever its length.
{ printf '%5000s' ''; printf '0 1.5 3 0 0 -1 0 inf\n'; printf '0 1.5 3 0 0 -1 0 4'; printf '%6000s\n' ''; } > "$tmp/long.txt"
expect 0 '' -- "$RTCL" trace builtin:cornell --rays "$tmp/long.txt" --out "$tmp/long_hits.txt"
checks=$((checks + 1))
if [ "$(cut -d' ' -f1,2 "$tmp/long_hits.txt" | tr '\n' ,)" != "1 4,1 4," ]; then
    echo "FAIL: long lines:"; cat "$tmp/long_hits.txt"; fails=$((fails + 1))
fi
# Two rays' numbers on one long line are an error, not two rays.
{ printf '0 1.5 3 0 0 -1 0 inf'; printf '%5000s' ''; printf '0 1.5 3 0 0 -1 0 inf\n'; } > "$tmp/two.txt"
expect 2 'two.txt:1: expected 8 numbers .*found: ' -- "$RTCL" trace builtin:cornell --rays "$tmp/two.txt" --out "$tmp/x.txt"
# Timing and paths (issue 20): --packet-path forces packets or single rays,
# the same hits either way; --stats and --json report the trace time alone
# and the path; bad values are refused.
for path in packets single; do
    expect 0 '' -- "$RTCL" trace builtin:cornell --rays "$tmp/random.txt" --out "$tmp/path_$path.txt" \
        --backend packet --packet-path "$path"
    checks=$((checks + 1))
    cmp -s "$tmp/cpu.txt" "$tmp/path_$path.txt" || { echo "FAIL: packet path $path differs from cpu"; fails=$((fails + 1)); }
done
expect 0 'path: packet .*: 0 rays in packets .*, 2000 one at a time' -- "$RTCL" trace builtin:cornell \
    --rays "$tmp/random.txt" --backend packet --packet-path single --stats --reps 2
expect 0 'trace: 2000 rays \(any hit\), 3 runs after a warm-up: min [0-9.]+ ms, median [0-9.]+ ms' -- \
    "$RTCL" trace builtin:cornell --rays "$tmp/random.txt" --any-hit --stats --reps 3
expect 0 '^\{"rays": 2000, "reps": 2, .*"ms_min": [0-9.]+, "ms_median": [0-9.]+, "mrays": [0-9.]+, .*"backend": "packet"' -- \
    "$RTCL" trace builtin:cornell --rays "$tmp/random.txt" --backend packet --json --reps 2
expect 2 "--packet-path: 'both' is not one of auto, packets or single" -- "$RTCL" trace builtin:cornell --rays "$rays" --out "$tmp/x.txt" --packet-path both
expect 2 'reps' -- "$RTCL" trace builtin:cornell --rays "$rays" --stats --reps 0
expect 2 "unknown backend 'warp'" -- "$RTCL" trace builtin:cornell --rays "$rays" --out "$tmp/x.txt" --backend warp
expect 2 '--out HITS.txt is required \(or --stats or --json\)' -- "$RTCL" trace builtin:cornell --rays "$rays"
expect 0 'usage: rtcl trace' -- "$RTCL" trace --help
finish
