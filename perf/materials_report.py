#!/usr/bin/python3
"""Saint-Venant-Kirchhoff against Neo-Hookean on the paper's ball (docs/user-guide.md,
"Materials"): inputs/rubber_ball.xml (thrown down at 20 m/s) run with each model, its energy
error and vertical stretch (the ball's height over its diameter, from the fields) against time,
and the first impact of inputs/ball.xml (3.4 m/s) with each model: its contact period and least
vertical stretch. Writes docs/rubber_ball.png, perf/results/materials.json and the table in
perf/README.md between <!-- materials:begin --> and <!-- materials:end -->.

    /usr/bin/python3 perf/materials_report.py [--build build] [--reuse]

--reuse reads the out/materials_* directories of an earlier run instead of running (about four
minutes on the 2-core VM). Needs numpy, h5py and matplotlib.
"""
import argparse, csv, glob, json, os, subprocess, sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from report_util import ENV, ROOT, replace_section  # noqa: E402

import h5py  # noqa: E402
import numpy as np  # noqa: E402
import matplotlib  # noqa: E402
matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402

MODELS = ['svk', 'neo-hookean']
DIAMETER = 0.8


def run(build, case, model, sets, reuse):
    """Runs inputs/<case>.xml with Material/model = model; returns (output dir, last error line
    or '' when the run completed)."""
    out = os.path.join('out', 'materials_%s_%s' % (case, model))
    log = os.path.join(ROOT, out + '.log')
    if not reuse:
        cmd = [os.path.join(build, 'bin', 'emcontact'), 'inputs/%s.xml' % case, '--output', out,
               '--overwrite', '--set', 'Bodies/ball/Material/model=' + model,
               '--set', 'Output/plot=false', '--set', 'Output/progress=false']
        for s in sets:
            cmd += ['--set', s]
        p = subprocess.run(cmd, capture_output=True, text=True, env=ENV, cwd=ROOT)
        open(log, 'w').write(p.stdout + p.stderr)
    lines = open(log).read().strip().splitlines()
    errors = [line for line in lines if line.startswith('error:')]
    return os.path.join(ROOT, out), errors[-1] if errors else ''


def monitors(out):
    with open(os.path.join(out, 'monitors.csv')) as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def stretches(out):
    """(time, height / diameter) of the ball at every written frame."""
    with h5py.File(os.path.join(out, 'mesh.h5'), 'r') as m:
        X = m['geometry'][:]
        nodes = np.unique(m['topology'][:])
    series = []
    for name in sorted(glob.glob(os.path.join(out, 'fields_*.h5'))):
        with h5py.File(name, 'r') as f:
            z = X[nodes, 2] + f['displacement'][:][nodes, 2]
            series.append((float(f['time'][()]), (z.max() - z.min()) / DIAMETER))
    return series


def first_impact(rows):
    """Contact period of the first run of steps with active contact."""
    on = [i for i, r in enumerate(rows) if r['active_contacts'] > 0]
    if not on:
        return float('nan')
    end = on[0]
    while end + 1 < len(rows) and rows[end + 1]['active_contacts'] > 0:
        end += 1
    return rows[end]['time'] - rows[on[0]]['time']


def energy_error(rows):
    e0 = rows[0]['total']
    return max(abs(r['total'] - e0) for r in rows) / abs(e0)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--build', default=os.path.join(ROOT, 'build'))
    ap.add_argument('--reuse', action='store_true')
    args = ap.parse_args()
    result = {}
    fig, (ax_e, ax_s) = plt.subplots(1, 2, figsize=(11, 4))
    for model in MODELS:
        rb, rb_error = run(args.build, 'rubber_ball', model, [], args.reuse)
        rows = monitors(rb)
        s = stretches(rb)
        ball, ball_error = run(args.build, 'ball', model,
                               ['Time/end=0.5', 'Output/every=10'], args.reuse)
        brows = monitors(ball)
        bs = [v for t, v in stretches(ball)]
        result[model] = {
            'rubber_ball': {'completed': not rb_error, 'error': rb_error,
                            'end_time': rows[-1]['time'], 'steps': int(rows[-1]['step']),
                            'min_stretch': min(v for t, v in s),
                            'energy_error': energy_error(rows),
                            'newton_per_step': sum(r['newton_iterations'] for r in rows[1:])
                            / max(1, len(rows) - 1)},
            'ball_first_impact': {'completed': not ball_error, 'period_s': first_impact(brows),
                                  'min_stretch': min(bs)}}
        t = [r['time'] * 1e3 for r in rows]
        label = model + ('' if not rb_error else
                         ' (an element at the contact inverts at t = %.1f ms: x, the run stops)'
                         % (rows[-1]['time'] * 1e3))
        style = dict(lw=3, alpha=0.6) if rb_error else dict(lw=1.5)
        ax_e.semilogy(t[1:], [max(abs(r['total'] - rows[0]['total']) / rows[0]['total'], 1e-17)
                              for r in rows[1:]], label=label, **style)
        line, = ax_s.plot([x * 1e3 for x, v in s], [v for x, v in s], label=label, **style)
        if rb_error:
            ax_s.plot([s[-1][0] * 1e3], [s[-1][1]], 'x', ms=12, mew=3, color=line.get_color())
    ax_e.set_xlabel('t [ms]')
    ax_e.set_ylabel('|E - E0| / E0')
    ax_e.set_title('rubber_ball.xml: energy error')
    ax_s.set_xlabel('t [ms]')
    ax_s.set_ylabel('height / diameter')
    ax_s.set_title('rubber_ball.xml: vertical stretch (20 m/s)')
    for ax in (ax_e, ax_s):
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(ROOT, 'docs', 'rubber_ball.png'), dpi=90)
    os.makedirs(os.path.join(ROOT, 'perf', 'results'), exist_ok=True)
    json.dump(result, open(os.path.join(ROOT, 'perf', 'results', 'materials.json'), 'w'), indent=1)
    lines = ['| model | rubber_ball.xml (20 m/s) | least height / diameter | max \\|E-E0\\|/E0 | '
             'Newton/step | ball.xml first impact: contact period | its least height / diameter |',
             '|---|---|---|---|---|---|---|']
    for model in MODELS:
        r, b = result[model]['rubber_ball'], result[model]['ball_first_impact']
        status = 'completes, %d steps' % r['steps'] if r['completed'] else \
            'stops at t = %.2f ms: %s' % (r['end_time'] * 1e3, r['error'].split(':', 2)[-1]
                                          .split(';')[0].strip()[:120])
        lines.append('| %s | %s | %.3f | %.1e | %.2f | %.1f ms | %.3f |' % (
            model, status, r['min_stretch'], r['energy_error'], r['newton_per_step'],
            b['period_s'] * 1e3, b['min_stretch']))
    ratio = result['neo-hookean']['ball_first_impact']['period_s'] / \
        result['svk']['ball_first_impact']['period_s']
    lines.append('')
    lines.append('At the paper\'s own impact (ball.xml, 3.4 m/s) the Neo-Hookean contact period '
                 'is %.1f%% of the SVK one: strains there are not small.' % (100 * ratio))
    replace_section(os.path.join(ROOT, 'perf', 'README.md'), 'materials', '\n'.join(lines),
                    heading='### Saint-Venant-Kirchhoff against Neo-Hookean on the ball')
    print('\n'.join(lines))


if __name__ == '__main__':
    main()
