#!/usr/bin/python3
"""Memory per MPI rank: each rank's peak resident set (the line "emcontact: peak resident memory
per rank: ..." every successful run prints) for the ball (inputs/ball.xml) on 1, 2, 4 and 8
(oversubscribed) ranks, against the libraries' own footprint (the baseline: the tumbling box, 920 tets, one step, on
2 ranks: rank 0's peak and the other rank's). The ball runs the `impact` phase of scaling_report.py (centre 5 mm above the ground,
(2, 0, -3) m/s): two steps, the first in flight, the second with contact, with a field frame
written at every step (Output/every = 1, so that the output's gathers to rank 0 are measured).
For each run: the peak per rank, (peak - baseline) per rank (rank 0's baseline for rank 0, the
other rank's for the others), the ideal share baseline + (1-rank peak - rank 0's baseline) / N,
bytes per tet per rank above the baseline, the set-up
and stepping seconds of the summary line and the output seconds (Teuchos timer "emcontact:
output", maximum over ranks). Writes perf/results/memory.json, perf/results/memory.png and the
table in perf/README.md between <!-- memory:begin --> and <!-- memory:end -->.

    /usr/bin/python3 perf/memory_report.py [--build build] [--sizes 0.0129 0.0081]
        [--ranks 1 2 4 8] [--big-ranks 1 4] [--steps 2]
    /usr/bin/python3 perf/memory_report.py --rewrite   # table, fit and plot from the JSON

The first size runs on --ranks, the others (heavy: GBs per run) on --big-ranks. Runs one at a
time; memory does not depend on the machine's load, the times do.
"""
import argparse, datetime, json, os, re, subprocess, sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from report_util import ENV, ROOT, replace_section  # noqa: E402
from scaling_report import PHASES  # noqa: E402

MEMORY = re.compile(r'emcontact: peak resident memory per rank: (.*)')
SUMMARY = re.compile(r'emcontact: (\d+) tets, (\d+) nodes on (\d+) rank\(s\); setup ([\d.]+) s; (\d+) steps to '
                     r't = \S+ in ([\d.]+) s')


def per_rank_mib(line):
    """The per-rank numbers of the memory line (up to 8 ranks: one per rank, rank 0 first)."""
    if 'median' in line:
        sys.exit('more than 8 ranks: the line holds min/median/max only: %s' % line)
    return [int(x) for x in line.split('MiB')[0].split()]


def emcontact(build, ranks, args, out):
    cmd = []
    if ranks > 1:
        cmd += ['mpirun', '--oversubscribe', '--mca', 'mpi_yield_when_idle', '1', '--bind-to', 'none', '-np', str(ranks)]
    cmd += [os.path.join(build, 'bin', 'emcontact')] + args + [
        '--output', out, '--overwrite', '--set', 'Output/plot=false', '--set', 'Output/progress=false']
    p = subprocess.run(cmd, capture_output=True, text=True, env=ENV, cwd=ROOT)
    if p.returncode != 0:
        sys.exit('failed: %s\n%s%s' % (' '.join(cmd), p.stdout[-3000:], p.stderr[-3000:]))
    m, s = MEMORY.search(p.stdout), SUMMARY.search(p.stdout)
    r = dict(command=' '.join(cmd), ranks=int(s[3]), tets=int(s[1]), nodes=int(s[2]), setup_s=float(s[4]),
             steps=int(s[5]), stepping_s=float(s[6]), peak_mib=per_rank_mib(m[1]))
    tm = re.search(r'emcontact: output\s+(.*)', p.stdout)  # maximum over ranks on 2+ ranks
    nums = re.findall(r'([\d.e+-]+) \(', tm[1]) if tm else []
    r['output_s'] = float(nums[2] if len(nums) >= 3 else nums[0]) if nums else 0.0
    return r


def ball(build, size, ranks, steps):
    out = os.path.join('out', 'memory_%s_np%d' % (size, ranks))
    args = ['inputs/ball.xml', '--set', 'Bodies/ball/Mesh/size=%s' % size, '--set', 'Time/end=%g' % (steps * 0.001),
            '--set', 'Output/every=1'] + PHASES['impact']
    r = emcontact(build, ranks, args, out)
    r['size'] = size
    with open(os.path.join(ROOT, out, 'monitors.csv')) as f:
        rows = f.read().splitlines()[2:]  # the header, then row 0 (the initial state)
    head = open(os.path.join(ROOT, out, 'monitors.csv')).readline().strip().split(',')
    col = head.index('active_contacts')
    r['contact_steps'] = sum(1 for x in rows if int(x.split(',')[col]) > 0)
    return r


def derived(r, one, base):
    """(peak - baseline) per rank, the ideal share of the 1-rank run's part above the baseline
    (base: rank 0's and another rank's), bytes per tet per rank above the baseline."""
    n = r['ranks']
    ideal = [b + (one['peak_mib'][0] - base[0]) / n for b in (base[0], base[1])]
    above = [p - base[min(k, 1)] for k, p in enumerate(r['peak_mib'])]
    return dict(above_mib=above, ideal_mib=ideal if n > 1 else ideal[:1],
                bytes_per_tet=[a * 1048576.0 / r['tets'] for a in above])


def row(r, d):
    p = r['peak_mib']
    return '| %d | %d | %s | %s | %s | %s | %.1f | %.2f | %.2f |' % (
        r['tets'], r['ranks'], ' '.join('%d' % x for x in p), ' '.join('%d' % x for x in d['above_mib']),
        ' '.join('%.0f' % x for x in d['ideal_mib']), ' '.join('%.0f' % x for x in d['bytes_per_tet']), r['setup_s'],
        r['stepping_s'] / max(r['steps'], 1), r['output_s'])


def fit(results, base):
    """Least squares over every rank of every run: peak - baseline = R tets + S tets / N (bytes),
    R the bytes per tet on every rank, S the distributed bytes per tet; rank 0 only
    on 1 rank (on more, its peak holds what is left of Gmsh's meshing: perf/README.md)."""
    import numpy as np
    rows, rhs = [], []
    for runs in results.values():
        for r in runs:
            n, t = r['ranks'], r['tets']
            for k, p in enumerate(r['peak_mib']):
                if k == 0 and n > 1:
                    continue
                rows.append([t, t / n])
                rhs.append((p - base[min(k, 1)]) * 1048576.0)
    (rep, dist), *_ = np.linalg.lstsq(np.array(rows), np.array(rhs), rcond=None)
    return dict(replicated_bytes_per_tet=rep, distributed_bytes_per_tet=dist)


def write(results, baseline, steps, argv):
    base = baseline['peak_mib']
    for runs in results.values():
        one = next(r for r in runs if r['ranks'] == 1)
        for r in runs:
            r.update(derived(r, one, base))
    f = fit(results, base)
    os.makedirs(os.path.join(ROOT, 'perf', 'results'), exist_ok=True)
    json.dump(dict(date=datetime.date.today().isoformat(), command=argv, steps=steps, baseline=baseline, fit=f,
                   runs=[r for runs in results.values() for r in runs]),
              open(os.path.join(ROOT, 'perf', 'results', 'memory.json'), 'w'), indent=1)
    plot(results, base, os.path.join(ROOT, 'perf', 'results', 'memory.png'))
    md = ['Measured by `/usr/bin/python3 perf/memory_report.py%s` (`inputs/ball.xml`, the `impact` phase of '
          '`scaling_report.py`: %d steps, the first in flight, the second with contact; a field frame at every step; '
          'Belos GMRES + ILU(0), Kokkos Serial). Peak resident memory per rank from the run\'s line "emcontact: peak '
          'resident memory per rank", in MiB, rank 0 first. Baseline: the tumbling box (`inputs/tumbling_box.xml`, '
          '920 tets, one step) on 2 ranks, the libraries\' own footprint: %d MiB on rank 0, '
          '%d MiB on the other rank; "peak - baseline" takes rank 0\'s for rank 0 and the '
          'other\'s for the others. Ideal: baseline + (1-rank peak - rank 0\'s baseline) / N (rank 0\'s, then the '
          'others\'). Bytes per tet per rank: (peak - baseline) / tets. Times: set-up and seconds per step of '
          'the summary line, output seconds of the timer `emcontact: output` (maximum over ranks, whole run). The '
          'machine has 2 cores shared with other work, so runs on 4 and 8 ranks are oversubscribed and all times are '
          'noisy (compare them only roughly); the memory figures do not depend on the load.'
          % (''.join(' ' + x for x in argv), steps, base[0], base[1]), '',
          '| tets | ranks | peak per rank [MiB] | peak - baseline [MiB] | ideal [MiB] | bytes/tet per rank | '
          'set-up [s] | step [s] | output [s] |',
          '|---|---|---|---|---|---|---|---|---|']
    for runs in results.values():
        md += [row(r, r) for r in runs]
    md += ['', 'Fitted over every run and rank but rank 0 on 2+ ranks (least squares, peak - baseline = R tets + '
           'S tets / N): R = %.0f bytes per tet on every rank (what is not divided among the ranks: '
           'ghosts, interface rows, surfaces), S = %.0f bytes per tet shared by the ranks.' % (f['replicated_bytes_per_tet'], f['distributed_bytes_per_tet']),
           '', '![peak resident memory per rank](results/memory.png)']
    text = '\n'.join(md)
    print(text)
    replace_section(os.path.join(ROOT, 'perf', 'README.md'), 'memory', text, '## Memory per rank')


def plot(results, base, path):
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.ticker  # noqa: F401 (matplotlib.ticker below)
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for (tets, runs), c in zip(sorted(results.items()), ('C0', 'C1', 'C2')):
        one = next(r for r in runs if r['ranks'] == 1)['peak_mib'][0]
        ns = [r['ranks'] for r in runs]
        ax.plot(ns, [r['peak_mib'][0] for r in runs], 'o-', color=c, label='%d tets: rank 0' % tets)
        ax.plot(ns, [max(r['peak_mib'][1:]) if r['ranks'] > 1 else r['peak_mib'][0] for r in runs], 's--',
                color=c, label='%d tets: largest other rank' % tets)
        fine = [1 + k * (max(ns) - 1) / 100 for k in range(101)]
        ax.plot(fine, [base[0] + (one - base[0]) / n for n in fine], ':', color=c,
                label='%d tets: ideal, baseline + (1-rank peak - baseline) / N' % tets)
    ax.axhline(base[0], color='gray', lw=0.8, label='baseline (tumbling box), rank 0')
    ax.axhline(base[1], color='gray', lw=0.8, ls='--', label='baseline (tumbling box), other ranks')
    ax.set_xscale('log', base=2)
    ax.set_yscale('log')
    ax.set_yticks([125, 250, 500, 1000, 2000, 4000])
    ax.yaxis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
    ax.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.set_xlabel('MPI ranks')
    ax.set_ylabel('peak resident memory per rank [MiB]')
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--build', default='build')
    ap.add_argument('--sizes', nargs='+', default=['0.0129', '0.0081'])
    ap.add_argument('--ranks', nargs='+', type=int, default=[1, 2, 4, 8])
    ap.add_argument('--big-ranks', nargs='+', type=int, default=[1, 4])
    ap.add_argument('--steps', type=int, default=2)
    ap.add_argument('--rewrite', action='store_true', help='the table and plot from perf/results/memory.json')
    a = ap.parse_args()
    if a.rewrite:
        return rewrite()
    build = os.path.join(ROOT, a.build)
    baseline = emcontact(build, 2, ['inputs/tumbling_box.xml', '--set', 'Time/end=0.01'], 'out/memory_baseline')
    print(baseline, flush=True)
    results = {}
    for k, size in enumerate(a.sizes):
        runs = []
        for n in (a.ranks if k == 0 else a.big_ranks):
            runs.append(ball(build, size, n, a.steps))
            print(runs[-1], flush=True)
        results[runs[0]['tets']] = runs
    write(results, baseline, a.steps, sys.argv[1:])


def rewrite():
    """--rewrite: the table, fit and plot again from perf/results/memory.json, without running."""
    d = json.load(open(os.path.join(ROOT, 'perf', 'results', 'memory.json')))
    results = {}
    for r in d['runs']:
        results.setdefault(r['tets'], []).append(r)
    write(results, d['baseline'], d.get('steps', 2), d.get('command', []))


if __name__ == '__main__':
    main()
