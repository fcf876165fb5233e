#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""check_hits.py CASEDIR HITSDIR LABEL [--strict] - compares the hit files
HITSDIR/NAME.hits written by 'rtcl trace' with the exact expectations of
CASEDIR/manifest.json (gen_cases.py) and prints per category: rays, leaks
(a required hit missed, or a hit on a surface behind the required one),
false hits (a required miss hit), wrong primitives
(a hit on a primitive outside the allowed set: degenerate, behind the nearest,
or not the one the tie rule picks), t out of bound (grazing rays), maximum and
mean relative error of t and maximum error of the barycentrics, and how many
'either' rays hit. The last line is the summary.

With --strict the exit status is 1 when any leak, false hit, wrong primitive
or t out of bound was found (the watertight default must have none); without
it the failures are only reported (the other triangle tests). --json=FILE
also writes the per-category figures (and their totals under "total") to
FILE, for the speed-against-error study (bench/study_tri_tests.sh), with the
median, 90th and 99th percentiles of t's relative error (bench/tri_t_error.sh).
"""
import json
import os
import sys
from fractions import Fraction as Fr


def parse_q(s):
    return Fr(s)


def main():
    args = [a for a in sys.argv[1:] if not a.startswith('--')]
    strict = '--strict' in sys.argv
    json_out = next((a[len('--json='):] for a in sys.argv[1:] if a.startswith('--json=')), None)
    if len(args) != 3:
        print(__doc__)
        return 2
    casedir, hitsdir, label = args
    with open(os.path.join(casedir, 'manifest.json')) as f:
        manifest = json.load(f)
    stats, order, problems = {}, [], []
    for case in manifest['cases']:
        path = os.path.join(hitsdir, case['name'] + '.hits')
        try:
            with open(path) as f:
                lines = [l.split() for l in f if l.strip()]
        except OSError as e:
            print('%s: %s' % (label, e))
            return 2
        if len(lines) != len(case['expect']):
            print('%s: %s has %d lines for %d rays' % (label, path, len(lines), len(case['expect'])))
            return 2
        cat = case['category']
        if cat not in stats:
            order.append(cat)
            stats[cat] = dict(rays=0, leaks=0, false=0, prim=0, tbound=0, terr_max=0.0, terr_sum=0.0,
                              terr_n=0, bary=0.0, either=0, either_hit=0, must=0, terrs=[])
        s = stats[cat]
        for i, (e, h) in enumerate(zip(case['expect'], lines)):
            s['rays'] += 1
            s['must'] += e['hit'] == 'must'
            hit = h[0] == '1'
            what = None
            if e['hit'] == 'either':
                s['either'] += 1
                s['either_hit'] += hit
            if e['hit'] == 'must' and not hit:
                s['leaks'] += 1
                what = 'leak'
            elif e['hit'] == 'miss' and hit:
                s['false'] += 1
                what = 'false hit (prim %s, t %s)' % (h[4], h[1])
            elif hit:
                prims = e['prims']
                far = max((parse_q(x[0]) for x in prims.values()), default=None)
                if h[4] not in prims and e['hit'] == 'must' and Fr(float(h[1])) > far * (1 + Fr(1, 2**16)):
                    s['leaks'] += 1  # through the surface to one behind it
                    what = 'leak through to prim %s at t %s' % (h[4], h[1])
                elif h[4] not in prims:
                    s['prim'] += 1
                    what = 'prim %s not in %s' % (h[4], sorted(prims, key=int))
                elif not e.get('approx_t') and '--any-hit' not in case['flags']:
                    t, u, v = (parse_q(x) for x in prims[h[4]])
                    err = abs(Fr(float(h[1])) - t) / abs(t) if t else abs(Fr(float(h[1])))
                    err = float(err)
                    s['terr_max'] = max(s['terr_max'], err)
                    s['terr_sum'] += err
                    s['terr_n'] += 1
                    s['terrs'].append(err)
                    s['bary'] = max(s['bary'], float(abs(Fr(float(h[2])) - u)),
                                    float(abs(Fr(float(h[3])) - v)))
                    if 't_tol' in e and err > e['t_tol']:
                        s['tbound'] += 1
                        what = 't error %.3g > bound %.3g' % (err, e['t_tol'])
            if what:
                problems.append('%s ray %d (%s): %s' % (case['name'], i + 1, e.get('note', ''), what))
    head = '%-20s %6s %6s %6s %6s %6s %10s %10s %10s %9s' % (
        'category', 'rays', 'leaks', 'false', 'prim', 't>tol', 't max rel', 't mean rel',
        'bary max', 'either')
    print('== %s' % label)
    print(head)
    tot = dict(rays=0, must=0, leaks=0, false=0, prim=0, tbound=0)
    for cat in order:
        s = stats[cat]
        for k in tot:
            tot[k] += s[k]
        print('%-20s %6d %6d %6d %6d %6d %10.3g %10.3g %10.3g %9s' % (
            cat, s['rays'], s['leaks'], s['false'], s['prim'], s['tbound'], s['terr_max'],
            s['terr_sum'] / s['terr_n'] if s['terr_n'] else 0.0, s['bary'],
            '%d/%d' % (s['either_hit'], s['either'])))
    for p in problems[:12]:
        print('  ' + p)
    if len(problems) > 12:
        print('  ... and %d more' % (len(problems) - 12))
    if json_out:
        figures = {}
        for cat in order:
            s = dict(stats[cat])
            errs = sorted(s.pop('terrs'))
            s['terr_mean'] = s['terr_sum'] / s['terr_n'] if s['terr_n'] else 0.0
            # The distribution of t's relative error (issue 26: beside the other tests).
            for q in (50, 90, 99):
                s['terr_p%d' % q] = errs[min(len(errs) - 1, len(errs) * q // 100)] if errs else 0.0
            figures[cat] = s
        figures['total'] = tot
        with open(json_out, 'w') as f:
            json.dump({'label': label, 'categories': order, 'figures': figures}, f, indent=1)
    bad = tot['leaks'] + tot['false'] + tot['prim'] + tot['tbound']
    print('SUMMARY %s: %d rays, %d leaks, %d false hits, %d wrong prims, %d t out of bound: %s' % (
        label, tot['rays'], tot['leaks'], tot['false'], tot['prim'], tot['tbound'],
        ('FAIL' if strict else 'reported') if bad else 'ok'))
    return 1 if strict and bad else 0


if __name__ == '__main__':
    sys.exit(main())
