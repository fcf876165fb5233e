#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# cli_shared_symbols.sh - librtcl.so exports the public API and nothing else
# (issue 19): every defined dynamic symbol of the shared library is a
# function declared in rt.h, and every function declared in rt.h is
# exported (a user program links against it). The library's inside (the
# builders, the tracers, the formats) stays local; rtcl and the tests link
# the static library for it. rt.h is read here on its own (comments
# removed, every rt_xxx followed by '('), not through the build's list.
source "$RT_SOURCE_DIR/tests/shell_check.sh"
lib=$RT_BINARY_DIR/librtcl.so
command -v nm >/dev/null || { echo "skipped: nm (binutils) is needed"; exit 77; }
command -v python3 >/dev/null || { echo "skipped: python3 is needed"; exit 77; }
[ -e "$lib" ] || { echo "FAIL: no $lib"; exit 1; }
nm -D --defined-only "$lib" >"$tmp/nm.txt" || { echo "FAIL: nm -D $lib"; exit 1; }
python3 - "$RT_SOURCE_DIR/host/rt.h" "$tmp/nm.txt" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
text = re.sub(r"//[^\n]*", "", text)
public = set(re.findall(r"\b(rt_\w+)\s*\(", text))
assert len(public) >= 10, "too few functions found in rt.h: %s" % sorted(public)
exported = set()
for line in open(sys.argv[2]):
    f = line.split()
    if len(f) >= 3 and f[1] not in ("A",):  # A: a version node's name, not code or data
        exported.add(f[2].split("@")[0])
extra = sorted(exported - public)
missing = sorted(public - exported)
if extra:
    print("FAIL: librtcl.so exports %d symbols that rt.h does not declare: %s%s"
          % (len(extra), " ".join(extra[:30]), " ..." if len(extra) > 30 else ""))
if missing:
    print("FAIL: rt.h declares functions librtcl.so does not export: %s" % " ".join(missing))
print("%d public functions, %d exported symbols" % (len(public), len(exported)))
sys.exit(1 if extra or missing else 0)
PY
