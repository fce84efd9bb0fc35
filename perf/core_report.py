#!/usr/bin/python3
"""Runs the elastodynamics-core cases and writes the measured figures (conservation errors,
wall time per step) to perf/results/core.json and into perf/README.md between the markers
<!-- core:begin --> and <!-- core:end -->.

Usage (from the repository root, after building into build/):
    /usr/bin/python3 perf/core_report.py [--build build] [--no-readme]   (--no-readme: print only)
"""
import argparse, csv, datetime, json, os, platform, re, subprocess, sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from report_util import ENV, ROOT, replace_section  # noqa: E402



def run(build, xml, out, ranks=1, sets=()):
    cmd = [os.path.join(build, 'bin', 'emcontact'), xml, '--output', out, '--overwrite', '--set', 'Output/progress=false']
    for s in sets:
        cmd += ['--set', s]
    if ranks > 1:
        cmd = ['mpirun', '--oversubscribe', '-np', str(ranks)] + cmd
    p = subprocess.run(cmd, capture_output=True, text=True, env=ENV, cwd=ROOT)
    if p.returncode != 0:
        sys.exit('failed: %s\n%s\n%s' % (' '.join(cmd), p.stdout, p.stderr))
    m = re.search(r'emcontact: (\d+) tets, (\d+) nodes on (\d+) rank\(s\); setup ([\d.]+) s; (\d+) steps to '
                  r't = \S+ in ([\d.]+) s \(([\d.]+) s/step, ([\d.]+) Newton', p.stdout)
    summary = dict(tets=int(m[1]), nodes=int(m[2]), ranks=int(m[3]), setup_s=float(m[4]), steps=int(m[5]),
                   stepping_s=float(m[6]), s_per_step=float(m[7]), newton_per_step=float(m[8]),
                   command=' '.join(cmd[cmd.index(os.path.join(build, 'bin', 'emcontact')):]))
    timers = {}
    for line in p.stdout.splitlines():
        t = re.match(r'emcontact: (assembly|elimination|linear solve|preconditioner|output)\s+([\d.e+-]+)', line)
        if t:
            timers[t[1]] = float(t[2])
    summary['timers'] = timers
    with open(os.path.join(ROOT, out, 'monitors.csv')) as f:
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
    return summary, rows


def drifts(rows):
    r0 = rows[0]
    n = lambda v: sum(x * x for x in v) ** 0.5
    vec = lambda r, q: [r[q + c] for c in 'xyz']
    scaleE = max(r['kinetic'] + r['elastic'] + abs(r['potential']) for r in rows)
    dE = max(abs(r['total'] - r0['total']) for r in rows) / scaleE
    dL = max(n([a - b for a, b in zip(vec(r, 'L'), vec(r0, 'L'))]) for r in rows) / max(n(vec(r0, 'L')), 1e-300)
    dJ = max(n([a - b for a, b in zip(vec(r, 'J'), vec(r0, 'J'))]) for r in rows) / max(n(vec(r0, 'J')), 1e-300)
    return dict(E=dE, L=dL, J=dJ)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--build', default='build')
    ap.add_argument('--no-readme', action='store_true')
    a = ap.parse_args()
    build = os.path.join(ROOT, a.build)
    res = dict(date=datetime.date.today().isoformat(), machine='%s, %d cores' % (platform.processor() or platform.machine(), os.cpu_count()))
    cons = []
    for name, xml, sets in (
            ('tumbling box, energy-momentum', 'inputs/tumbling_box.xml', ['Output/every=0']),
            ('tumbling box, mid-point', 'inputs/tumbling_box.xml', ['Output/every=0', 'Time/integrator=midpoint']),
            ('falling box, gravity', 'inputs/falling_box.xml', ['Output/every=0'])):
        s, rows = run(build, xml, 'out/report_%d' % len(cons), 1, sets)
        cons.append(dict(case=name, steps=s['steps'], tets=s['tets'], **drifts(rows), newton_per_step=s['newton_per_step'],
                         command=s['command']))
    res['conservation'] = cons
    timing = []
    for ranks in (1, 2):
        s, _ = run(build, 'perf/inputs/box50k.xml', 'out/report_box50k_np%d' % ranks, ranks)
        timing.append(s)
    res['timing'] = timing
    os.makedirs(os.path.join(ROOT, 'perf', 'results'), exist_ok=True)
    with open(os.path.join(ROOT, 'perf', 'results', 'core.json'), 'w') as f:
        json.dump(res, f, indent=1)

    md = ['Measured by `/usr/bin/python3 perf/core_report.py` on %s.' % res['machine'], '',
          '| case | tets | steps | max \\|E-E0\\| / max(K+W+\\|Pi\\|) | max \\|L-L0\\|/\\|L0\\| | max \\|J-J0\\|/\\|J0\\| | Newton its/step |',
          '|---|---|---|---|---|---|---|']
    for c in cons:
        lj = ('n/a', 'n/a') if 'gravity' in c['case'] else ('%.1e' % c['L'], '%.1e' % c['J'])
        md.append('| %s | %d | %d | %.1e | %s | %s | %.2f |' % (c['case'], c['tets'], c['steps'], c['E'], lj[0], lj[1], c['newton_per_step']))
    md += ['', 'L and J are not conserved under gravity (the body gains momentum), E is. Commands: ' +
           '; '.join('`build/bin/emcontact %s`' % c['command'].split('emcontact ', 1)[-1] for c in cons) + '.', '',
           '| 50k-tet body | ranks | wall s/step | Newton its/step | assembly s | linear solve s | preconditioner s | setup s |',
           '|---|---|---|---|---|---|---|---|']
    for t in timing:
        tm = t['timers']
        md.append('| %d tets, %d steps | %d | %.3f | %.2f | %.2f | %.2f | %.2f | %.2f |' % (
            t['tets'], t['steps'], t['ranks'], t['s_per_step'], t['newton_per_step'], tm.get('assembly', 0),
            tm.get('linear solve', 0), tm.get('preconditioner', 0), t['setup_s']))
    md += ['', 'Wall time per step of `perf/inputs/box50k.xml` (Belos GMRES + ILU(0), 1 ms steps); the timer '
           'columns are totals over the run, maximum over ranks. Parallel efficiency at 2 ranks: %.0f%%.' % (
               100 * timing[0]['s_per_step'] / (2 * timing[1]['s_per_step']))]
    text = '\n'.join(md)
    print(text)
    if not a.no_readme:
        replace_section(os.path.join(ROOT, 'perf', 'README.md'), 'core', text)


if __name__ == '__main__':
    main()
