# SPDX-License-Identifier: Apache-2.0
# check_public_api.sh MAP OBJECT_DIR - the Python extension module calls the
# library through rt.h alone: every rt_ function its own objects (the .o files
# under OBJECT_DIR, before the static library is linked in) leave undefined
# is one that librtcl.so exports (MAP: the version script written from rt.h).
set -euo pipefail
map=$1
dir=$2
mapfile -t objects < <(find "$dir" -name '*.o' | sort)
[ "${#objects[@]}" -gt 0 ] || { echo "FAIL: no object files under $dir"; exit 1; }
public=$(sed -n 's/^ *\(rt_[A-Za-z0-9_]*\);$/\1/p' "$map" | sort -u)
[ -n "$public" ] || { echo "FAIL: no public functions in $map"; exit 1; }
used=$(nm -u "${objects[@]}" | awk '{print $NF}' | grep '^rt_' | sort -u)
[ -n "$used" ] || { echo "FAIL: the module calls no rt_ function (wrong objects?)"; exit 1; }
outside=$(comm -23 <(echo "$used") <(echo "$public"))
if [ -n "$outside" ]; then
    echo "FAIL: the Python module calls functions outside rt.h:"
    echo "$outside"
    exit 1
fi
echo "the Python module calls $(echo "$used" | wc -l) functions, all of rt.h"
