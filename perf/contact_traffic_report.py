#!/usr/bin/python3
"""What each rank holds and receives of contact (docs/THEORY.md §8), on the ball's impact phase
(the ball 5 mm above the ground, moving down at 3 m/s; most steps have contact) at two mesh
sizes on 1 and 2 ranks: the rank's contact nodes (largest over the ranks), those owned by other
ranks and the bytes it receives per import of their positions, the number of imports; against
what replicating every position (the design before §8) costs: 3 N doubles on every rank and
24 (N - N/ranks) bytes received per import. Also the contact time per step against the
assembly's (Teuchos timers, largest over the ranks). Writes perf/results/contact_traffic.json
and the table in perf/README.md between <!-- contact_traffic:begin --> and
<!-- contact_traffic:end -->.

    /usr/bin/python3 perf/contact_traffic_report.py [--build build] [--steps 6] [--sizes 0.026 0.0129]
"""
import argparse, json, os, re, subprocess, sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from report_util import ENV, ROOT, replace_section  # noqa: E402

IMPACT = ['--set', 'Bodies/ball/Mesh/center={0, 0, 0.405}', '--set', 'Bodies/ball/Initial/velocity={2, 0, -3}']


def timer(stdout, name, steps):
    tm = re.search(r'^emcontact: %s\s+([\d.e+-]+ \(.*)' % re.escape(name), stdout, re.M)
    if not tm:
        return 0.0
    nums = re.findall(r'([\d.e+-]+) \(', tm[1])
    return float(nums[2] if len(nums) >= 3 else nums[0]) / steps


def run(build, size, ranks, steps, preconditioner):
    out = os.path.join('out', 'traffic_%s_np%d' % (size, ranks))
    cmd = []
    if ranks > 1:
        cmd += ['mpirun', '--oversubscribe', '--mca', 'mpi_yield_when_idle', '1', '--bind-to', 'none', '-np', str(ranks)]
    cmd += [os.path.join(build, 'bin', 'emcontact'), 'inputs/ball.xml', '--output', out, '--overwrite',
            '--set', 'Bodies/ball/Mesh/size=%s' % size, '--set', 'Time/end=%g' % (steps * 0.001),
            '--set', 'Output/every=0', '--set', 'Output/plot=false', '--set', 'Output/progress=false',
            '--set', 'Solver/Linear/preconditioner=%s' % preconditioner] + IMPACT
    p = subprocess.run(cmd, capture_output=True, text=True, env=ENV, cwd=ROOT)
    if p.returncode != 0:
        sys.exit('failed: %s\n%s%s' % (' '.join(cmd), p.stdout, p.stderr[-3000:]))
    m = re.search(r'emcontact: (\d+) tets, (\d+) nodes on (\d+) rank\(s\).*?(\d+) steps to', p.stdout)
    c = re.search(r'emcontact: (\d+) contact nodes per rank \((\d+) owned by other ranks\), (\d+) bytes received per '
                  r'import of their positions, (\d+) imports', p.stdout)
    r = dict(size=size, tets=int(m[1]), nodes=int(m[2]), ranks=int(m[3]), steps=int(m[4]),
             contact_nodes=int(c[1]), remote=int(c[2]), bytes_per_import=int(c[3]), imports=int(c[4]))
    r['assembly_s'] = timer(p.stdout, 'assembly', r['steps'])
    r['contact_s'] = timer(p.stdout, 'contact', r['steps'])
    for k, name in (('select_s', 'contact: node selection'), ('activation_s', 'contact: activation'),
                    ('rows_s', 'contact: chains and rows')):
        r[k] = timer(p.stdout, name, r['steps'])
    r['replicated_bytes'] = 24 * (r['nodes'] - r['nodes'] // r['ranks'])
    return r


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--build', default='build')
    ap.add_argument('--steps', type=int, default=6)
    ap.add_argument('--sizes', nargs='+', default=['0.026', '0.0129'])
    ap.add_argument('--preconditioner', default='muelu')
    a = ap.parse_args()
    rows = [run(a.build, s, n, a.steps, a.preconditioner) for s in a.sizes for n in (1, 2)]
    os.makedirs(os.path.join(ROOT, 'perf', 'results'), exist_ok=True)
    with open(os.path.join(ROOT, 'perf', 'results', 'contact_traffic.json'), 'w') as f:
        json.dump(rows, f, indent=1)
    lines = ['Measured by `/usr/bin/python3 perf/contact_traffic_report.py --steps %d --sizes %s` (the '
             'ball\'s impact phase, `preconditioner = %s`; largest over the ranks).' % (
                 a.steps, ' '.join(a.sizes), a.preconditioner), '',
             '| tets | nodes | ranks | contact nodes per rank | of which remote | bytes received per import | '
             'imports per step | replicated: doubles per rank / bytes per import | contact / assembly s per step | '
             'of contact: selection / activation / chains and rows (host) |',
             '|---|---|---|---|---|---|---|---|---|---|']
    for r in rows:
        lines.append('| %d | %d | %d | %d (%.1f%% of the nodes) | %d | %d | %.1f | %d / %d | %.4f / %.4f (%.1f%%) | %.4f / %.4f / %.4f |' % (
            r['tets'], r['nodes'], r['ranks'], r['contact_nodes'], 100.0 * r['contact_nodes'] / r['nodes'],
            r['remote'], r['bytes_per_import'], r['imports'] / r['steps'], 3 * r['nodes'], r['replicated_bytes'],
            r['contact_s'], r['assembly_s'], 100 * r['contact_s'] / max(r['assembly_s'], 1e-12),
            r['select_s'], r['activation_s'], r['rows_s']))
    replace_section(os.path.join(ROOT, 'perf', 'README.md'), 'contact_traffic', '\n'.join(lines),
                    '## Contact memory and traffic per rank')
    print('\n'.join(lines))


if __name__ == '__main__':
    main()
