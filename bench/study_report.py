#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""study_report.py STUDY DATA_DIR OUT_DIR --command CMD [options] - writes the
report section OUT_DIR/STUDY.md and the plot OUT_DIR/plots/STUDY.png of one
speed-against-error study (issue 7) from what its script measured into
DATA_DIR (bench/study_tri_tests.sh, study_builders.sh, study_opencl_options.sh).

STUDY: tri_tests, builders or opencl_options. Every number in the section is
read from DATA_DIR or computed here from it (the Pareto fronts too); the
sentences that read the tables are generated from the same numbers. Python's
standard library only; the plot is drawn by gnuplot (pngcairo where it works,
else png).
"""
import argparse
import json
import math
import os
import subprocess
import sys

# ---- shared helpers ------------------------------------------------------------


def read_tsv(path):
    with open(path) as f:
        lines = [l.rstrip('\n').split('\t') for l in f if l.strip()]
    head = lines[0]
    return [dict(zip(head, l)) for l in lines[1:]]


def pareto(rows, objectives):
    """Flags of the rows no other row dominates. objectives: (function of a
    row, 'min' or 'max') pairs; a row dominates another when it is at least as
    good in every objective and better in one."""
    def better_eq(a, b, sense):
        return a <= b if sense == 'min' else a >= b

    def strictly(a, b, sense):
        return a < b if sense == 'min' else a > b
    vals = [[f(r) for f, _ in objectives] for r in rows]
    senses = [s for _, s in objectives]
    flags = []
    for i, vi in enumerate(vals):
        dominated = False
        for j, vj in enumerate(vals):
            if j == i:
                continue
            if all(better_eq(vj[k], vi[k], senses[k]) for k in range(len(senses))) and \
                    any(strictly(vj[k], vi[k], senses[k]) for k in range(len(senses))):
                dominated = True
                break
        flags.append(not dominated)
    return flags


def md_table(head, rows, right=None):
    """A markdown table; columns listed in right are right-aligned."""
    right = right or set()
    out = ['| ' + ' | '.join(head) + ' |',
           '|' + '|'.join('---:' if i in right else '---' for i in range(len(head))) + '|']
    for r in rows:
        out.append('| ' + ' | '.join(str(c) for c in r) + ' |')
    return '\n'.join(out)


def sci(x):
    if x == 0:
        return '0'
    if math.isinf(x):
        return 'inf'
    return '%.2e' % x


def ms(x):
    return '%.1f' % x if x >= 100 else '%.2f' % x if x >= 1 else '%.3f' % x


def pct(a, b):
    return 100.0 * (a - b) / b if b else 0.0


def scene_label(path, root, shared):
    path = os.path.abspath(path)
    if path.startswith(shared + os.sep):
        return '$S/' + os.path.relpath(path, shared)
    if path.startswith(root + os.sep):
        return os.path.relpath(path, root)
    return path


def short_scene(path):
    return os.path.basename(path)


def scenes_of(data):
    out, i = [], 1
    while os.path.exists(os.path.join(data, 'scene%d.tsv' % i)):
        with open(os.path.join(data, 'scene%d.name' % i)) as f:
            name = f.read().strip()
        out.append((name, read_tsv(os.path.join(data, 'scene%d.tsv' % i))))
        i += 1
    return out


def gnuplot_terminal():
    for term in ('pngcairo', 'png'):
        try:
            r = subprocess.run(['gnuplot', '-e', 'set terminal %s' % term], capture_output=True,
                               text=True, timeout=30)
        except (OSError, subprocess.TimeoutExpired):
            return None
        if r.returncode == 0 and not r.stderr.strip():
            return term
    return None


def gp_str(s):
    return '"' + s.replace('\\', '\\\\').replace('"', '\\"') + '"'


def write_points(path, pts):
    """pts: (x, y, label) triples, one line each."""
    with open(path, 'w') as f:
        for x, y, label in pts:
            f.write('%.9g %.9g %s\n' % (x, y, gp_str(label)))


def spaced_labels(pts, front, logx, logy, gap_x=0.2, gap_y=0.07):
    """The points to label: the Pareto front's first, then any other whose
    place (axes scaled to [0, 1], log where the axis is) is farther than gap_x
    across or gap_y up or down from every point labelled so far (labels run to
    the right of their point), so that labels do not pile up."""
    def coords(p):
        x, y = p[0], p[1]
        return (math.log10(x) if logx and x > 0 else x, math.log10(y) if logy and y > 0 else y)
    cs = [coords(p) for p in pts]
    span = [max(c[k] for c in cs) - min(c[k] for c in cs) or 1.0 for k in (0, 1)]
    lo = [min(c[k] for c in cs) for k in (0, 1)]
    norm = [((c[0] - lo[0]) / span[0], (c[1] - lo[1]) / span[1]) for c in cs]
    order = [i for i in range(len(pts)) if front[i]] + [i for i in range(len(pts)) if not front[i]]
    chosen = []
    for i in order:
        if front[i] or all(abs(norm[i][0] - norm[j][0]) > gap_x or
                           abs(norm[i][1] - norm[j][1]) > gap_y for j in chosen):
            chosen.append(i)
    return [pts[i] for i in sorted(chosen)]


def axis_range(v, log, below, above, zero=False):
    """A range around the values v with room for labels: below and above are
    shares of the values' span (in decades on a log axis)."""
    if log:
        lo, hi = math.log10(min(v)), math.log10(max(v))
        span = max(hi - lo, 0.3)
        return 10 ** (lo - below * span), 10 ** (hi + above * span)
    lo, hi = min(v), max(v)
    span = hi - lo if hi > lo else (abs(hi) or 1.0) * 0.2
    # zero: the axis starts just below 0 (room for labels under points at 0).
    return (-0.1 * span if zero and lo >= 0 else lo - below * span), hi + above * span


# Vertical label offsets (character heights) of the levels label_levels
# assigns: above the point, below it, further above, further below.
LABEL_OFFSETS = (0.5, -0.8, 1.6, -1.9)


def label_levels(pts, logx, logy, gap_x=0.22, gap_y=0.06):
    """A level (LABEL_OFFSETS) per label so that labels whose points are close
    (axes scaled to [0, 1]; labels run to the right) do not print over each
    other: in x order, each takes the first level no close labelled point
    before it holds."""
    if not pts:
        return []
    def coords(p):
        return (math.log10(p[0]) if logx and p[0] > 0 else p[0],
                math.log10(p[1]) if logy and p[1] > 0 else p[1])
    cs = [coords(p) for p in pts]
    lo = [min(c[k] for c in cs) for k in (0, 1)]
    span = [max(c[k] for c in cs) - lo[k] or 1.0 for k in (0, 1)]
    norm = [((c[0] - lo[0]) / span[0], (c[1] - lo[1]) / span[1]) for c in cs]
    levels = [0] * len(pts)
    done = []
    for i in sorted(range(len(pts)), key=lambda i: norm[i][0]):
        taken = {levels[j] for j in done
                 if abs(norm[i][0] - norm[j][0]) < gap_x and abs(norm[i][1] - norm[j][1]) < gap_y}
        levels[i] = next((lv for lv in range(len(LABEL_OFFSETS)) if lv not in taken), 0)
        done.append(i)
    return levels


def panel(data_dir, key, pts, front, xlabel, ylabel, title, logx=False, logy=False, ymin0=False,
          label_all=False):
    """gnuplot commands for one panel: every point (grey), the Pareto front
    (red, connected in x order, larger) and the labels of the front and of the
    other points that have room (spaced_labels)."""
    all_path = os.path.join(data_dir, 'plot_%s_all.dat' % key)
    front_path = os.path.join(data_dir, 'plot_%s_front.dat' % key)
    label_path = os.path.join(data_dir, 'plot_%s_labels.dat' % key)
    write_points(all_path, pts)
    write_points(front_path, sorted((p for p, f in zip(pts, front) if f), key=lambda p: p[0]))
    labels = pts if label_all else spaced_labels(pts, front, logx, logy)
    levels = label_levels(labels, logx, logy)
    for lv in range(len(LABEL_OFFSETS)):
        write_points('%s.%d' % (label_path, lv), [p for p, l in zip(labels, levels) if l == lv])
    cmds = ['unset logscale', 'set title %s' % gp_str(title), 'set xlabel %s' % gp_str(xlabel),
            'set ylabel %s' % gp_str(ylabel), 'set grid', 'unset key',
            'set format x "%g"', 'set format y "%g"',
            'set xrange [%.9g:%.9g]' % axis_range([p[0] for p in pts], logx, 0.08, 0.35),
            'set yrange [%.9g:%.9g]' % axis_range([p[1] for p in pts], logy, 0.12, 0.15,
                                                  ymin0 and not logy)]
    if logx:
        cmds.append('set logscale x')
    if logy:
        cmds += ['set logscale y', 'set format y "%.0e"']
    cmds.append(
        'plot %s using 1:2 with points pt 7 ps 1.1 lc rgb "#7f7f7f" title "measured", '
        '%s using 1:2 with linespoints pt 7 ps 1.8 lw 2 lc rgb "#d62728" title "Pareto front", '
        '%s' % (gp_str(all_path), gp_str(front_path),
                ', '.join('%s using 1:2:3 with labels left offset 0.7,%.1f font ",9" notitle'
                          % (gp_str('%s.%d' % (label_path, lv)), dy)
                          for lv, dy in enumerate(LABEL_OFFSETS))))
    return cmds


def draw(out_png, data_dir, title, panels, cols, width, height):
    """panels: lists of gnuplot commands (one list per panel)."""
    term = gnuplot_terminal()
    if term is None:
        sys.exit('study_report.py: gnuplot with a png or pngcairo terminal is needed')
    rows = (len(panels) + cols - 1) // cols
    font = 'Sans,10' if term == 'pngcairo' else 'Sans 10'
    script = ['set terminal %s size %d,%d font %s noenhanced' % (term, width, height,
                                                                gp_str(font)),
              'set output %s' % gp_str(out_png),
              'set multiplot layout %d,%d title %s font ",12"'
              % (rows, cols, gp_str(title + ' - red, connected: the Pareto front of each '
                                    'panel\'s two axes; grey: the other points'))]
    for p in panels:
        script += p
    script.append('unset multiplot')
    gp = os.path.join(data_dir, 'plot.gp')
    with open(gp, 'w') as f:
        f.write('\n'.join(script) + '\n')
    r = subprocess.run(['gnuplot', gp], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit('study_report.py: gnuplot failed: %s' % r.stderr)


def no_data_plot(out_png, data_dir, text):
    term = gnuplot_terminal()
    if term is None:
        sys.exit('study_report.py: gnuplot with a png or pngcairo terminal is needed')
    gp = os.path.join(data_dir, 'plot.gp')
    with open(gp, 'w') as f:
        f.write('set terminal %s size 800,300 noenhanced\nset output %s\nunset border\nunset tics\n'
                'set label 1 %s at graph 0.5,0.5 center\nset xrange [0:1]\nset yrange [0:1]\n'
                'plot 2 notitle\n' % (term, gp_str(out_png), gp_str(text)))
    subprocess.run(['gnuplot', gp], check=True, capture_output=True)


# The Pareto fronts, the plots and the comparisons in the sentences use the
# min times: on a shared machine other work only ever adds time, so the
# least disturbed run is the best estimate of what the code costs; the
# medians stand beside them in the tables and measure the disturbance.
MIN_NOTE = ('Pareto fronts, plots and comparisons use the min times (other work on a shared '
            'machine only adds time, so the least disturbed run estimates the cost best); the '
            'medians beside them show how much the runs were disturbed.')


def machine(args):
    return ('%d threads for every peer on this %d-core machine' % (args.threads, os.cpu_count()))


def spread(rows, lo, mid):
    """The largest (median - min) / min over rows: how noisy the timings were."""
    return max((float(r[mid]) - float(r[lo])) / float(r[lo]) * 100.0 for r in rows
               if float(r[lo]) > 0)


def noise_note(args, noise, gap, what):
    """How to read a time difference gap (percent) given the spread noise."""
    if args.runs < 3:
        return ('with %d timed run(s) there is no spread to judge the noise by: read the times '
                'as rough' % args.runs)
    if abs(gap) <= noise:
        return '%s is within that noise' % what
    return '%s is larger than that spread' % what


def names(items):
    items = list(items)
    if not items:
        return 'none'
    if len(items) == 1:
        return items[0]
    return ', '.join(items[:-1]) + ' and ' + items[-1]


# ---- study a: triangle tests -------------------------------------------------------

TEST_LABEL = {'watertight': 'watertight', 'mt': 'Moller-Trumbore', 'pluecker': 'Pluecker',
              'badouel': 'Badouel/Wald'}


def tri_tests(args):
    data = args.data
    tests = ['watertight', 'mt', 'pluecker', 'badouel']
    leaks = {t: json.load(open(os.path.join(data, 'leaks-%s.json' % t))) for t in tests}
    cats = leaks['watertight']['categories']
    scenes = scenes_of(data)
    summary = {}
    for t in tests:
        fig = leaks[t]['figures']['total']
        rows = [next(r for r in tsv if r['test'] == t) for _, tsv in scenes]
        rays = sum(int(r['rays']) for r in rows)
        hits = sum(int(r['hits']) for r in rows)
        summary[t] = dict(
            leaks=fig['leaks'], must=fig['must'], closed_rays=fig['rays'],
            false=fig['false'], prim=fig['prim'],
            mrays_min=rays / sum(float(r['min_ms']) for r in rows) / 1e3,
            mrays_med=rays / sum(float(r['median_ms']) for r in rows) / 1e3,
            tmax=max(float(r['t_max_rel']) for r in rows),
            tmean=sum(float(r['t_mean_rel']) * int(r['hits']) for r in rows) / hits if hits else 0,
            sample=sum(int(r['sample']) for r in rows),
            decisive=sum(int(r['differ_decisive']) for r in rows),
            edge=sum(int(r['differ_edge']) for r in rows),
            edge_rays=sum(int(r['edge_rays']) for r in rows), rays=rays)
    trows = [summary[t] for t in tests]
    objectives = [(lambda s: s['mrays_min'], 'max'), (lambda s: s['leaks'], 'min'),
                  (lambda s: s['tmax'], 'min'), (lambda s: s['tmean'], 'min')]
    front = pareto(trows, objectives)
    scene_names = [scene_label(n, args.root, args.shared) for n, _ in scenes]
    s0 = summary['watertight']
    md = ['## Speed against error: triangle tests', '', '```', args.command, '```', '']
    md.append(
        'What is measured. *Leaks*: the closed-mesh categories of the robustness suite '
        '(`tests/robust/gen_cases.py`: %s; %d rays, %d of them must hit because they cross a '
        'closed surface exactly through a shared vertex or edge), traced by `rtcl trace` on the '
        'scalar oracle with each test; a leak is such a ray that misses, or passes through to a '
        'surface behind (`tests/robust/check_hits.py`, the exact expectations of '
        '`docs/ROBUSTNESS.md`). *Speed*: the primary rays of %s at %dx%d (%d rays in all), '
        '`rt_trace_rays_with` on the scalar oracle, %s; each test traces once as a warm-up (the '
        'first also builds the BVH; not counted), then %d timed run(s) interleaved test by test; '
        'Mrays/s is all scenes\' rays over the sum of the min (or median) times. *Error of t*: for '
        'every hit, t recomputed in double precision for the triangle the test reported (the plane '
        'crossing from the same float inputs), relative error, maximum and mean over all hits. '
        '*Closest hit*: on %d rays per scene (every k-th), a double-precision brute-force '
        'reference over every triangle; a test differs when it misses where the reference hits '
        'or the other way round, or hits a triangle whose double-precision t is more than 2^-16 '
        'away from the reference\'s; "at an edge" are the rays whose reference changes when '
        'every triangle grows or shrinks by 2^-16 in barycentric coordinates (%d of the %d '
        'sampled rays here), the others are decisive (`bench/bench_tri_study.c`).'
        % (', '.join('`%s`' % c for c in cats), s0['closed_rays'], s0['must'],
           names('`%s`' % n for n in scene_names), args.width, args.height, s0['rays'],
           machine(args), args.runs, args.sample, s0['edge_rays'], s0['sample']))
    md.append('')
    head = ['test', 'leaks (of %d must-hit rays)' % s0['must'], 'Mrays/s (min / median time)',
            'max rel. error of t', 'mean rel. error of t',
            'closest hit differs: decisive / at an edge (of %d)' % s0['sample'], 'Pareto']
    rows = []
    for t, f in zip(tests, front):
        s = summary[t]
        rows.append([TEST_LABEL[t], s['leaks'], '%.2f / %.2f' % (s['mrays_min'], s['mrays_med']),
                     sci(s['tmax']), sci(s['tmean']), '%d / %d' % (s['decisive'], s['edge']),
                     'yes' if f else 'no'])
    md.append(md_table(head, rows, right={1, 2, 3, 4, 5}))
    md.append('')
    md.append('"Pareto": no other test is at least as good in all of Mrays/s (min time), leaks, '
              'maximum and mean error of t, and better in one. In the plot each panel marks the '
              'front of its own two axes. ' + MIN_NOTE)
    md.append('')
    md.append('![Triangle tests: Mrays/s against leaks and against the relative error of t, '
              'Pareto fronts marked](plots/tri_tests.png)')
    md.append('')
    head = ['scene', 'test', 'min ms', 'median ms', 'Mrays/s (min)', 'max rel. error of t',
            'mean rel. error of t', 'differs: decisive / at an edge']
    rows = []
    for (name, tsv), label in zip(scenes, scene_names):
        for r in tsv:
            rows.append([label, TEST_LABEL[r['test']], ms(float(r['min_ms'])),
                         ms(float(r['median_ms'])),
                         '%.2f' % (int(r['rays']) / float(r['min_ms']) / 1e3),
                         sci(float(r['t_max_rel'])), sci(float(r['t_mean_rel'])),
                         '%s / %s (of %s)' % (r['differ_decisive'], r['differ_edge'], r['sample'])])
    md.append('Per scene:')
    md.append('')
    md.append(md_table(head, rows, right={2, 3, 4, 5, 6, 7}))
    md.append('')
    head = ['category', 'rays', 'must hit'] + ['leaks: %s' % TEST_LABEL[t] for t in tests]
    rows = []
    for c in cats:
        f = leaks['watertight']['figures'][c]
        rows.append([c, f['rays'], f['must']] + [leaks[t]['figures'][c]['leaks'] for t in tests])
    md.append('Leaks per category (closed meshes; no false hit or wrong primitive counted here: '
              '%s):' % ', '.join('%s %d/%d' % (TEST_LABEL[t], summary[t]['false'], summary[t]['prim'])
                                 for t in tests))
    md.append('')
    md.append(md_table(head, rows, right=set(range(1, 3 + len(tests)))))
    md.append('')
    # Reading, generated from the numbers above.
    by_speed = sorted(tests, key=lambda t: -summary[t]['mrays_min'])
    fastest, slowest = by_speed[0], by_speed[-1]
    noise = max(spread(tsv, 'min_ms', 'median_ms') for _, tsv in scenes)
    gap = pct(summary[fastest]['mrays_min'], summary[slowest]['mrays_min'])
    tight = [TEST_LABEL[t] for t in tests if summary[t]['leaks'] == 0]
    leaky = sorted((t for t in tests if summary[t]['leaks']), key=lambda t: -summary[t]['leaks'])
    read = []
    if tight:
        read.append('%s %s no leak%s.' % (
            names(tight), 'has' if len(tight) == 1 else 'have',
            '; ' + names('%s %d' % (TEST_LABEL[t], summary[t]['leaks']) for t in leaky) +
            ' leak' if leaky else ''))
    else:
        read.append('Every test leaks: %s.' % names('%s %d' % (TEST_LABEL[t], summary[t]['leaks'])
                                                       for t in leaky))
    read.append('By min time %s was the fastest (%.2f Mrays/s) and %s the slowest (%.2f), '
                '%.1f%% apart; the median of one scene and test was up to %.1f%% above its '
                'minimum on this shared machine, so %s.' % (
                    TEST_LABEL[fastest], summary[fastest]['mrays_min'], TEST_LABEL[slowest],
                    summary[slowest]['mrays_min'], gap, noise,
                    noise_note(args, noise, gap, 'the gap')))
    by_err = sorted(tests, key=lambda t: summary[t]['tmax'])
    read.append('The largest relative error of t on real rays was %s\'s (%s), the smallest '
                'maximum %s\'s (%s); the means range from %s to %s.' % (
                    TEST_LABEL[by_err[-1]], sci(summary[by_err[-1]]['tmax']),
                    TEST_LABEL[by_err[0]], sci(summary[by_err[0]]['tmax']),
                    sci(min(summary[t]['tmean'] for t in tests)),
                    sci(max(summary[t]['tmean'] for t in tests))))
    dec = [t for t in tests if summary[t]['decisive']]
    read.append('On the decisive sampled rays %s.' % (
        'no test disagreed with the double-precision closest hit' if not dec else
        names('%s differed on %d' % (TEST_LABEL[t], summary[t]['decisive']) for t in dec)))
    read.append('On the Pareto front (all four criteria): %s.' % names(
        TEST_LABEL[t] for t, f in zip(tests, front) if f))
    md.append(' '.join(r[0].upper() + r[1:] for r in read))
    md.append('')
    with open(os.path.join(args.out, 'tri_tests.md'), 'w') as f:
        f.write('\n'.join(md))

    panels = []
    for key, ylabel, logy in (('leaks', 'leaks (closed-mesh rays that must hit)', False),
                              ('tmax', 'max relative error of t', True),
                              ('tmean', 'mean relative error of t', True)):
        pts = [(summary[t]['mrays_min'], max(summary[t][key], 1e-30) if logy else summary[t][key],
                TEST_LABEL[t]) for t in tests]
        fr = pareto(trows, [(lambda s: s['mrays_min'], 'max'), (lambda s, k=key: s[k], 'min')])
        panels.append(panel(data, key, pts, fr, 'Mrays/s (min time, all scenes)', ylabel,
                            'Mrays/s against %s' % ylabel.split(' (')[0], logy=logy,
                            ymin0=not logy, label_all=True))
    draw(os.path.join(args.out, 'plots', 'tri_tests.png'), data,
         'Triangle tests: speed against error (%d threads, cpu oracle)' % args.threads, panels, 3,
         1650, 520)


# ---- study b: builders ---------------------------------------------------------------


def setup_label(r):
    b, bins, leaf = r['builder'], r['bins'], r['leaf']
    if b == 'embree':
        return 'Embree, leaf %s' % leaf
    if b.startswith('thesis'):
        return '%s (%s bins, leaf %s)' % (b, bins, leaf)
    return 'sah, %s bins, leaf %s%s' % (bins, leaf, ' (default)' if (bins, leaf) == ('16', '10')
                                         else '')


def setup_short(r):
    b = r['builder']
    if b == 'embree':
        return 'embree'
    if b.startswith('thesis'):
        return b
    return 'sah %s/%s' % (r['bins'], r['leaf'])


def ranks(v):
    order = sorted(range(len(v)), key=lambda i: v[i])
    out = [0.0] * len(v)
    i = 0
    while i < len(order):
        j = i
        while j + 1 < len(order) and v[order[j + 1]] == v[order[i]]:
            j += 1
        for k in range(i, j + 1):
            out[order[k]] = (i + j) / 2.0
        i = j + 1
    return out


def spearman(a, b):
    ra, rb = ranks(a), ranks(b)
    ma, mb = sum(ra) / len(ra), sum(rb) / len(rb)
    num = sum((x - ma) * (y - mb) for x, y in zip(ra, rb))
    den = math.sqrt(sum((x - ma) ** 2 for x in ra) * sum((y - mb) ** 2 for y in rb))
    return num / den if den else 0.0


def builders(args):
    data = args.data
    scenes = scenes_of(data)
    md = ['## Speed against error: BVH builders', '', '```', args.command, '```', '']
    md.append(
        'What is measured (`bench/bench_builders.c`), per scene and setup: *build ms*, every mesh '
        'BVH of the scene built by the setup (the sum over meshes; `rt_bvh_build`, for Embree '
        '`rtcBuildBVH` alone at medium quality, branching factor 2, its build primitives prepared '
        'and its tree converted to our nodes outside the timer, which favours Embree slightly); '
        '*SAH*, `rt_bvh_measure` (Ct = 1, Ci = 2, areas relative to the root, triangle-weighted '
        'over meshes; Embree\'s tree converted, so measured the same way); *trace ms*, one frame of '
        'the thesis\'s benchmark set-up (primary and shadow rays, Phong; `rtcl render --direct`) at '
        '%dx%d through those trees, traced by the scalar oracle, so every tree is traced by the '
        'same code. Threads: thesis-scalar and thesis-neon are single-threaded setups (the '
        'thesis\'s setups 1 and 2); thesis-mt, sah and Embree build with %d threads; every frame '
        'is traced with %s. Each setup is built and traced once as a warm-up (not counted), then '
        '%d time(s), setups interleaved round by round; min and median. All setups use Ct = 1, '
        'Ci = 2; the SAH builder bins nodes under 64 primitives into at most 8 bins whatever the '
        'setting (`host/bvh_sah.c`), so its bin count acts on the larger nodes. "image differs" '
        'counts the pixels that are not the default build\'s image bit for bit: it must be 0 '
        '(closest hits have a total order, so the tree cannot change them).'
        % (args.width, args.height, args.threads, machine(args), args.runs))
    md.append('')
    panels = []
    read = []
    for name, tsv in scenes:
        label = scene_label(name, args.root, args.shared)
        obj = [(lambda r: float(r['build_min']), 'min'), (lambda r: float(r['sah']), 'min'),
               (lambda r: float(r['trace_min']), 'min')]
        front = pareto(tsv, obj)
        head = ['setup', 'build threads', 'build ms (min / median)', 'SAH', 'nodes',
                'trace ms (min / median)', 'Mrays/s (min)', 'image differs', 'Pareto']
        rows = []
        for r, f in zip(tsv, front):
            rows.append([setup_label(r), r['build_threads'],
                         '%s / %s' % (ms(float(r['build_min'])), ms(float(r['build_median']))),
                         '%.2f' % float(r['sah']), r['nodes'],
                         '%s / %s' % (ms(float(r['trace_min'])), ms(float(r['trace_median']))),
                         '%.2f' % (int(r['rays']) / float(r['trace_min']) / 1e3),
                         r['differ'], 'yes' if f else 'no'])
        md.append('`%s` (%s triangles, %s rays per frame):' % (label, tsv[0]['tris'],
                                                                 tsv[0]['rays']))
        md.append('')
        md.append(md_table(head, rows, right={1, 2, 3, 4, 5, 6, 7}))
        md.append('')
        # Panels: SAH against build ms; trace ms against build ms.
        # Build times on a log axis where they span more than a factor of 8.
        bt = [float(r['build_min']) for r in tsv]
        logx = min(bt) > 0 and max(bt) / min(bt) > 8
        xlabel = 'build ms (min%s)' % (', log scale' if logx else '')
        pts = [(float(r['build_min']), float(r['sah']), setup_short(r)) for r in tsv]
        fr = pareto(tsv, obj[:2])
        panels.append(panel(data, 'sah%d' % len(panels), pts, fr, xlabel,
                            'SAH cost (Ct = 1, Ci = 2)', '%s: SAH against build time'
                            % short_scene(name), logx=logx))
        pts = [(float(r['build_min']), float(r['trace_min']), setup_short(r)) for r in tsv]
        fr = pareto(tsv, [obj[0], obj[2]])
        panels.append(panel(data, 'trace%d' % len(panels), pts, fr, xlabel,
                            'trace ms (min, one frame)', '%s: trace time against build time'
                            % short_scene(name), logx=logx))
        # Reading.
        d = {setup_short(r): r for r in tsv}
        # Setups that built the very same trees (equal hashes of their bytes)
        # trace the same rays through the same nodes: their spread is noise.
        same = {}
        for r in tsv:
            same.setdefault(r['tree'], []).append(r)
        twins = max(same.values(), key=len)
        tw = [float(r['trace_min']) for r in twins]
        groups = [[float(r['trace_min']) for r in g] for g in same.values() if len(g) > 1]
        twin_noise = max((pct(max(g), min(g)) for g in groups), default=None)

        def within(a, b):
            if twin_noise is None:
                return ''
            return ' (%s the %.1f%% by which identical trees differed in this run)' % (
                'within' if abs(pct(a, b)) <= twin_noise else 'more than', twin_noise)
        best_sah = min(tsv, key=lambda r: float(r['sah']))
        best_build = min(tsv, key=lambda r: float(r['build_min']))
        best_trace = min(tsv, key=lambda r: float(r['trace_min']))
        rho = spearman([float(r['sah']) for r in tsv], [float(r['trace_min']) for r in tsv])
        noise = spread(tsv, 'trace_min', 'trace_median') if args.runs >= 3 else 0.0
        s = ['`%s`: the lowest SAH is %s\'s (%.2f), the fastest build %s\'s (%s ms), the '
             'fastest frame %s\'s (%s ms).' % (
                 short_scene(name), setup_short(best_sah), float(best_sah['sah']),
                 setup_short(best_build), ms(float(best_build['build_min'])),
                 setup_short(best_trace), ms(float(best_trace['trace_min'])))]
        if 'sah 16/10' in d and 'thesis-scalar' in d:
            a, b = float(d['thesis-scalar']['trace_min']), float(d['sah 16/10']['trace_min'])
            s.append('The thesis\'s leaf rule (every node of at most 10 triangles is a leaf) gives '
                     'an SAH %.0f%% above the SAH builder\'s default (which keeps splitting while '
                     'the SAH says so) and a frame %.0f%% %s%s.' % (
                         pct(float(d['thesis-scalar']['sah']), float(d['sah 16/10']['sah'])),
                         abs(pct(a, b)), 'slower' if a > b else 'faster', within(a, b)))
        if 'embree' in d and 'sah 16/10' in d:
            s.append('Embree\'s tree has an SAH %+.1f%% against the default\'s, built in %s ms '
                     'against %s ms.' % (
                         pct(float(d['embree']['sah']), float(d['sah 16/10']['sah'])),
                         ms(float(d['embree']['build_min'])),
                         ms(float(d['sah 16/10']['build_min']))))
        s.append('The rank correlation of SAH and frame time over the setups is %.2f (Spearman). '
                 '%s%s.' % (
                     rho, 'Frame medians were up to %.1f%% above their minimum' % noise
                     if args.runs >= 3 else 'With %d timed run(s) there is no spread to judge '
                     'the noise by' % args.runs, '' if len(twins) < 2 else
                     '; %s built the very same trees (equal bytes) and traced them in min '
                     'times %.1f%% apart, so trace differences of that size are noise' % (
                         names(setup_short(r) for r in twins), pct(max(tw), min(tw)))))
        s.append('Pareto-optimal (build, SAH, trace): %s.' % names(
            setup_short(r) for r, f in zip(tsv, front) if f))
        bad = [setup_short(r) for r in tsv if r['differ'] != '0']
        s.append('Every tree gave the default image bit for bit.' if not bad else
                 'NOT the default image: %s.' % names(bad))
        read.append(' '.join(s))
    md.append('![BVH builders: SAH and trace time against build time per scene, Pareto fronts '
              'marked](plots/builders.png)')
    md.append('')
    md.append('In the plot each panel marks the Pareto front of its own two axes (red, '
              'connected); points too close to a labelled one are left unlabelled (the tables '
              'list every setup). "Pareto" in the tables: no other setup is at least as good in '
              'build ms, SAH and trace ms together and better in one. ' + MIN_NOTE)
    md.append('')
    md += [r + '\n' for r in read]
    with open(os.path.join(args.out, 'builders.md'), 'w') as f:
        f.write('\n'.join(md))
    draw(os.path.join(args.out, 'plots', 'builders.png'), data,
         'BVH builders: build time, SAH and trace time (scalar oracle, %d threads)' % args.threads,
         panels, 2, 1500, 470 * len(scenes))


# ---- study c: OpenCL build options ----------------------------------------------------


def compare(rtcl, a, b):
    r = subprocess.run([rtcl, 'compare', a, b], capture_output=True, text=True)
    if r.returncode not in (0, 1):
        sys.exit('study_report.py: rtcl compare %s %s: %s' % (a, b, r.stderr))
    out = {}
    for line in r.stdout.splitlines():
        k, _, v = line.partition(':')
        v = v.strip()
        if k == 'max abs difference':
            out['max'] = float(v)
        elif k == 'PSNR':
            out['psnr'] = math.inf if v.startswith('inf') else float(v.split()[0])
        elif k == 'differing pixels':
            parts = v.split()
            out['differ'], out['pixels'] = int(parts[0]), int(parts[2])
    return out


def opencl_options(args):
    data = args.data
    scenes = scenes_of(data)
    md = ['## Speed against error: OpenCL kernel build options', '', '```', args.command, '```',
          '']
    if not scenes:
        with open(os.path.join(data, 'devices.txt')) as f:
            why = f.read().strip().splitlines()
        md.append('No OpenCL device on this machine (`rtcl devices`: %s): nothing was measured.'
                  % (why[0] if why else 'no output'))
        with open(os.path.join(args.out, 'opencl_options.md'), 'w') as f:
            f.write('\n'.join(md) + '\n')
        no_data_plot(os.path.join(args.out, 'plots', 'opencl_options.png'), data,
                     'no OpenCL device: nothing measured')
        return
    device = next(r['device'] for r in scenes[0][1] if r['name'] != 'oracle')
    md.append(
        'What is measured (`bench/bench_cl_options.c`): the OpenCL backend on `%s` (PoCL, the only '
        'OpenCL device on this machine; its pthread device runs its own pool of one thread per '
        'core), with extra kernel build options appended to the exact build\'s (`rtcl render '
        '--cl-options`, `rt_render_options.device_options`): none (the exact build), '
        '`-cl-mad-enable`, `-cl-fast-relaxed-math`, `-DRT_NATIVE_MATH` (every division and square '
        'root of `kernels/rt_shared.h` as `native_divide` and `native_sqrt`) and the last two '
        'together. The exact build keeps `-cl-fp32-correctly-rounded-divide-sqrt`, which the '
        'variants do not remove. Frames at %dx%d with the scene\'s shading (Whitted: reflection '
        'and refraction where materials have them); the CPU oracle with %s renders the reference '
        'image and is timed beside them. Each variant (and the oracle) renders a warm-up frame '
        '(BVH build, kernel build or cache load, upload; not counted), then %d frame(s), variants '
        'interleaved frame by frame; frame ms is `rt_render_stats.render_ms` (the launches and '
        'read-backs of a frame), min and median. Error: `rtcl compare` of each variant\'s image '
        'with the oracle\'s, as 32-bit float EXR (max abs difference, PSNR with peak 1, pixels '
        'with any channel different) and as the 8-bit PNG (pixels that differ there).'
        % (device, args.width, args.height, machine(args), args.runs))
    md.append('')
    panels, read = [], []
    for i, (name, tsv) in enumerate(scenes):
        label = scene_label(name, args.root, args.shared)
        sdir = os.path.join(data, 'scene%d' % (i + 1))
        oracle = next(r for r in tsv if r['name'] == 'oracle')
        vs = [r for r in tsv if r['name'] != 'oracle']
        for r in vs:
            f = compare(args.rtcl, os.path.join(sdir, 'oracle.exr'),
                        os.path.join(sdir, r['name'] + '.exr'))
            p = compare(args.rtcl, os.path.join(sdir, 'oracle.png'),
                        os.path.join(sdir, r['name'] + '.png'))
            r.update(max=f['max'], psnr=f['psnr'], differ=f['differ'], pixels=f['pixels'],
                     differ8=p['differ'])
        exact = next(r for r in vs if r['options'] == '(exact build)')
        obj = [(lambda r: float(r['min_ms']), 'min'), (lambda r: r['max'], 'min'),
               (lambda r: r['differ'], 'min')]
        front = pareto(vs, obj)
        head = ['variant (extra options)', 'exact promised', 'frame ms (min / median)',
                'vs exact build (min)', 'max abs difference', 'PSNR (dB)',
                'differing pixels (float)', 'differing pixels (8-bit)', 'Pareto']
        rows = [['CPU oracle (reference, %s threads)' % args.threads, 'yes',
                 '%s / %s' % (ms(float(oracle['min_ms'])), ms(float(oracle['median_ms']))),
                 '%+.1f%%' % pct(float(oracle['min_ms']), float(exact['min_ms'])),
                 '-', '-', '-', '-', '-']]
        for r, f in zip(vs, front):
            rows.append(['`%s`' % r['options'] if r['options'] != '(exact build)' else
                         'none (exact build)', 'yes' if r['exact'] == '1' else 'no',
                         '%s / %s' % (ms(float(r['min_ms'])), ms(float(r['median_ms']))),
                         '%+.1f%%' % pct(float(r['min_ms']), float(exact['min_ms'])),
                         sci(r['max']), 'inf' if math.isinf(r['psnr']) else '%.1f' % r['psnr'],
                         '%d (%.2f%%)' % (r['differ'], 100.0 * r['differ'] / r['pixels']),
                         r['differ8'], 'yes' if f else 'no'])
        md.append('`%s` (%s rays per frame):' % (label, exact['rays']))
        md.append('')
        md.append(md_table(head, rows, right={2, 3, 4, 5, 6, 7}))
        md.append('')
        short = {r['name']: ('exact' if r['options'] == '(exact build)' else r['options']
                             .replace('-cl-', '').replace('-DRT_', '')) for r in vs}
        pts = [(float(r['min_ms']), r['max'], short[r['name']]) for r in vs]
        panels.append(panel(data, 'max%d' % i, pts, pareto(vs, obj[:2]), 'frame ms (min)',
                            'max abs difference from the oracle',
                            '%s: max difference against frame time' % short_scene(name),
                            ymin0=True, label_all=True))
        pts = [(float(r['min_ms']), 100.0 * r['differ'] / r['pixels'], short[r['name']])
               for r in vs]
        panels.append(panel(data, 'px%d' % i, pts, pareto(vs, [obj[0], obj[2]]),
                            'frame ms (min)', 'pixels differing from the oracle (%, float)',
                            '%s: differing pixels against frame time' % short_scene(name),
                            ymin0=True, label_all=True))
        same = [r['options'] for r in vs if r['differ'] == 0 and r is not exact]
        diff = [r for r in vs if r['differ'] > 0]
        noise = spread(vs, 'min_ms', 'median_ms') if args.runs >= 3 else 0.0
        s = ['`%s`: the exact build gave the oracle\'s image %s.' % (
            short_scene(name), 'bit for bit' if exact['differ'] == 0 else
            'with %d differing pixels (it must not)' % exact['differ'])]
        if same:
            s.append('%s changed no bit here: the image is the oracle\'s.' % names(
                '`%s`' % x for x in same))
        if diff:
            s.append(names('`%s` changed %d pixels (%d visible in 8 bits; max %s, PSNR %.1f dB; '
                           'min frame time %+.1f%% against the exact build)'
                           % (r['options'], r['differ'], r['differ8'], sci(r['max']), r['psnr'],
                              pct(float(r['min_ms']), float(exact['min_ms']))) for r in diff) + '.')
        others = [r for r in vs if r is not exact]
        fastest = min(others, key=lambda r: float(r['min_ms']))
        gain = pct(float(fastest['min_ms']), float(exact['min_ms']))
        if gain < 0:
            s.append('The fastest variant (min frame time) was %s, %.1f%% below the exact '
                     'build' % (short[fastest['name']], -gain))
        else:
            s.append('No variant\'s min frame time was below the exact build\'s (the nearest: '
                     '%s, %+.1f%%)' % (short[fastest['name']], gain))
        s[-1] += ('; frame medians were up to %.1f%% above their minimum (other work on the '
                  'shared machine), so %s.' % (noise, noise_note(args, noise, gain,
                                                                'that difference')))
        if same:
            twins = [r for r in vs if r['differ'] == 0 and r is not exact]
            diffs = [pct(float(r['min_ms']), float(exact['min_ms'])) for r in twins]
            if args.runs < 3:
                verdict = 'too few runs to tell noise from a real difference'
            elif max(abs(x) for x in diffs) <= noise:
                verdict = 'within the runs\' spread, so no speed-up is shown'
            else:
                verdict = ('more than the runs\' spread for some: the compiler may emit other, '
                           'faster code for the same arithmetic, or the noise was larger than '
                           'its measure')
            s.append('%s gave the exact build\'s bits; their min frame times differ from its by '
                     '%s (%s).' % (names('`%s`' % r['options'] for r in twins),
                                   names('%+.1f%%' % x for x in diffs), verdict))
        s.append('Pareto-optimal (frame time, max difference, differing pixels): %s.' % names(
            short[r['name']] for r, f in zip(vs, front) if f))
        read.append(' '.join(s))
    md.append('![OpenCL build options: image error against frame time per scene, Pareto fronts '
              'marked](plots/opencl_options.png)')
    md.append('')
    md.append('"Pareto": no other variant is at least as good in frame time, max difference and '
              'differing pixels together and better in one (the CPU oracle, a reference, is not '
              'a candidate). ' + MIN_NOTE)
    md.append('')
    md += [r + '\n' for r in read]
    with open(os.path.join(args.out, 'opencl_options.md'), 'w') as f:
        f.write('\n'.join(md))
    draw(os.path.join(args.out, 'plots', 'opencl_options.png'), data,
         'OpenCL kernel build options on PoCL: error against frame time', panels, 2, 1500,
         470 * len(scenes))


def main():
    p = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    p.add_argument('study', choices=['tri_tests', 'builders', 'opencl_options'])
    p.add_argument('data')
    p.add_argument('out')
    p.add_argument('--command', required=True, help='the command shown above the section')
    p.add_argument('--root', required=True)
    p.add_argument('--shared', required=True)
    p.add_argument('--runs', type=int, required=True)
    p.add_argument('--threads', type=int, required=True)
    p.add_argument('--width', type=int, required=True)
    p.add_argument('--height', type=int, required=True)
    p.add_argument('--sample', type=int, default=0)
    p.add_argument('--rtcl')
    args = p.parse_args()
    args.root = os.path.abspath(args.root)
    args.shared = os.path.abspath(args.shared)
    os.makedirs(os.path.join(args.out, 'plots'), exist_ok=True)
    globals()[args.study](args)
    return 0


if __name__ == '__main__':
    sys.exit(main())
