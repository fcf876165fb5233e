# SPDX-License-Identifier: Apache-2.0
# cli_kernel_cache.sh - the on-disk kernel cache (README, "Kernel cache";
# issue 30, item 10). On each device backend found (OpenCL, Vulkan): images
# rendered with a cold cache, a warm one, and a damaged entry (garbage,
# truncated, a valid header over a payload the driver must refuse) are
# byte-identical, and the damaged entry is replaced by a good one; the folder
# rules ($RTCL_CACHE_DIR, $XDG_CACHE_HOME/rtcl, $HOME/.cache/rtcl), the off
# switch, and an unusable folder (not an error, no message); the one-line
# compile notice on a terminal only.
source "$RT_SOURCE_DIR/tests/shell_check.sh"

# have API: the build has the backend and the machine a device for it.
have() {
    no_leak_check "$RTCL" devices --api "$1" >"$tmp/devices_$1.txt" 2>&1
}

# entry_ok FILE: the file is a whole entry (kernel_cache.h's header: the
# magic, and a payload whose size and FNV-1a checksum match).
entry_ok() {
    python3 - "$1" <<'EOF'
import struct, sys
d = open(sys.argv[1], "rb").read()
def fnv(b):
    h = 0xcbf29ce484222325
    for x in b: h = ((h ^ x) * 0x100000001b3) & 0xffffffffffffffff
    return h
ok = len(d) > 48 and d[:8] == b"rtclkc1\n"
if ok:
    size, check = struct.unpack("<QQ", d[32:48])
    ok = size == len(d) - 48 and check == fnv(d[48:])
sys.exit(0 if ok else 1)
EOF
}

# refused FILE: keeps the header's key, replaces the payload by 4096 bytes
# no driver takes, with a size and checksum that match (so the driver itself
# must refuse it, not our checksum).
refused() {
    python3 - "$1" <<'EOF'
import struct, sys
d = open(sys.argv[1], "rb").read()
def fnv(b):
    h = 0xcbf29ce484222325
    for x in b: h = ((h ^ x) * 0x100000001b3) & 0xffffffffffffffff
    return h
body = bytes((i * 7 + 3) & 0xff for i in range(4096))
open(sys.argv[1], "wb").write(d[:32] + struct.pack("<QQ", len(body), fnv(body)) + body)
EOF
}

# quiet NAME FILE: FILE (a command's stderr) holds only rtcl's "wrote" line.
quiet() {
    checks=$((checks + 1))
    if grep -v -E '^wrote ' "$2" | grep -q .; then
        echo "FAIL: $1: stderr is not quiet:"; cat "$2"; fails=$((fails + 1))
    fi
}

# same NAME A B: the images are byte-identical.
same() {
    checks=$((checks + 1))
    cmp -s "$2" "$3" || { echo "FAIL: $1: image differs from the cold cache's"; fails=$((fails + 1)); }
}

# PoCL's own kernel cache, shared by the runs here: a build from source
# after a damaged entry then costs little (ours is what is tested).
export POCL_CACHE_DIR=$tmp/pocl
ran=0
for api in opencl vulkan; do
    if ! have $api; then
        echo "skipped $api: no $api device: $(head -1 "$tmp/devices_$api.txt")"
        continue
    fi
    ran=1
    kind=$([ $api = opencl ] && echo cl || echo vk)
    # A scene with secondary rays (the wavefront kernels too on a GPU).
    render() { # render OUT ENV...: rtcl under env ENV..., stderr into $tmp/err.txt
        local out=$1
        shift
        no_leak_check env "$@" "$RTCL" render builtin:cornell --width 64 \
            --height 36 --backend $api -o "$out" 2>"$tmp/err.txt" || {
            echo "FAIL: $api render into $out: $(cat "$tmp/err.txt")"; fails=$((fails + 1))
        }
    }
    c=$tmp/cache_$api
    render "$tmp/${api}_cold.png" RTCL_CACHE_DIR="$c"
    quiet "$api cold" "$tmp/err.txt"
    entry=$(ls "$c"/$kind-*.bin 2>/dev/null | head -1)
    checks=$((checks + 1))
    if [ -z "$entry" ] || ! entry_ok "$entry"; then
        echo "FAIL: $api: no whole cache entry after a cold run: $(ls -la "$c" 2>&1)"
        fails=$((fails + 1))
        continue
    fi
    # Warm: the entry is used and left as it is.
    sum=$(cksum <"$entry")
    render "$tmp/${api}_warm.png" RTCL_CACHE_DIR="$c"
    quiet "$api warm" "$tmp/err.txt"
    same "$api warm" "$tmp/${api}_cold.png" "$tmp/${api}_warm.png"
    checks=$((checks + 1))
    [ "$(cksum <"$entry")" = "$sum" ] || { echo "FAIL: $api: a warm run rewrote the entry"; fails=$((fails + 1)); }
    # Damaged entries: garbage, truncated, a payload the driver refuses.
    for damage in garbage truncated refused; do
        case $damage in
        garbage) head -c "$(wc -c <"$entry")" /dev/urandom >"$entry" ;;
        truncated) head -c 100 "$entry" >"$tmp/t" && mv "$tmp/t" "$entry" ;;
        refused) refused "$entry" ;;
        esac
        render "$tmp/${api}_$damage.png" RTCL_CACHE_DIR="$c"
        quiet "$api $damage entry" "$tmp/err.txt"
        same "$api $damage entry" "$tmp/${api}_cold.png" "$tmp/${api}_$damage.png"
        checks=$((checks + 1))
        entry_ok "$entry" || { echo "FAIL: $api: the $damage entry was not replaced"; fails=$((fails + 1)); }
        render "$tmp/${api}_after_$damage.png" RTCL_CACHE_DIR="$c"
        same "$api after the $damage entry" "$tmp/${api}_cold.png" "$tmp/${api}_after_$damage.png"
    done
    checks=$((checks + 1))
    [ "$(ls "$c" | wc -l)" = 1 ] || { echo "FAIL: $api: stray files in the cache: $(ls "$c")"; fails=$((fails + 1)); }

    # The folder rules: XDG_CACHE_HOME/rtcl, else HOME/.cache/rtcl; off (the
    # drivers may keep their own caches there: PoCL, Mesa).
    mkdir -p "$tmp/home_$api"
    render "$tmp/x.png" -u RTCL_CACHE_DIR XDG_CACHE_HOME="$tmp/xdg_$api" HOME="$tmp/home_$api"
    checks=$((checks + 1))
    ls "$tmp/xdg_$api"/rtcl/$kind-*.bin >/dev/null 2>&1 ||
        { echo "FAIL: $api: nothing in XDG_CACHE_HOME/rtcl"; fails=$((fails + 1)); }
    render "$tmp/x.png" -u RTCL_CACHE_DIR -u XDG_CACHE_HOME HOME="$tmp/home_$api"
    checks=$((checks + 1))
    ls "$tmp/home_$api"/.cache/rtcl/$kind-*.bin >/dev/null 2>&1 ||
        { echo "FAIL: $api: nothing in HOME/.cache/rtcl"; fails=$((fails + 1)); }
    for off in off OFF 0 none; do
        mkdir -p "$tmp/home_off"
        render "$tmp/${api}_off.png" RTCL_CACHE_DIR="$off" XDG_CACHE_HOME="$tmp/xdg_off" HOME="$tmp/home_off"
        quiet "$api RTCL_CACHE_DIR=$off" "$tmp/err.txt"
        same "$api RTCL_CACHE_DIR=$off" "$tmp/${api}_cold.png" "$tmp/${api}_off.png"
        checks=$((checks + 1))
        [ ! -e "$tmp/home_off/.cache/rtcl" ] && [ ! -e "$tmp/xdg_off/rtcl" ] && [ ! -e "$off" ] ||
            { echo "FAIL: $api: RTCL_CACHE_DIR=$off wrote a cache"; fails=$((fails + 1)); }
    done
    # A folder that cannot be made: not an error, no message.
    : >"$tmp/a_file"
    render "$tmp/${api}_bad.png" RTCL_CACHE_DIR="$tmp/a_file/sub"
    quiet "$api unusable folder" "$tmp/err.txt"
    same "$api unusable folder" "$tmp/${api}_cold.png" "$tmp/${api}_bad.png"
done
[ $ran = 1 ] || { echo "skipped: no OpenCL device and no Vulkan device"; exit 77; }

# The compile notice (OpenCL): one line when stderr is a terminal and the
# kernels are compiled, none on a cache hit, never on a pipe.
if have opencl; then
    RTCL_CACHE_DIR=$tmp/notice_pipe "$RTCL" render builtin:cornell --width 16 --height 8 \
        --backend opencl -o "$tmp/n.png" 2>"$tmp/err.txt"
    quiet "a cold cache on a pipe" "$tmp/err.txt"
    if command -v script >/dev/null && script -q -c true /dev/null >/dev/null 2>&1; then
        for run in cold warm; do
            RTCL_CACHE_DIR=$tmp/notice script -q -c "'$RTCL' render builtin:cornell --width 16 \
                --height 8 --backend opencl -o '$tmp/n.png'" /dev/null >"$tmp/tty_$run.txt" 2>&1
        done
        checks=$((checks + 2))
        [ "$(grep -c 'rtcl render: compiling the OpenCL kernels for .* (once; cached in .*/notice)' \
            "$tmp/tty_cold.txt")" = 1 ] ||
            { echo "FAIL: no compile notice on a terminal: $(cat "$tmp/tty_cold.txt")"; fails=$((fails + 1)); }
        ! grep -q 'compiling' "$tmp/tty_warm.txt" ||
            { echo "FAIL: a compile notice on a cache hit: $(cat "$tmp/tty_warm.txt")"; fails=$((fails + 1)); }
    else
        echo "note: no script(1): the terminal notice is not checked"
    fi
fi
finish
