#!/usr/bin/python3
"""Whole-run scaling of the ball (inputs/ball.xml) with mesh size and MPI ranks: wall time per
step (first steps, free flight), the Teuchos timer breakdown, Newton iterations per step, and
the peak memory per tet. Writes perf/results/scaling.json and the table in perf/README.md
between <!-- scaling:begin --> and <!-- scaling:end -->.

    /usr/bin/python3 perf/scaling_report.py [--build build] [--steps 10] [--sizes 0.0524 0.026 0.0129]
"""
import argparse, datetime, json, os, re, subprocess, sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from report_util import ENV, ROOT, replace_section  # noqa: E402

TIMERS = ('assembly', 'elimination', 'linear solve', 'preconditioner', 'output')


def run(build, size, ranks, steps):
    out = 'out/scaling_%s_np%d' % (size, ranks)
    cmd = ['/usr/bin/time', '-v']
    if ranks > 1:
        cmd += ['mpirun', '--oversubscribe', '-np', str(ranks)]
    cmd += [os.path.join(build, 'bin', 'emcontact'), 'inputs/ball.xml', '--output', out,
            '--set', 'Bodies/ball/Mesh/size=%s' % size, '--set', 'Time/end=%g' % (steps * 0.001),
            '--set', 'Output/every=0', '--set', 'Output/plot=false', '--set', 'Output/progress=false']
    p = subprocess.run(cmd, capture_output=True, text=True, env=ENV, cwd=ROOT)
    if p.returncode != 0:
        sys.exit('failed: %s\n%s%s' % (' '.join(cmd), p.stdout, p.stderr[-3000:]))
    m = re.search(r'emcontact: (\d+) tets, (\d+) nodes on (\d+) rank\(s\); setup ([\d.]+) s; (\d+) steps to '
                  r't = \S+ in ([\d.]+) s \(([\d.]+) s/step, ([\d.]+) Newton', p.stdout)
    r = dict(size=size, tets=int(m[1]), nodes=int(m[2]), ranks=int(m[3]), setup_s=float(m[4]), steps=int(m[5]),
             s_per_step=float(m[7]), newton_per_step=float(m[8]))
    for t in TIMERS:  # maximum over ranks (the third number on 2+ ranks, the only one on 1)
        tm = re.search(r'emcontact: %s\s+(.*)' % t, p.stdout)
        if tm:
            nums = re.findall(r'([\d.e+-]+) \(', tm[1])
            r[t] = float(nums[2] if len(nums) >= 3 else nums[0]) / r['steps']
    rss = re.search(r'Maximum resident set size \(kbytes\): (\d+)', p.stderr)
    r['max_rss_mb'] = int(rss[1]) / 1024 if rss else float('nan')  # of mpirun's children: the largest rank
    return r


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--build', default='build')
    ap.add_argument('--steps', type=int, default=10)
    ap.add_argument('--sizes', nargs='+', default=['0.0524', '0.026', '0.0129'])
    a = ap.parse_args()
    build = os.path.join(ROOT, a.build)
    res = []
    for size in a.sizes:
        for ranks in (1, 2):
            res.append(run(build, size, ranks, a.steps))
            print(res[-1], flush=True)
    os.makedirs(os.path.join(ROOT, 'perf', 'results'), exist_ok=True)
    json.dump(dict(date=datetime.date.today().isoformat(), runs=res),
              open(os.path.join(ROOT, 'perf', 'results', 'scaling.json'), 'w'), indent=1)
    md = ['Measured %s by `/usr/bin/python3 perf/scaling_report.py` (%d steps of `inputs/ball.xml` from t = 0, '
          'free flight, Belos GMRES + ILU(0); times per step, maximum over ranks).' % (datetime.date.today(), a.steps), '',
          '| tets | ranks | wall s/step | per tet per step [us] | Newton its/step | assembly | elimination | linear solve | '
          'preconditioner | parallel efficiency | peak RSS MB (per tet kB) |', '|---|---|---|---|---|---|---|---|---|---|---|']
    one = {}
    for r in res:
        if r['ranks'] == 1:
            one[r['size']] = r['s_per_step']
        eff = one[r['size']] / (r['ranks'] * r['s_per_step']) if r['size'] in one else float('nan')
        md.append('| %d | %d | %.4f | %.2f | %.2f | %.4f | %.4f | %.4f | %.4f | %.0f%% | %.0f (%.2f) |' % (
            r['tets'], r['ranks'], r['s_per_step'], 1e6 * r['s_per_step'] * r['ranks'] / r['tets'], r['newton_per_step'],
            r.get('assembly', 0), r.get('elimination', 0), r.get('linear solve', 0), r.get('preconditioner', 0),
            100 * eff, r['max_rss_mb'], 1024 * r['max_rss_mb'] / r['tets'] * r['ranks']))
    text = '\n'.join(md)
    print(text)
    replace_section(os.path.join(ROOT, 'perf', 'README.md'), 'scaling', text, '## Whole runs: mesh size and ranks')


if __name__ == '__main__':
    main()
