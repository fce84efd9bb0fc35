#!/usr/bin/python3
"""The linear solve per Newton iteration for each solver choice, on 1 and 2 ranks: the first
steps of inputs/ball.xml (8k tets) and of its refined version (65k tets). Writes
perf/results/solvers.json and the table in perf/README.md between <!-- solvers:begin --> and
<!-- solvers:end -->.

    /usr/bin/python3 perf/solvers_report.py [--build build] [--steps 20]
"""
import argparse, csv, datetime, json, os, re, subprocess, sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from report_util import ENV, ROOT, replace_section  # noqa: E402

# (type, preconditioner, label, extra --set): muelu with the six rigid-body modes (the default
# near null space) and with MueLu's own translations only
CHOICES = [('gmres', 'ilu', 'ilu', []), ('gmres', 'schwarz', 'schwarz', []),
           ('gmres', 'muelu', 'muelu (rigid-body modes)', []),
           ('gmres', 'muelu', 'muelu (translations)', ['Solver/Linear/multigrid near null space=translations']),
           ('cg', 'ilu', 'ilu', []), ('klu2', 'none', 'none', []),
           ('mumps', 'none', 'none', [])]


def run(build, size, ranks, typ, prec, label, extra, steps):
    out = 'out/solver_%s_%s_%s_np%d' % (size, typ, re.sub(r'\W+', '_', label), ranks)
    cmd = ([] if ranks == 1 else ['mpirun', '--oversubscribe', '-np', str(ranks)]) + [
        os.path.join(build, 'bin', 'emcontact'), 'inputs/ball.xml', '--output', out, '--overwrite',
        '--set', 'Bodies/ball/Mesh/size=%s' % size, '--set', 'Time/end=%g' % (steps * 0.001),
        '--set', 'Solver/Linear/type=%s' % typ, '--set', 'Solver/Linear/preconditioner=%s' % prec,
        '--set', 'Output/every=0', '--set', 'Output/plot=false', '--set', 'Output/progress=false']
    for e in extra:
        cmd += ['--set', e]
    p = subprocess.run(cmd, capture_output=True, text=True, env=ENV, cwd=ROOT)
    if p.returncode != 0:
        return dict(size=size, ranks=ranks, type=typ, prec=label, error=(p.stdout + p.stderr).strip().splitlines()[-1][:200])
    m = re.search(r'emcontact: (\d+) tets.*?(\d+) steps to .*? \(([\d.]+) s/step', p.stdout)
    tm = re.search(r'emcontact: linear solve\s+(.*)', p.stdout)
    nums = re.findall(r'([\d.e+-]+) \(([\d.e+-]+)\)', tm[1])
    solve_s, calls = float(nums[-2][0] if len(nums) >= 3 else nums[0][0]), float(nums[0][1])
    setup = 'MUMPS factorisation' if typ == 'mumps' else 'preconditioner'  # mumps: its factors
    pm = re.search(r'emcontact: %s\s+([\d.e+-]+) \(([\d.e+-]+)\)' % setup, p.stdout)
    with open(os.path.join(ROOT, out, 'monitors.csv')) as f:
        rows = list(csv.DictReader(f))[1:]
    its = sum(int(r['linear_iterations']) for r in rows) / max(1, sum(int(r['newton_iterations']) for r in rows))
    return dict(size=size, ranks=ranks, type=typ, prec=label, tets=int(m[1]), s_per_step=float(m[3]),
                solve_per_newton=solve_s / calls, krylov_per_solve=its,
                prec_setups=int(float(pm[2])) if pm else 0, prec_s=float(pm[1]) if pm else 0.0)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--build', default='build')
    ap.add_argument('--steps', type=int, default=20)
    ap.add_argument('--sizes', nargs='+', default=['0.0524', '0.026'])
    a = ap.parse_args()
    build = os.path.join(ROOT, a.build)
    res = []
    for size in a.sizes:
        for typ, prec, label, extra in CHOICES:
            for ranks in (1, 2):
                if typ == 'klu2' and (ranks > 1 or size != a.sizes[0]):
                    continue  # one rank only; too slow to factor beyond small problems
                res.append(run(build, size, ranks, typ, prec, label, extra, a.steps))
                print(res[-1], flush=True)
    json.dump(dict(date=datetime.date.today().isoformat(), runs=res),
              open(os.path.join(ROOT, 'perf', 'results', 'solvers.json'), 'w'), indent=1)
    md = ['Measured by `/usr/bin/python3 perf/solvers_report.py` (%d steps of `inputs/ball.xml` from t = 0; '
          'the time per linear solve is the maximum over ranks; the preconditioner is reused while it works).'
          % a.steps, '',
          '| tets | solver | ranks | s per linear solve | Krylov its per solve | preconditioner setups (s) | wall s/step |',
          '|---|---|---|---|---|---|---|']
    for r in res:
        if 'error' in r:
            md.append('| %s | %s + %s | %d | failed: %s | | | |' % (r['size'], r['type'], r['prec'], r['ranks'], r['error']))
            continue
        md.append('| %d | %s + %s | %d | %.4f | %.1f | %d (%.2f) | %.4f |' % (
            r['tets'], r['type'], r['prec'], r['ranks'], r['solve_per_newton'], r['krylov_per_solve'],
            r['prec_setups'], r['prec_s'], r['s_per_step']))
    text = '\n'.join(md)
    print(text)
    replace_section(os.path.join(ROOT, 'perf', 'README.md'), 'solvers', text, '## Linear solvers')


if __name__ == '__main__':
    main()
