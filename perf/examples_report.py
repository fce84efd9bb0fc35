#!/usr/bin/python3
"""Runs the paper's examples (inputs/ball.xml, and the frictionless ones when present, and the ball
with Coulomb friction, inputs/ball_friction.xml), copies
their plots to docs/, and writes the measured figures to perf/results/examples.json and into
perf/README.md between <!-- examples:begin --> and <!-- examples:end -->.

Usage (from the repository root, after building):
    /usr/bin/python3 perf/examples_report.py [--build build] [--only ball] [--only ball_friction]
                                             [--reuse]
--reuse summarises existing out/<name>/ runs instead of running again.
"""
import argparse, datetime, json, os, re, shutil, subprocess, sys, time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from report_util import ROOT, replace_section  # noqa: E402
sys.path.insert(0, os.path.join(ROOT, 'tools'))
from summarize_run import load, summarize  # noqa: E402

EXAMPLES = [('ball', 'inputs/ball.xml'), ('three_disks', 'inputs/three_disks.xml'),
            ('hollow_cylinders', 'inputs/hollow_cylinders.xml'), ('ball_friction', 'inputs/ball_friction.xml')]
# The momentum components each example conserves: on the frictionless plane z = 0 the plane's
# reaction is along z, so Lx, Ly and Jz; the ball (full stick, gravity) conserves none.
CONSERVED = {'ball': [], 'three_disks': ['Lx', 'Ly', 'Jz'], 'hollow_cylinders': ['Lx', 'Ly', 'Jz'],
             'ball_friction': []}
# Balls that roll once friction has stopped their contact point's slip (docs/THEORY.md §11.6):
# initial speed v0 along x without spin, outer and inner radii. A rigid shell rolls at
# v0 / (1 + I / (m R^2)), I = (2/5) m (R^5 - r^5) / (R^3 - r^3) (angular momentum about the
# contact point is conserved); in flight v_x and the spin are constant.
ROLLING = {'ball_friction': dict(v0=2.0, R=0.4, r=0.2)}
NOTES = {'ball_friction': 'The contact nodes stick through most of each impact and slide where their force leaves '
                          'the cone; the soft ball (E = 4e6 Pa) gives back the shear it stored while they stuck, '
                          'so it leaves each bounce spinning faster or slower than rolling (omega R / v_x above: '
                          'the superball\'s alternation) and its v_x alternates about the rigid ball\'s rolling '
                          'speed. A rigid ball sliding into its first bounce would end it rolling, having lost '
                          'k / (1 + k) = 31% of its kinetic energy (k = I / (m R^2)).'}


def rolling(rows, v0, R, r):
    """v_x and omega_y R / v_x (omega from the spin angular momentum J - com x L and the closed-form
    I of the mesh's mass m = Lx(0) / v0) in each flight (10 steps or more without an active node)
    after a contact; the closed-form speed."""
    k = 0.4 * (R ** 5 - r ** 5) / ((R ** 3 - r ** 3) * R * R)
    m = rows[0]['Lx'] / v0
    flights, cur, touched = [], [], False
    for row in rows[1:]:
        if row['active_contacts'] > 0:
            touched = True
            if cur:
                flights.append(cur)
            cur = []
        elif touched:
            cur.append(row)
    if cur:
        flights.append(cur)
    out = []
    for f in (f for f in flights if len(f) >= 10):
        row = f[len(f) // 2]
        vx = row['Lx'] / m
        spin = row['Jy'] - (row['com_z'] * row['Lx'] - row['com_x'] * row['Lz'])
        out.append(dict(t=row['time'], vx=vx, roll=spin / (k * m * R * R) * R / vx))
    return dict(v_closed=v0 / (1 + k), flights=out)


def run(build, name, xml, reuse):
    out = os.path.join('out', name)
    info = {}
    if not reuse:
        cmd = [os.path.join(build, 'bin', 'emcontact'), xml, '--output', out, '--overwrite',
               '--set', 'Output/progress=false', '--set', 'Output/plot=true']
        t0 = time.time()
        p = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
        info['wall_s'] = time.time() - t0
        if p.returncode != 0:
            sys.exit('failed: %s\n%s%s' % (' '.join(cmd), p.stdout, p.stderr))
        m = re.search(r'emcontact: (\d+) tets, (\d+) nodes', p.stdout)
        info.update(tets=int(m[1]), nodes=int(m[2]))
        info['command'] = 'build/bin/emcontact %s --output %s' % (xml, out)
        with open(os.path.join(ROOT, out, 'stdout.txt'), 'w') as f:
            f.write(p.stdout)
    elif os.path.exists(os.path.join(ROOT, out, 'stdout.txt')):
        txt = open(os.path.join(ROOT, out, 'stdout.txt')).read()
        m = re.search(r'emcontact: (\d+) tets, (\d+) nodes.*?total ([\d.]+) s', txt)
        info.update(tets=int(m[1]), nodes=int(m[2]), wall_s=float(m[3]))
        info['command'] = 'build/bin/emcontact %s --output %s' % (xml, out)
    rows = load(os.path.join(ROOT, out, 'monitors.csv'))
    info.update(summarize(rows))
    info['E0'] = rows[0]['total']
    if name in ROLLING:
        info['rolling'] = rolling(rows, **ROLLING[name])
    png = os.path.join(ROOT, out, 'energies.png')
    if os.path.exists(png):
        shutil.copy(png, os.path.join(ROOT, 'docs', name + '_energies.png'))
    return info


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--build', default='build')
    ap.add_argument('--only', action='append')
    ap.add_argument('--reuse', action='store_true')
    a = ap.parse_args()
    build = os.path.join(ROOT, a.build)
    os.makedirs(os.path.join(ROOT, 'docs'), exist_ok=True)
    res_path = os.path.join(ROOT, 'perf', 'results', 'examples.json')
    res = json.load(open(res_path)) if os.path.exists(res_path) else {}
    for name, xml in EXAMPLES:
        if (a.only and name not in a.only) or not os.path.exists(os.path.join(ROOT, xml)):
            continue
        res[name] = run(build, name, xml, a.reuse)
        res[name]['date'] = datetime.date.today().isoformat()
    os.makedirs(os.path.dirname(res_path), exist_ok=True)
    json.dump(res, open(res_path, 'w'), indent=1)

    md = ['Measured by `/usr/bin/python3 perf/examples_report.py` on this project\'s 2-core machine, one rank.', '',
          '| example | tets | steps | wall s | Newton its/step (max) | max \\|E+D-E0\\|/\\|E0\\| | conserved components: max drift / initial \\|L\\| or \\|J\\| | contact periods [s] | active gap min / max [m] | re-solves/step |',
          '|---|---|---|---|---|---|---|---|---|---|']
    # Rows measured on one day share a batch number (the dates stay in the JSON): the VM's speed
    # varies between days, so wall times compare only within a batch.
    days = sorted({res[name].get('date', '') for name, _ in EXAMPLES if name in res})
    for name, _ in EXAMPLES:
        if name not in res:
            continue
        r = res[name]
        label = name if len(days) == 1 else '%s (batch %d)' % (name, days.index(r.get('date', '')) + 1)
        comps = ', '.join('%s %.1e' % (c, r[c + '_drift_abs'] / max(r[c[0] + '_initial'], 1e-300))
                          for c in CONSERVED[name]) or 'none (gravity, %s)' % (
                              'friction' if r.get('dissipated', 0) else 'full stick')
        md.append('| %s | %d | %d | %.0f | %.2f (%d) | %.1e | %s | %s | %.2g / %.2g | %.2f |' % (
            label, r['tets'], r['steps'], r['wall_s'], r['newton_per_step'], r['max_newton'],
            r.get('ED_drift', r['E_drift']),
            comps, ', '.join('%.3f-%.3f' % tuple(p) for p in r['contact_periods']), r['gap_min'], r['gap_max'],
            r['resolves'] / max(1, r['steps'])))
    together = ('all rows measured on one day' if len(days) == 1 else
                'rows of one batch measured on one day: compare wall times only within a batch')
    md += ['', "Wall times: one rank, %s (the VM's speed has varied by up to 2x between days). " % together +
           'Active gap: g_N at the end of the step of the nodes active in it (negative: penetration); '
           're-solves: extra solves of a step for the active set (docs/THEORY.md §6). D: the energy '
           'dissipated by friction (0 without friction, docs/THEORY.md §11.2); E + D is conserved.', '']
    for name, _ in EXAMPLES:
        r = res.get(name, {})
        if 'rolling' not in r:
            continue
        ro = r['rolling']
        fl = ro['flights']
        md += ['**%s**: D = %.2f J of E0 = %.2f J (%.1f%%) dissipated by friction. After each bounce '
               'the ball flies with v_x (closed form v0 / (1 + I / (m R^2)) = %.4f m/s; '
               'omega R / v_x with the closed-form I of the mesh\'s mass, 1 when rolling): %s.' % (
                   name, r['dissipated'], r['E0'], 100 * r['dissipated'] / r['E0'], ro['v_closed'],
                   ', '.join('t = %.2f s: %.4f (%+.1f%%), %.3f' % (f['t'], f['vx'], 100 * (f['vx'] / ro['v_closed'] - 1),
                                                                  f['roll']) for f in fl))
               + (' ' + NOTES[name] if name in NOTES else ''), '']
    for name, _ in EXAMPLES:
        if name in res and os.path.exists(os.path.join(ROOT, 'docs', name + '_energies.png')):
            what = 'energies (with the dissipated D and E + D), L' if res[name].get('dissipated', 0) else 'energies, L'
            md.append('![%s: %s and J against time](../docs/%s_energies.png)' % (name, what, name))
    text = '\n'.join(md)
    print(text)
    replace_section(os.path.join(ROOT, 'perf', 'README.md'), 'examples', text)


if __name__ == '__main__':
    main()
