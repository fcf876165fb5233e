# SPDX-License-Identifier: Apache-2.0
# install_check.sh BUILD PYTHON SITE - `cmake --install` puts the package rtcl
# where the interpreter finds it: installed to a fresh prefix, it imports from
# PREFIX/SITE (SITE: RT_PYTHON_INSTALL_DIR, relative to the prefix) with no
# path into the build tree, from another folder, and answers a query.
set -euo pipefail
build=$1
python=$2
site=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" > "$tmp/install.log" ||
    { echo "FAIL: cmake --install:"; tail -20 "$tmp/install.log"; exit 1; }
case $site in /*) dir=$site ;; *) dir="$tmp/prefix/$site" ;; esac
[ -f "$dir/rtcl/__init__.py" ] || { echo "FAIL: no rtcl package under $dir"; exit 1; }
cd "$tmp"
env -u PYTHONPATH PYTHONPATH="$dir" PYTHONDONTWRITEBYTECODE=1 "$python" - "$dir" <<'PY'
import os, sys
import numpy as np
import rtcl
where = os.path.dirname(rtcl.__file__)
assert where.startswith(sys.argv[1]), "imported from %s" % where
s = rtcl.Scene()
s.add_mesh(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]]), [[0, 1, 2]])
h = s.cast_rays(np.array([[0.25, 0.25, 1, 0, 0, -1]]))
assert h["t_hit"][0] == 1.0
print("rtcl %s installed in %s: a query answered" % (rtcl.__version__, where))
PY
