#!/usr/bin/python3
"""The paper's ball (inputs/ball.xml) with and without `close gap` (docs/THEORY.md §7): per
impact the contact period, the rebound (vertical momentum after / before), the spin about the
centre of mass and the largest active gap; the energy error and Newton iterations of the run.
Writes perf/results/closure.json, docs/ball_gap_closure.png and the table in perf/README.md between
<!-- closure:begin --> and <!-- closure:end -->.

    /usr/bin/python3 perf/closure_report.py [--build build] [--reuse]

--reuse reads out/ball_close_{false,true}/monitors.csv of an earlier run instead of running
(and the CPU time from out/ball_close_*.log if that run was timed by /usr/bin/time -v).
"""
import argparse, csv, json, os, re, resource, subprocess, sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from report_util import ENV, ROOT, replace_section  # noqa: E402

import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402


def run(build, close):
    out = 'out/ball_close_%s' % ('true' if close else 'false')
    cmd = [os.path.join(build, 'bin', 'emcontact'), 'inputs/ball.xml', '--output', out, '--overwrite',
           '--set', 'Contact/ball on ground/close gap=%s' % ('true' if close else 'false'),
           '--set', 'Output/plot=false', '--set', 'Output/progress=false']
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    p = subprocess.run(cmd, capture_output=True, text=True, env=ENV, cwd=ROOT)
    if p.returncode != 0:
        sys.exit('%s failed: %s' % (' '.join(cmd), (p.stdout + p.stderr).strip().splitlines()[-1]))
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    return out, (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)


def logged_cpu(out):
    """CPU seconds from a `/usr/bin/time -v` log beside an earlier run's directory (or nan)."""
    try:
        log = open(os.path.join(ROOT, out + '.log')).read()
        return sum(float(x) for x in re.findall(r'(?:User|System) time \(seconds\): ([\d.]+)', log))
    except OSError:
        return float('nan')


def impacts(rows):
    """Contiguous runs of steps with active contact: (start, end) row indices."""
    out, start = [], None
    for i, r in enumerate(rows):
        on = int(r['active_contacts']) > 0
        if on and start is None:
            start = i
        if not on and start is not None:
            out.append((start, i - 1))
            start = None
    if start is not None:
        out.append((start, len(rows) - 1))
    return out


def spin(r):
    """Angular momentum about the centre of mass: J - c x L (the ball is the only body)."""
    c = [float(r['com_x']), float(r['com_y']), float(r['com_z'])]
    L = [float(r['Lx']), float(r['Ly']), float(r['Lz'])]
    J = [float(r['Jx']), float(r['Jy']), float(r['Jz'])]
    cxL = [c[1] * L[2] - c[2] * L[1], c[2] * L[0] - c[0] * L[2], c[0] * L[1] - c[1] * L[0]]
    return [J[i] - cxL[i] for i in range(3)]


def summarize(out, seconds):
    rows = list(csv.DictReader(open(os.path.join(ROOT, out, 'monitors.csv'))))
    E0 = float(rows[0]['total'])
    scale = max(float(r['kinetic']) + float(r['elastic']) + abs(float(r['potential'])) for r in rows)
    res = dict(seconds=seconds, steps=len(rows) - 1,
               dE=max(abs(float(r['total']) - E0) for r in rows) / scale,
               newton=sum(int(r['newton_iterations']) for r in rows[1:]) / (len(rows) - 1),
               impacts=[])
    for a, b in impacts(rows):
        before, after = rows[max(a - 1, 0)], rows[min(b + 1, len(rows) - 1)]
        res['impacts'].append(dict(
            t0=float(rows[a]['time']) - float(rows[a]['dt']), t1=float(rows[b]['time']),
            rebound=-float(after['Lz']) / float(before['Lz']),
            spin=spin(after), gap_max=max(float(r['gap_max']) for r in rows[a:b + 1]),
            gap_min=min(float(r['gap_min']) for r in rows[a:b + 1])))
    res['t'] = [float(r['time']) for r in rows]
    res['gap_max'] = [float(r['gap_max']) for r in rows]
    res['total'] = [(float(r['total']) - E0) / scale for r in rows]
    return res


def table(runs):
    lines = ['| closure | impact | contact t [s] | rebound Lz after/before | spin about the centre after (x, y, z) | active gap max [m] | active gap min [m] |',
             '|---|---|---|---|---|---|---|']
    for name, r in runs:
        for k, i in enumerate(r['impacts']):
            if i['t1'] - i['t0'] < 0.0015:  # a single-step touch is listed in the count only
                continue
            lines.append('| %s | %d | %.3f-%.3f | %.4f | (%.2f, %.2f, %.2f) | %.1e | %.1e |' % (
                name, k + 1, i['t0'], i['t1'], i['rebound'], *i['spin'], i['gap_max'], i['gap_min']))
    lines.append('')
    lines.append('| closure | contacts (incl. single-step touches) | Newton/step | max energy error | CPU time [s] |')
    lines.append('|---|---|---|---|---|')
    for name, r in runs:
        lines.append('| %s | %d | %.2f | %.1e | %.0f |' % (name, len(r['impacts']), r['newton'], r['dE'], r['seconds']))
    return '\n'.join(lines)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--build', default='build')
    ap.add_argument('--reuse', action='store_true')
    a = ap.parse_args()
    runs = []
    for close in (False, True):
        if a.reuse:
            out = 'out/ball_close_%s' % ('true' if close else 'false')
            sec = logged_cpu(out)
        else:
            out, sec = run(a.build, close)
        runs.append(('on' if close else 'off', summarize(out, sec)))
    os.makedirs(os.path.join(ROOT, 'perf', 'results'), exist_ok=True)
    json.dump({n: {k: v for k, v in r.items() if k not in ('t', 'gap_max', 'total')} for n, r in runs},
              open(os.path.join(ROOT, 'perf', 'results', 'closure.json'), 'w'), indent=1)
    fig, ax = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    for name, r in runs:
        ax[0].plot(r['t'], [1e3 * g for g in r['gap_max']], label='close gap = %s' % ('true' if name == 'on' else 'false'))
        ax[1].plot(r['t'], r['total'], label='close gap = %s' % ('true' if name == 'on' else 'false'))
    ax[0].set_ylabel('largest active gap g_N at n+1 [mm]')
    ax[1].set_ylabel('(E - E0) / max(K + W + |Pi|)')
    ax[1].set_xlabel('t [s]')
    for x in ax:
        x.legend()
        x.grid(alpha=0.3)
    fig.suptitle("inputs/ball.xml: the hovering gap with and without the closure")
    fig.tight_layout()
    fig.savefig(os.path.join(ROOT, 'docs', 'ball_gap_closure.png'), dpi=90)
    text = ('Measured by `/usr/bin/python3 perf/closure_report.py` (inputs/ball.xml, full stick '
            'on the rigid ground, dt = 1 ms, 2.5 s).\n\n') + table(runs)
    replace_section(os.path.join(ROOT, 'perf', 'README.md'), 'closure', text)
    print(text)


if __name__ == '__main__':
    main()
