#!/usr/bin/python3
"""Thread scaling with an OpenMP build of Kokkos (perf/build_trilinos_openmp.sh, then emcontact
built against it, e.g. in build-omp/): the assembly benchmark (BM_Assembly) and whole runs of
the ball (flight and impact phases, as perf/scaling_report.py) with OMP_NUM_THREADS = each of
--threads on each of --ranks (ranks x threads). Efficiency = t(1 rank, first thread count) /
(R N t(R ranks, N threads)). With --repeat R each run (and the benchmark) is
made R times, the thread counts interleaved (1, 2, 1, 2, ...) so that a drift of the shared
machine's speed hits both alike, and each time (the wall time per step and every timer) is the
smallest of the R, each benchmark rate the largest: the run least disturbed by other work. Each
run is made with each of --preconditioners (Solver/Linear/preconditioner); the column "against
the first" is the first preconditioner's time on the first thread count over this run's. Writes
perf/results/threads.json, the plot perf/results/threads.png (the whole step's speed-up against
cores, R N, per phase, size and preconditioner, with the ideal line) and the table in
perf/README.md between <!-- threads:begin --> and <!-- threads:end -->.

    /usr/bin/python3 perf/threads_report.py --build build-omp [--threads 1 2] [--ranks 1 2]
        [--sizes 0.026 0.0129] [--repeat 3] [--preconditioners ilu chebyshev]
"""
import argparse, datetime, json, os, subprocess, sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from report_util import ENV, ROOT, replace_section  # noqa: E402
from scaling_report import CONTACT_TIMERS, TIMERS, run  # noqa: E402


def assembly_rate(build, threads):
    env = dict(ENV, OMP_NUM_THREADS=str(threads), OMP_PROC_BIND='spread', OMP_PLACES='threads')
    out = os.path.join(ROOT, 'out', 'threads_bench_%d.json' % threads)
    os.makedirs(os.path.dirname(out), exist_ok=True)
    subprocess.run([os.path.join(build, 'bin', 'bench_assembly'), '--benchmark_filter=BM_Assembly',
                    '--benchmark_min_time=1', '--benchmark_out=' + out, '--benchmark_out_format=json'],
                   env=env, check=True, capture_output=True)
    return {b['name']: b['tets_per_s'] for b in json.load(open(out))['benchmarks']}


def fastest(trials):
    """The first trial with each time (wall s/step and every timer) replaced by its minimum."""
    r = dict(trials[0], repeats=len(trials))
    for key in ('s_per_step',) + TIMERS + CONTACT_TIMERS:
        vals = [t[key] for t in trials if key in t]
        if vals:
            r[key] = min(vals)
    return r


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--build', default='build-omp')
    ap.add_argument('--threads', type=int, nargs='+', default=[1, 2])
    ap.add_argument('--ranks', type=int, nargs='+', default=[1], help='MPI ranks, each with --threads')
    ap.add_argument('--sizes', nargs='+', default=['0.026', '0.0129'])
    ap.add_argument('--steps', type=int, default=10)
    ap.add_argument('--phases', nargs='+', default=['flight', 'impact'])
    ap.add_argument('--repeat', type=int, default=1, help='runs per configuration; the fastest times are kept')
    ap.add_argument('--preconditioners', nargs='+', default=['ilu', 'chebyshev'])
    ap.add_argument('--from-json', action='store_true',
                    help='no runs: the tables from perf/results/threads.json, as measured with these arguments')
    a = ap.parse_args()
    if a.from_json:
        saved = json.load(open(os.path.join(ROOT, 'perf', 'results', 'threads.json')))
        return write_tables(a, saved['assembly'], saved['runs'])
    build = os.path.join(ROOT, a.build)
    os.makedirs(os.path.join(ROOT, 'perf', 'results'), exist_ok=True)
    bench = {n: {} for n in a.threads}  # the fastest of --repeat interleaved runs of each rate
    for _ in range(a.repeat):
        for n in a.threads:
            for name, rate in assembly_rate(build, n).items():
                bench[n][name] = max(rate, bench[n].get(name, 0))
    runs = []
    for phase in a.phases:
        for size in a.sizes:
            configs = [(p, r, n) for p in a.preconditioners for r in a.ranks for n in a.threads]
            trials = {c: [] for c in configs}
            for _ in range(a.repeat):
                for p, r, n in configs:
                    trials[p, r, n].append(dict(run(build, size, r, a.steps, phase, threads=n, preconditioner=p),
                                                prec_name=p))
            runs += [fastest(trials[c]) for c in configs]
    json.dump(dict(date=datetime.date.today().isoformat(), assembly=bench, runs=runs),
              open(os.path.join(ROOT, 'perf', 'results', 'threads.json'), 'w'), indent=1)
    write_tables(a, bench, runs)


def plot(runs, n1, path):
    """The whole step's speed-up t(1 rank, n1 threads) / t against cores (ranks x threads)."""
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4))
    cores = sorted({r.get('ranks', 1) * r['threads'] for r in runs})
    for key in sorted({(r['phase'], r['tets'], r['prec_name']) for r in runs}):
        sel = [r for r in runs if (r['phase'], r['tets'], r['prec_name']) == key]
        one = next((r for r in sel if r.get('ranks', 1) == 1 and r['threads'] == n1), None)
        if one is None:
            continue
        for ranks in sorted({r.get('ranks', 1) for r in sel}):
            pts = sorted((r.get('ranks', 1) * r['threads'], one['s_per_step'] / r['s_per_step'])
                         for r in sel if r.get('ranks', 1) == ranks)
            ax.plot([c for c, _ in pts], [v for _, v in pts], 'o-',
                    label='%s, %dk tets, %s, %d rank(s)' % (key[0], key[1] // 1000, key[2], ranks))
    ax.plot(cores, [c / cores[0] for c in cores], 'k--', label='ideal')
    ax.set_xlabel('cores (ranks x threads)')
    ax.set_ylabel('speed-up of the whole step')
    ax.set_xticks(cores)
    ax.legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def write_tables(a, assembly, runs):
    plot(runs, a.threads[0], os.path.join(ROOT, 'perf', 'results', 'threads.png'))
    bench = {int(n): rates for n, rates in assembly.items()}
    missing = sorted({t for r in runs for t in TIMERS if t not in r})
    n1 = a.threads[0]
    md = ['Measured by `/usr/bin/python3 perf/threads_report.py --build %s --steps %d --repeat %d --preconditioners %s` '
          '(Kokkos OpenMP, ranks %s x threads %s, `OMP_PROC_BIND=spread OMP_PLACES=threads`; the phases as in the '
          'scaling table; efficiency %d t_ref / (cores t), t_ref the time on 1 rank and %d thread(s), with the same '
          'preconditioner; each time the smallest of %d interleaved runs, each rate '
          'the largest%s).' % (a.build, a.steps, a.repeat, ' '.join(a.preconditioners),
                               ' '.join(map(str, a.ranks)), ' '.join(map(str, a.threads)), a.threads[0], a.threads[0],
                               a.repeat,
                               '; not recorded, n/a: the ' + ', '.join(missing) + ' timer' if missing else ''), '',
          '| benchmark | threads | tets/s | efficiency |', '|---|---|---|---|']
    for name in bench[n1]:
        for n in a.threads:
            md.append('| %s | %d | %.3gM | %.0f%% |' % (name, n, bench[n][name] / 1e6, 100 * bench[n][name] / (n * bench[n1][name])))
    md += ['', '| phase | tets | preconditioner | ranks | threads | wall s/step | Newton its/step | Krylov its/solve | s/step: ' +
           ' / '.join(TIMERS) + ' | efficiency | against the first |', '|---|---|---|---|---|---|---|---|---|---|---|']
    p1 = a.preconditioners[0]
    for r in runs:
        one = next(x for x in runs if x['phase'] == r['phase'] and x['size'] == r['size'] and x['threads'] == n1
                   and x.get('ranks', 1) == 1 and x['prec_name'] == r['prec_name'])
        first = next(x for x in runs if x['phase'] == r['phase'] and x['size'] == r['size'] and x['threads'] == n1
                     and x.get('ranks', 1) == 1 and x['prec_name'] == p1)
        cores = r.get('ranks', 1) * r['threads']
        md.append('| %s | %d | %s | %d | %d | %.4f | %.2f | %.1f | %s | %.0f%% | %.2fx |' % (
            r['phase'], r['tets'], r['prec_name'], r.get('ranks', 1), r['threads'], r['s_per_step'],
            r['newton_per_step'], r['krylov_per_solve'], ' / '.join('%.4f' % r[t] if t in r else 'n/a' for t in TIMERS),
            100 * one['s_per_step'] * n1 / (cores * r['s_per_step']), first['s_per_step'] / r['s_per_step']))
    md += ['', 'Contact (THEORY §8) in the impact phase with %s, s/step, and its share of the assembly:' % p1, '',
           '| tets | threads | contact | ' + ' | '.join(t.split(': ')[1] for t in CONTACT_TIMERS) +
           ' | contact / assembly | contact efficiency |', '|---|---|---|' + '---|' * len(CONTACT_TIMERS) + '---|---|']
    for r in runs:
        if r['phase'] != 'impact' or r['prec_name'] != p1 or r.get('ranks', 1) != 1:
            continue
        one = next(x for x in runs if x['phase'] == 'impact' and x['size'] == r['size'] and x['threads'] == n1
                   and x.get('ranks', 1) == 1 and x['prec_name'] == p1)
        md.append('| %d | %d | %.4f | %s | %.1f%% | %.0f%% |' % (
            r['tets'], r['threads'], r.get('contact', 0), ' | '.join('%.4f' % r.get(t, 0) for t in CONTACT_TIMERS),
            100 * r.get('contact', 0) / r['assembly'], 100 * one.get('contact', 0) / (r['threads'] * r.get('contact', 1e-300))))
    text = '\n'.join(md)
    print(text)
    replace_section(os.path.join(ROOT, 'perf', 'README.md'), 'threads', text, '## Thread scaling')


if __name__ == '__main__':
    main()
