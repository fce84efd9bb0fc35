#!/usr/bin/python3
"""Whole-run scaling of the ball (inputs/ball.xml) with mesh size and MPI ranks, in two phases:
`flight` (the first steps from t = 0, no contact) and `impact` (the ball placed 5 mm above the
ground, moving down at 3 m/s: it hits at the second step, so most steps have contact). For each
run: wall time per step, the Teuchos timer breakdown (assembly, contact, elimination, linear
solve, preconditioner, output), Newton iterations per step, Krylov iterations per linear solve
(from monitors.csv), the peak memory per tet, and the parallel efficiency:
  strong: the same mesh on 1 and 2 ranks, efficiency = t1 / (2 t2);
  weak:   a mesh of about twice the tets on 2 ranks, efficiency = t1(N) / t2(2N).
Writes perf/results/scaling.json and the tables in perf/README.md between
<!-- scaling:begin --> and <!-- scaling:end -->.

    /usr/bin/python3 perf/scaling_report.py [--build build] [--steps 10]
        [--sizes 0.0524 0.026 0.0129] [--weak 0.0524:0.0416 0.026:0.0206] [--phases flight impact]

Set EMC_RUN_PREFIX (e.g. "env OMP_NUM_THREADS=2") to run under a launcher; --threads N adds
OMP_NUM_THREADS=N to the environment (for an OpenMP build; see perf/README.md).
"""
import argparse, csv, datetime, json, os, re, subprocess, sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from report_util import ENV, ROOT, replace_section  # noqa: E402

PRECONDITIONER = 'ilu'  # --preconditioner: the tables below were measured with ILU(0)
TIMERS = ('assembly', 'contact', 'elimination', 'linear solve', 'preconditioner', 'output')
# the parts of 'contact' (THEORY §8): search and activation, a new P, the iterates' rows and
# projections, the host pass of chains and rows, the selection of the rank's contact nodes
CONTACT_TIMERS = ('contact: activation', 'contact: new P', 'contact: Newton iterates', 'contact: chains and rows',
                  'contact: node selection')
PHASES = {
    'flight': [],
    'impact': ['--set', 'Bodies/ball/Mesh/center={0, 0, 0.405}',
               '--set', 'Bodies/ball/Initial/velocity={2, 0, -3}'],
}


def run(build, size, ranks, steps, phase, threads=None, preconditioner=None):
    out = os.path.join('out', 'scaling_%s_%s_np%d_t%s' % (phase, size, ranks, threads or 0))
    cmd = ['/usr/bin/time', '-v']
    if ranks > 1:
        cmd += ['mpirun', '--oversubscribe', '--mca', 'mpi_yield_when_idle', '1', '--bind-to', 'none', '-np', str(ranks)]
    cmd += [os.path.join(build, 'bin', 'emcontact'), 'inputs/ball.xml', '--output', out, '--overwrite',
            '--set', 'Bodies/ball/Mesh/size=%s' % size, '--set', 'Time/end=%g' % (steps * 0.001),
            '--set', 'Output/every=0', '--set', 'Output/plot=false', '--set', 'Output/progress=false']
    cmd += PHASES[phase] + ['--set', 'Solver/Linear/preconditioner=%s' % (preconditioner or PRECONDITIONER)]
    env = dict(ENV)
    if threads:
        env.update(OMP_NUM_THREADS=str(threads), OMP_PROC_BIND='spread', OMP_PLACES='threads')
    p = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=ROOT)
    if p.returncode != 0:
        sys.exit('failed: %s\n%s%s' % (' '.join(cmd), p.stdout, p.stderr[-3000:]))
    m = re.search(r'emcontact: (\d+) tets, (\d+) nodes on (\d+) rank\(s\); setup ([\d.]+) s; (\d+) steps to '
                  r't = \S+ in ([\d.]+) s \(([\d.]+) s/step, ([\d.]+) Newton', p.stdout)
    r = dict(phase=phase, size=size, tets=int(m[1]), nodes=int(m[2]), ranks=int(m[3]), threads=threads or 1,
             setup_s=float(m[4]), steps=int(m[5]), s_per_step=float(m[7]), newton_per_step=float(m[8]))
    for t in TIMERS + CONTACT_TIMERS:  # maximum over ranks (the third number on 2+ ranks, the only one on 1)
        tm = re.search(r'emcontact: %s\s+(.*)' % re.escape(t), p.stdout)
        if tm:
            nums = re.findall(r'([\d.e+-]+) \(', tm[1])
            r[t] = float(nums[2] if len(nums) >= 3 else nums[0]) / r['steps']
    with open(os.path.join(ROOT, out, 'monitors.csv')) as f:
        rows = list(csv.DictReader(f))[1:]  # row 0 is the initial state
    newton = sum(int(x['newton_iterations']) for x in rows)
    r['krylov_per_solve'] = sum(int(x['linear_iterations']) for x in rows) / max(newton, 1)
    r['contact_steps'] = sum(1 for x in rows if int(x['active_contacts']) > 0)
    rss = re.search(r'Maximum resident set size \(kbytes\): (\d+)', p.stderr)
    r['max_rss_mb'] = int(rss[1]) / 1024 if rss else float('nan')  # of mpirun's children: the largest rank
    return r


def row(r, eff):
    return '| %s | %d | %d | %d | %.4f | %.2f | %.2f | %.1f | %d | %s | %.0f%% | %.0f (%.2f) |' % (
        r['phase'], r['tets'], r['ranks'], r['threads'], r['s_per_step'], 1e6 * r['s_per_step'] * r['ranks'] / r['tets'],
        r['newton_per_step'], r['krylov_per_solve'], r['contact_steps'],
        ' / '.join('%.4f' % r.get(t, 0) for t in TIMERS), 100 * eff, r['max_rss_mb'],
        1024 * r['max_rss_mb'] / r['tets'] * r['ranks'])


HEADER = ['| phase | tets | ranks | threads | wall s/step | per tet per step [us] | Newton its/step | Krylov its/solve | '
          'steps with contact | s/step: ' + ' / '.join(TIMERS) + ' | efficiency | peak RSS MB (per tet kB) |',
          '|---|---|---|---|---|---|---|---|---|---|---|---|']


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--build', default='build')
    ap.add_argument('--steps', type=int, default=10)
    ap.add_argument('--sizes', nargs='+', default=['0.0524', '0.026', '0.0129'])
    ap.add_argument('--weak', nargs='*', default=['0.0524:0.0416', '0.026:0.0206'])
    ap.add_argument('--phases', nargs='+', default=['flight', 'impact'])
    ap.add_argument('--preconditioner', default='ilu', help='Solver/Linear/preconditioner (ilu, muelu, auto, ...)')
    a = ap.parse_args()
    global PRECONDITIONER
    PRECONDITIONER = a.preconditioner
    build = os.path.join(ROOT, a.build)
    strong, weak = [], []
    for phase in a.phases:
        for size in a.sizes:
            for ranks in (1, 2):
                strong.append(run(build, size, ranks, a.steps, phase))
                print(strong[-1], flush=True)
        for pair in a.weak:
            small, big = pair.split(':')
            one = next((r for r in strong if r['phase'] == phase and r['size'] == small and r['ranks'] == 1), None)
            if one is None:
                one = run(build, small, 1, a.steps, phase)
            two = run(build, big, 2, a.steps, phase)
            weak.append((one, two))
            print(two, flush=True)
    os.makedirs(os.path.join(ROOT, 'perf', 'results'), exist_ok=True)
    json.dump(dict(date=datetime.date.today().isoformat(), strong=strong, weak=[list(w) for w in weak]),
              open(os.path.join(ROOT, 'perf', 'results', 'scaling.json'), 'w'), indent=1)
    md = ['Measured by `/usr/bin/python3 perf/scaling_report.py` (%d steps of `inputs/ball.xml`: `flight` from t = 0, '
          '`impact` with the ball 5 mm above the ground at 3 m/s downward; Belos GMRES + preconditioner %s, Kokkos Serial; times per '
          'step, maximum over ranks).' % (a.steps, a.preconditioner), '',
          '### Strong scaling (the same mesh on 1 and 2 ranks; efficiency t1 / (2 t2))', ''] + HEADER
    for r in strong:
        one = next(x for x in strong if x['phase'] == r['phase'] and x['size'] == r['size'] and x['ranks'] == 1)
        md.append(row(r, one['s_per_step'] / (r['ranks'] * r['s_per_step'])))
    if weak:
        md += ['', '### Weak scaling (about twice the tets on 2 ranks; efficiency t1(N) / t2(2N))', ''] + HEADER
        for one, two in weak:
            md.append(row(one, 1.0))
            md.append(row(two, one['s_per_step'] / two['s_per_step']))
    text = '\n'.join(md)
    print(text)
    replace_section(os.path.join(ROOT, 'perf', 'README.md'), 'scaling', text, '## Whole runs: mesh size and ranks')


if __name__ == '__main__':
    main()
