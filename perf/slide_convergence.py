#!/usr/bin/python3
"""The sliding block of tests/regression/slide.xml (docs/THEORY.md §11.6: a block at 1 m/s on a
rigid plane, mu = 0.3, stops after v^2 / (2 mu g) decelerating at mu g) at several step sizes
and mesh sizes: the error of the stopping distance (the centre's x at t = 0.5 s) and of the
deceleration (least-squares slope of v_x = L_x / m over 0.05-0.25 s). Writes the table into
docs/THEORY.md between <!-- slide_convergence:begin --> and <!-- slide_convergence:end -->.

    /usr/bin/python3 perf/slide_convergence.py [--build build] [--dt 0.01 0.005 0.0025]
                                               [--h 0.05 0.1]
"""
import argparse, csv, os, re, subprocess, sys, time
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from report_util import ENV, ROOT, replace_section  # noqa: E402

MU, G, V0, MASS = 0.3, 9.81, 1.0, 1000 * 0.2 * 0.2 * 0.1


def run(build, h, dt, young):
    out = 'out/slide_h%g_dt%g_E%g' % (h, dt, young)
    cmd = [os.path.join(build, 'bin', 'emcontact'), 'tests/regression/slide.xml', '--output', out,
           '--overwrite', '--set', 'Time/dt=%.17g' % dt,
           '--set', 'Bodies/block/Mesh/size=%.17g' % h,
           '--set', 'Bodies/block/Material/young=%.17g' % young]
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True, env=ENV, cwd=ROOT)
    if p.returncode != 0:
        sys.exit('%s failed: %s' % (' '.join(cmd), (p.stdout + p.stderr).strip()))
    with open(os.path.join(ROOT, out, 'monitors.csv')) as f:
        rows = list(csv.DictReader(f))
    tets = re.search(r'emcontact: (\d+) tets', p.stdout + p.stderr)
    return rows, time.time() - t0, tets[1] if tets else '?'


def errors(rows):
    """(stopping distance, its relative error, the error of its mean over 0.4-0.5 s (the ringing
    after the stop averaged), deceleration, its relative error, max |E + D - E0| / E0)."""
    d = V0 * V0 / (2 * MU * G)
    x_end = float(rows[-1]['com_x'])
    late = [float(r['com_x']) for r in rows if float(r['time']) >= 0.4 - 1e-9]
    x_mean = sum(late) / len(late)
    pts = [(float(r['time']), float(r['Lx']) / MASS) for r in rows
           if 0.05 <= float(r['time']) <= 0.25]
    n = len(pts)
    st, sv = sum(t for t, _ in pts), sum(v for _, v in pts)
    stt, stv = sum(t * t for t, _ in pts), sum(t * v for t, v in pts)
    a = -(n * stv - st * sv) / (n * stt - st * st)
    e0 = float(rows[0]['total'])
    bal = max(abs(float(r['total']) + float(r['dissipated']) - e0) for r in rows) / abs(e0)
    return x_end, (x_end - d) / d, (x_mean - d) / d, a, (a - MU * G) / (MU * G), bal


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--build', default='build')
    ap.add_argument('--dt', type=float, nargs='+', default=[0.01, 0.005, 0.0025])
    ap.add_argument('--h', type=float, nargs='+', default=[0.05, 0.02])
    ap.add_argument('--young', type=float, nargs='+', default=[1e7])
    ap.add_argument('--no-write', action='store_true', help='print the table only')
    args = ap.parse_args()
    lines = ['| E [Pa] | h [m] (tets) | dt [s] | steps | stop [m] | stop error | '
             'mean 0.4-0.5 s error | deceleration [m/s^2] | deceleration error | '
             'max \\|E+D-E0\\|/E0 |', '|---|---|---|---|---|---|---|---|---|---|']
    for young in args.young:
        for h in args.h:
            for dt in args.dt:
                rows, wall, tets = run(args.build, h, dt, young)
                x, ex, em, a, ea, bal = errors(rows)
                lines.append('| %g | %g (%s) | %g | %d | %.6f | %+.2e | %+.2e | %.4f | %+.2e | %.1e |' %
                             (young, h, tets, dt, len(rows) - 1, x, ex, em, a, ea, bal))
                print(lines[-1], '(%.0f s)' % wall, flush=True)
    if args.no_write:
        return
    text = ('Measured by `/usr/bin/python3 perf/slide_convergence.py --dt %s --h %s --young %s` '
            '(tests/regression/slide.xml with `--set Time/dt=...`, `Bodies/block/Mesh/size`, '
            '`Bodies/block/Material/young`; closed forms v^2 / (2 mu g) = %.6f m, '
            'mu g = %.4f m/s^2).\n\n' %
            (' '.join('%g' % x for x in args.dt),
             ' '.join('%g' % x for x in args.h), ' '.join('%g' % x for x in args.young),
             V0 * V0 / (2 * MU * G), MU * G))
    replace_section(os.path.join(ROOT, 'docs', 'THEORY.md'), 'slide_convergence',
                    text + '\n'.join(lines))


if __name__ == '__main__':
    main()
