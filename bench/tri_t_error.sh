#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# tri_t_error.sh BUILD_DIR OUT_DIR [BACKEND] - the distribution of t's relative error of
# the four triangle tests on the long-triangle cases of the robustness suite (issue 26
# item 5): sliver quads 1 to 1e5 long near and far from the origin, the closed cylinder
# 2e4 long (rays from its axis), the terrain strip; and on the closed-mesh categories
# (rays through shared vertices and edges). Each t against its exact rational value
# (tests/robust/gen_cases.py); rtcl trace on BACKEND (default cpu, the oracle).
# Prints a Markdown table per set: misses of required hits (leaks), the maximum, median
# and 99th percentile of |t - t*| / t*; writes OUT_DIR/t_error.md.
set -euo pipefail
build=${1:?usage: tri_t_error.sh BUILD_DIR OUT_DIR [BACKEND]}
out=${2:?usage: tri_t_error.sh BUILD_DIR OUT_DIR [BACKEND]}
backend=${3:-cpu}
root=$(cd "$(dirname "$0")/.." && pwd)
tests="watertight mt pluecker badouel"
mkdir -p "$out"

# The robustness cases (generated once per version of the generator).
. "$root/bench/robust_cases.sh"
robust_cases "$build" "$root"
# One row per long-triangle case (its category renamed to its name), one per closed-mesh
# category; closest-hit queries only (check_hits measures no t on any-hit queries).
mkdir -p "$out/cases"
names=$(python3 - "$cases/manifest.json" "$out/cases/manifest.json" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
closed = ('closed_vertex_edge', 'moved_1e3', 'moved_1e5', 'moved_1e6', 'scaled_1e-4', 'scaled_1e5')
keep = []
for c in m['cases']:
    if '--any-hit' in c['flags']:
        continue
    if c['category'] == 'long_triangles':
        c['category'] = c['name']
    elif c['category'] not in closed:
        continue
    keep.append(c)
m['cases'] = keep
json.dump(m, open(sys.argv[2], 'w'))
for c in keep:
    print(c['name'], ' '.join(c['flags']))
PY
)
for t in $tests; do
    mkdir -p "$out/hits-$t"
    while read -r name flags; do
        # shellcheck disable=SC2086
        "$build/rtcl" trace "$cases/$name.obj" --rays "$cases/$name.rays" \
            --out "$out/hits-$t/$name.hits" --backend "$backend" --tri-test "$t" $flags >/dev/null
    done <<<"$names"
    python3 "$root/tests/robust/check_hits.py" "$out/cases" "$out/hits-$t" "$backend/$t" \
        --json="$out/err-$t.json" >/dev/null
done

python3 - "$out" "$backend" $tests <<'PY' | tee "$out/t_error.md"
import json, sys
out, backend, tests = sys.argv[1], sys.argv[2], sys.argv[3:]
figs = {t: json.load(open('%s/err-%s.json' % (out, t))) for t in tests}
cats = figs[tests[0]]['categories']
print('Backend `%s`; per test: misses of required hits / max / median / 99th percentile of '
      't\'s relative error.\n' % backend)
print('| case | rays | ' + ' | '.join(tests) + ' |')
print('|---|---:|' + '---|' * len(tests))
for c in cats:
    cells = []
    for t in tests:
        f = figs[t]['figures'][c]
        cells.append('%d / %.2g / %.2g / %.2g' % (f['leaks'], f['terr_max'], f['terr_p50'], f['terr_p99']))
    print('| %s | %d | %s |' % (c, figs[tests[0]]['figures'][c]['rays'], ' | '.join(cells)))
PY
