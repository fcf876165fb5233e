#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# add_spdx.sh - gives every tracked source file that lacks it the line
# "SPDX-License-Identifier: Apache-2.0" (LICENSE), in the file's comment
# syntax, as its first line, or its second after a "#!" line. Idempotent: a
# file that has the identifier in its first two lines is left as it is.
#   tools/add_spdx.sh [--check] [DIR]   (DIR: a git checkout, default the repository)
# --check changes nothing: it lists the files that lack the line and exits 1
# if there is one (tests/license_check.sh).
set -euo pipefail
check=0
if [ "${1:-}" = "--check" ]; then check=1; shift; fi
dir=${1:-$(dirname "$0")/..}
cd "$dir"
id="SPDX-License-Identifier: Apache-2.0"

# The files: C, C++, OpenCL C, GLSL, the X-macro tables, shell, Python, CMake.
rt_spdx_files() {
    git ls-files -z -- '*.c' '*.h' '*.cpp' '*.cl' '*.glsl' '*.comp' '*.def' '*.sh' '*.py' \
        '*.cmake' '*CMakeLists.txt'
}

missing=0
while IFS= read -r -d '' f; do
    [ -f "$f" ] || continue # deleted in the work tree
    if head -n 2 -- "$f" | grep -q 'SPDX-License-Identifier:'; then continue; fi
    missing=$((missing + 1))
    if [ $check = 1 ]; then echo "$f"; continue; fi
    case "$f" in
    *.sh | *.py | *.cmake | *CMakeLists.txt) line="# $id" ;;
    *) line="/* $id */" ;;
    esac
    tmp="$f.spdx-tmp"
    if head -n 1 -- "$f" | grep -q '^#!'; then
        { head -n 1 -- "$f"; echo "$line"; tail -n +2 -- "$f"; } >"$tmp"
    else
        { echo "$line"; cat -- "$f"; } >"$tmp"
    fi
    chmod --reference="$f" "$tmp"
    mv -- "$tmp" "$f"
done < <(rt_spdx_files)

if [ $check = 1 ]; then
    [ $missing = 0 ] || { echo "$missing file(s) lack '$id' (run tools/add_spdx.sh)"; exit 1; }
else
    echo "add_spdx.sh: $missing file(s) given the SPDX line"
fi
