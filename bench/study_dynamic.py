#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""study_dynamic.py DATA_DIR OUT_DIR --command CMD [options] - the report
section OUT_DIR/dynamic.md and plot OUT_DIR/plots/dynamic.png of the dynamic
scenes study (bench/study_dynamic.sh) from what 'rtcl bench --animate --json'
wrote into DATA_DIR (policies.jsonl: one object per scene, frames one per
keyframe; long.jsonl: the long morph with --series). Every number in the
section is read from those files or computed here from them, the Pareto
fronts too. Python's standard library and gnuplot (through study_report.py's
helpers)."""
import argparse
import datetime
import json
import os
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import study_report as sr  # noqa: E402


def label(r):
    return '%s %s' % (r['engine'], r['policy'])


def rel(path, root, shared):
    p = path
    if p.startswith(root + '/'):
        p = p[len(root) + 1:]
    return p.replace(shared, '$S')


def ratio(a, b):
    return a / b if b else float('nan')


def policy_section(objs, root, shared, data_dir):
    out, panels = [], []
    for obj in objs:
        rows = [r for r in obj['dynamic'] if 'error' not in r]
        failed = [r for r in obj['dynamic'] if 'error' in r]
        name = rel(obj['scene'], root, shared)
        out.append('#### %s: %d of %d triangles morphing, %d keyframes, %d frames at %g fps, '
                   '%d runs\n' % (name, obj['morph_triangles'], obj['triangles'],
                                  obj['keyframes'], obj['frames'], obj['fps'], obj['runs']))
        front = sr.pareto(rows, [(lambda r: r['update_ms_min'], 'min'),
                                 (lambda r: r['trace_ms_min'], 'min')])
        table = []
        for r, f in zip(rows, front):
            same = r.get('images_match_rebuild')
            table.append([r['engine'], r['policy'] + (' (%d-wide)' % r['lanes'] if 'lanes' in r else ''),
                          sr.ms(r['update_ms_min']), sr.ms(r['update_ms_median']),
                          sr.ms(r['trace_ms_min']), sr.ms(r['trace_ms_median']),
                          sr.ms(r['frame_ms_min']), sr.ms(r['frame_ms_median']),
                          '%.2f' % r['sah'] if r.get('sah') is not None else '-',
                          'reference' if r['engine'] == 'rtcl' and r['policy'] == 'sah'
                          else ('yes' if same else 'NO') if same is not None else '-',
                          '**yes**' if f else ''])
        out.append(sr.md_table(['engine', 'policy', 'update ms min', 'median', 'trace ms min',
                                'median', 'frame ms min', 'median', 'SAH', 'frames = rebuild',
                                'Pareto'], table, right=set(range(2, 9))))
        for r in failed:
            out.append('\n%s failed: %s' % (label(r), r['error']))
        if obj.get('embree_missing'):
            out.append('\nNo Embree rows: %s.' % obj['embree_missing'])
        by = {(r['engine'], r['policy']): r for r in rows}
        notes = []
        if ('embree', 'refit') in by:
            e = by
            notes.append('refit / Embree REFIT update (min) %.2f (target at most 0.5)'
                         % ratio(e['rtcl', 'refit']['update_ms_min'],
                                 e['embree', 'refit']['update_ms_min']))
            notes.append('lbvh / Embree LOW update %.2f (target at most 1) at SAH %.2f against '
                         '%.2f' % (ratio(e['rtcl', 'lbvh']['update_ms_min'],
                                         e['embree', 'low']['update_ms_min']),
                                   e['rtcl', 'lbvh']['sah'], e['embree', 'low']['sah']))
            notes.append('rebuild / Embree MEDIUM update %.2f'
                         % ratio(e['rtcl', 'sah']['update_ms_min'],
                                 e['embree', 'medium']['update_ms_min']))
            ours = min((r for r in rows if r['engine'] == 'rtcl'), key=lambda r: r['frame_ms_min'])
            theirs = min((r for r in rows if r['engine'] == 'embree'),
                         key=lambda r: r['frame_ms_min'])
            notes.append('best whole frame: ours %s %s ms, Embree %s %s ms (ratio %.2f; '
                         'medians %s and %s)'
                         % (ours['policy'], sr.ms(ours['frame_ms_min']), theirs['policy'],
                            sr.ms(theirs['frame_ms_min']),
                            ratio(ours['frame_ms_min'], theirs['frame_ms_min']),
                            sr.ms(ours['frame_ms_median']), sr.ms(theirs['frame_ms_median'])))
        if 'brainstem' in name and any(r['engine'] == 'rtcl' for r in rows):
            best = min((r for r in rows if r['engine'] == 'rtcl'), key=lambda r: r['frame_ms_min'])
            notes.append('the issue\'s target for this animation, at most 33 ms per frame (30 '
                         'fps) with the update, is %s here (best: %s, %s ms)'
                         % ('met' if best['frame_ms_min'] <= 33.0 else 'not met',
                            best['policy'], sr.ms(best['frame_ms_min'])))
        if notes:
            out.append('\nFrom the minima: ' + '; '.join(notes) + '.')
        out.append('')
        if len(panels) < 2 and rows:
            pts = [(r['update_ms_min'], r['trace_ms_min'], label(r)) for r in rows]
            short = os.path.splitext(os.path.basename(obj['scene']))[0]
            panels.append(sr.panel(data_dir, 'pol%d' % len(panels), pts, front,
                                   'update ms per frame (min)', 'trace ms per frame (min)',
                                   '%s: update against trace, per frame' % short,
                                   ymin0=True, label_all=True))
    return out, panels


def long_section(obj, data_dir):
    rows = {r['policy']: r for r in obj['dynamic'] if r['engine'] == 'rtcl' and 'error' not in r}
    emb = {r['policy']: r for r in obj['dynamic'] if r['engine'] == 'embree' and 'error' not in r}
    out = []
    n = obj['frames']
    fps = obj['fps']
    want = ['refit', 'auto', 'sah']
    if not all(p in rows for p in want):
        return ['The long morph has no rows for refit, auto and rebuild.'], []
    sah = {p: rows[p]['series']['sah'] for p in want}
    trace = {p: rows[p]['series']['trace_ms'] for p in want}
    upd = {p: rows[p]['series']['update_ms'] for p in want}
    frame = {p: rows[p]['series']['frame_ms'] for p in want}
    # auto rebuilt where its tree is a fresh SAH build: its SAH cost equals
    # rebuild's (the same builder on the same positions).
    rebuilt = [k + 1 for k in range(n) if abs(sah['auto'][k] - sah['sah'][k]) < 1e-3]
    step = max(1, n // 24)
    table = []
    for k in range(0, n, step):
        table.append(['%d' % (k + 1), '%.2f' % ((k + 1) / fps)] +
                     ['%.2f' % sah[p][k] for p in want] +
                     [sr.ms(trace[p][k]) for p in want] +
                     [sr.ms(upd[p][k]) for p in want])
    out.append(sr.md_table(['frame', 'time s', 'SAH refit', 'auto', 'rebuild', 'trace ms refit',
                            'auto', 'rebuild', 'update ms refit', 'auto', 'rebuild'], table,
                           right=set(range(11))))
    ratios = [sah['refit'][k] / sah['sah'][k] for k in range(n)]
    worst = max(range(n), key=lambda k: ratios[k])
    mean = {p: statistics.mean(frame[p]) for p in want}
    tmean = {p: statistics.mean(trace[p]) for p in want}
    umean = {p: statistics.mean(upd[p]) for p in want}
    summary = ('\nEvery %sframe shown (medians over %d runs; all %d frames in the plot). The '
               'refitted tree\'s SAH cost reaches %.2f times the rebuilt tree\'s (frame %d, '
               '%.2f s); auto rebuilt at %d of %d frames%s. Means over the %d frames: update '
               '%s / %s / %s ms, trace %s / %s / %s ms, whole frame %s / %s / %s ms (refit / '
               'auto / rebuild).'
               % ('%dth ' % step if step > 1 else '', obj['runs'], n, ratios[worst], worst + 1,
                  (worst + 1) / fps, len(rebuilt), n,
                  ' (frames %s)' % ', '.join(str(k) for k in rebuilt[:20]) +
                  (', ...' if len(rebuilt) > 20 else '') if rebuilt else '', n,
                  sr.ms(umean['refit']), sr.ms(umean['auto']), sr.ms(umean['sah']),
                  sr.ms(tmean['refit']), sr.ms(tmean['auto']), sr.ms(tmean['sah']),
                  sr.ms(mean['refit']), sr.ms(mean['auto']), sr.ms(mean['sah'])))
    if emb:
        summary += (' Embree over the same frames, whole frame mean: ' + ', '.join(
            '%s %s ms' % (p.upper(), sr.ms(statistics.mean(r['series']['frame_ms'])))
            for p, r in emb.items()) + '.')
    smean = {p: statistics.mean(sah[p]) for p in want}
    tests = {p: rows[p]['series'].get('tests') for p in want}
    summary += (' Mean SAH cost: %.2f / %.2f / %.2f.' % (smean['refit'], smean['auto'],
                                                          smean['sah']))
    if all(tests[p] and None not in tests[p] for p in want):
        tr = [tests['refit'][k] / tests['sah'][k] for k in range(n)]
        summary += (' The counted traversal work (box tests + 2 x triangle tests of all rays, '
                    'which the SAH cost predicts and the machine\'s noise does not touch) of the '
                    'refitted tree is %.2f to %.2f times the rebuilt tree\'s (mean %.3f).'
                    % (min(tr), max(tr), statistics.mean(tr)))
    if rebuilt:
        after = [k for k in range(rebuilt[0] - 1, n)]
        a_s = statistics.mean(sah['auto'][k] for k in after)
        r_s = statistics.mean(sah['refit'][k] for k in after)
        summary += (' From auto\'s first rebuild (frame %d) on, its mean SAH cost is %.2f against '
                    'refit\'s %.2f: %s.'
                    % (rebuilt[0], a_s, r_s,
                       'the tree rebuilt for one pose fits the other poses worse than the tree '
                       'of frame 0 does, so the bound relative to the last rebuild lets it drift '
                       'further' if a_s > r_s else 'the rebuilds paid off'))
    out.append(summary)
    # Line panels: SAH and trace ms per frame.
    colors = {'refit': '#1f77b4', 'auto': '#2ca02c', 'sah': '#d62728'}
    panels = []
    for key, ylabel, title in (('sah', 'SAH cost (Ct 1, Ci 2)', 'long morph: SAH per frame'),
                               ('trace_ms', 'trace ms (median)', 'long morph: trace ms per frame'),
                               ('tests', 'box tests + 2 x triangle tests',
                                'long morph: counted traversal work per frame')):
        if any(v is None for p in want for v in rows[p]['series'].get(key) or [None]):
            continue
        path = os.path.join(data_dir, 'plot_long_%s.dat' % key)
        with open(path, 'w') as f:
            for k in range(n):
                f.write('%g %s\n' % ((k + 1) / fps,
                                     ' '.join('%.6g' % rows[p]['series'][key][k] for p in want)))
        cmds = ['unset logscale', 'set title %s' % sr.gp_str(title), 'set xlabel "time s"',
                'set ylabel %s' % sr.gp_str(ylabel), 'set grid', 'set key top left',
                'set autoscale x', 'set autoscale y', 'set format x "%g"', 'set format y "%g"']
        cmds.append('plot ' + ', '.join(
            '%s using 1:%d with lines lw 2 dt %d lc rgb "%s" title "%s"'
            % (sr.gp_str(path), i + 2, 2 if p == 'auto' else 1, colors[p], p)
            for i, p in enumerate(want)))
        panels.append(cmds)
    return out, panels


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('data')
    ap.add_argument('out')
    ap.add_argument('--command', required=True)
    ap.add_argument('--root', required=True)
    ap.add_argument('--shared', required=True)
    ap.add_argument('--threads', type=int, default=2)
    a = ap.parse_args()
    pol = [json.loads(l) for l in open(os.path.join(a.data, 'policies.jsonl')) if l.strip()]
    lng = [json.loads(l) for l in open(os.path.join(a.data, 'long.jsonl')) if l.strip()]
    first = pol[0]
    # When and where (the section is also appended on its own, outside report.sh).
    try:
        commit = subprocess.run(['git', '-C', a.root, 'rev-parse', '--short', 'HEAD'],
                                capture_output=True, text=True).stdout.strip() or 'unknown'
        cpu = next((l.split(':', 1)[1].strip() for l in
                    subprocess.run(['lscpu'], capture_output=True, text=True).stdout.splitlines()
                    if l.startswith('Model name:')), 'unknown CPU')
    except OSError:
        commit, cpu = 'unknown', 'unknown CPU'
    stamp = ('Measured %s from commit `%s` on `%s`, %d cores (a shared virtual machine: other '
             'jobs ran at the same time, so the figures are noisy).'
             % (datetime.datetime.now(datetime.timezone.utc).strftime('%Y-%m-%d'), commit, cpu,
                os.cpu_count() or 0))
    text = ['## Dynamic scenes (issue 16): update policies beside Embree, `rtcl bench --animate`',
            '', stamp, '', '```', a.command, '```', '',
            'What `rtcl bench --animate` measures (`bench/engines/bench_animate.c`): the scene\'s '
            'morphing object played frame by frame (frame k at time k/fps; the blend of two '
            'keyframes is the scene\'s work and not timed), %dx%d, one point light, primary plus '
            'shadow rays, %d threads. Ours: the packet backend, a fresh renderer per row and run, '
            'every mesh\'s update policy set; "update" is the mesh BVH updates the renderer '
            'reports, "frame" the whole `rt_render` (update, object BVH, layout rewritten in '
            'place, the packet tracer\'s wide BVHs, tracing and shading). Embree '
            '(`bench/peer/embree_anim.c`): the same instances in world space in a dynamic scene '
            '(no instancing, Embree\'s fastest case, where our packets go through the object BVH '
            'and transform rays into each instance; it matters in the keyframe scene, whose '
            'objects move), '
            'every geometry and the scene at build quality REFIT (scene LOW), LOW (Morton) or '
            'MEDIUM; "update" is `rtcCommitGeometry` of what changed plus `rtcCommitScene`, '
            '"frame" adds copying the moved vertices into its buffers and tracing the same rays '
            'with its widest native packets and shading them as we do. Frame 0 (the first '
            'build) is not counted; each figure is a run\'s mean over the frames (the thesis\'s '
            'section 4.1: build time averaged over the keyframes), min and median over the runs, '
            'the rows interleaved frame by frame (every row\'s frame k before any row\'s frame k + 1). "frames = rebuild": every frame\'s image is the '
            'rebuild row\'s, bit for bit. SAH: ours, the mesh BVHs\' cost (Ct 1, Ci 2, '
            'triangle-weighted) averaged over the frames; Embree\'s commit trees are not exposed, '
            'so its rows show the binary trees of its builders of that quality (`rtcBuildBVH`: '
            'LOW Morton, MEDIUM binned SAH; REFIT: the first frame\'s MEDIUM tree refitted) '
            'under the same measure. Pareto: no other row of the scene has both a lower update '
            'and a lower trace time (minima). The machine is a shared 2-core virtual machine '
            'with other jobs running: the minima are the figures to compare, the medians show '
            'the noise.' % (first['width'], first['height'], a.threads), '']
    text.append('### Per policy, one frame per keyframe\n')
    sec, panels = policy_section(pol, a.root, a.shared, a.data)
    text += sec
    if lng:
        o = lng[0]
        text.append('### A long morph: %s, %d frames at %g fps (%d keyframes, looping), %d runs\n'
                    % (rel(o['scene'], a.root, a.shared), o['frames'], o['fps'], o['keyframes'],
                       o['runs']))
        sec2, p2 = long_section(o, a.data)
        text += sec2
        panels += p2
    text.append('\n![update against trace per policy; SAH and trace ms per frame over the long '
                'morph](plots/dynamic.png)\n')
    with open(os.path.join(a.out, 'dynamic.md'), 'w') as f:
        f.write('\n'.join(text))
    term = sr.gnuplot_terminal()
    if term is None:
        sys.exit('study_dynamic.py: gnuplot with a png or pngcairo terminal is needed')
    font = 'Sans,10' if term == 'pngcairo' else 'Sans 10'
    png = os.path.join(a.out, 'plots', 'dynamic.png')
    script = ['set terminal %s size 1400,%d font %s noenhanced'
              % (term, 500 * ((len(panels) + 1) // 2), sr.gp_str(font)),
              'set output %s' % sr.gp_str(png),
              'set multiplot layout %d,2 title %s font ",12"'
              % ((len(panels) + 1) // 2,
                 sr.gp_str('Dynamic scenes: update against trace per frame (red, connected: the '
                           'Pareto front); over a long morph, refit against auto and rebuild'))]
    for p in panels:
        script += p
    script.append('unset multiplot')
    gp = os.path.join(a.data, 'plot.gp')
    with open(gp, 'w') as f:
        f.write('\n'.join(script) + '\n')
    r = subprocess.run(['gnuplot', gp], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit('study_dynamic.py: gnuplot failed: %s' % r.stderr)


if __name__ == '__main__':
    sys.exit(main())
