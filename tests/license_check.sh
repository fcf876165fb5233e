#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# license_check.sh - every tracked source file carries the Apache-2.0 SPDX
# line (issue 30, item 1; tools/add_spdx.sh adds it), and add_spdx.sh itself
# works on a scratch repository: each kind of file gets the line in its
# comment syntax, after a "#!" line where there is one, a second run changes
# nothing, and --check fails before and passes after.
source "$RT_SOURCE_DIR/tests/shell_check.sh"
src=$RT_SOURCE_DIR
script="$src/tools/add_spdx.sh"
checks=$((checks + 1))
[ -f "$src/LICENSE" ] && grep -q 'Apache License' "$src/LICENSE" &&
    grep -q 'Version 2.0, January 2004' "$src/LICENSE" ||
    { echo "FAIL: LICENSE is not the Apache-2.0 text"; fails=$((fails + 1)); }

# The script on a scratch repository.
if command -v git >/dev/null; then
    s="$tmp/scratch"
    mkdir -p "$s/sub"
    printf '/* a.c - x */\nint a;\n' >"$s/a.c"
    printf '#ifndef B_H\n#define B_H\n#endif\n' >"$s/sub/b.h"
    printf '#version 450\nvoid main() {}\n' >"$s/c.comp"
    printf '#!/bin/sh\necho hi\n' >"$s/d.sh"
    printf 'print(1)\n' >"$s/e.py"
    printf 'project(x)\n' >"$s/CMakeLists.txt"
    printf 'set(x 1)\n' >"$s/f.cmake"
    printf '/* SPDX-License-Identifier: Apache-2.0 */\nint g;\n' >"$s/g.c"
    printf 'not a source\n' >"$s/h.txt"
    printf 'int untracked;\n' >"$s/u.c"
    chmod +x "$s/d.sh"
    git -C "$s" init -q && git -C "$s" add a.c sub/b.h c.comp d.sh e.py CMakeLists.txt f.cmake g.c h.txt
    expect 1 '^a\.c$' -- bash "$script" --check "$s"
    expect 0 '7 file\(s\) given' -- bash "$script" "$s"
    # line N of FILE is TEXT
    line_is() {
        checks=$((checks + 1))
        local got
        got=$(sed -n "$2p" "$s/$1")
        [ "$got" = "$3" ] || { echo "FAIL: $1 line $2 is '$got', expected '$3'"; fails=$((fails + 1)); }
    }
    c='/* SPDX-License-Identifier: Apache-2.0 */'
    h='# SPDX-License-Identifier: Apache-2.0'
    line_is a.c 1 "$c"; line_is a.c 2 '/* a.c - x */'; line_is a.c 3 'int a;'
    line_is sub/b.h 1 "$c"; line_is c.comp 1 "$c"; line_is c.comp 2 '#version 450'
    line_is d.sh 1 '#!/bin/sh'; line_is d.sh 2 "$h"; line_is d.sh 3 'echo hi'
    line_is e.py 1 "$h"; line_is CMakeLists.txt 1 "$h"; line_is f.cmake 1 "$h"
    line_is g.c 1 "$c"; line_is g.c 2 'int g;'
    line_is h.txt 1 'not a source'; line_is u.c 1 'int untracked;'
    checks=$((checks + 1))
    [ -x "$s/d.sh" ] || { echo "FAIL: d.sh lost its execute bit"; fails=$((fails + 1)); }
    sum=$(cat "$s"/a.c "$s"/sub/b.h "$s"/d.sh | cksum)
    expect 0 ' 0 file\(s\) given' -- bash "$script" "$s"
    checks=$((checks + 1))
    [ "$sum" = "$(cat "$s"/a.c "$s"/sub/b.h "$s"/d.sh | cksum)" ] ||
        { echo "FAIL: a second run changed the files"; fails=$((fails + 1)); }
    expect 0 '' -- bash "$script" --check "$s"
fi

# The project's own files.
if git -C "$src" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    expect 0 '' -- bash "$script" --check "$src"
else
    echo "note: $src is not a git checkout: its files are not checked"
fi
finish
