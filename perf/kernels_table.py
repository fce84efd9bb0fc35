#!/usr/bin/python3
"""Writes the kernel benchmark table (from Google Benchmark's JSON files: bench_kernels, then
bench_search) into perf/README.md between <!-- kernels:begin --> and <!-- kernels:end -->."""
import json, os, re, sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from report_util import ROOT, replace_section  # noqa: E402

d = json.load(open(sys.argv[1]))
ctx = d['context']
head = ['Measured on %s (%d CPUs at %s MHz; Kokkos Serial, one core per process) with '
        '`bash perf/run_benchmarks.sh`.' % (ctx.get('host_name', '?'), ctx['num_cpus'], ctx['mhz_per_cpu'])]
for extra_json in sys.argv[2:]:  # later files replace the rows of the same name
    e = json.load(open(extra_json))
    names = {b['name'] for b in e['benchmarks']}
    d['benchmarks'] = [b for b in d['benchmarks'] if b['name'] not in names] + e['benchmarks']
    c = e['context']
    head.append('Rows of `%s`: from a separate run (load average %s).' % (
        os.path.basename(c.get('executable', extra_json)),
        ', '.join('%.1f' % v for v in c.get('load_avg', []))))
rows = [' '.join(head), '', '| benchmark | time per iteration | rate per core | target |', '|---|---|---|---|']
targets = {'BM_EmTet4': '-', 'BM_Assembly': '1M tets/s', 'BM_ContactSearch': '-', 'BM_ContactGridBuild': '-',
           'BM_ContactQueries': '4M queries/s', 'BM_ContactQueriesOrdered': '6M queries/s',
           'BM_ContactQueriesBatch': '4M queries/s', 'BM_ContactLocateAll': '4M queries/s',
           'BM_ContactQueries/32': '- (all in cache)'}
for b in d['benchmarks']:
    name = b['name']
    if name.startswith('BM_Elimination'):  # per Newton iteration, no rate target
        master = ('rigid master: masked A' if 'Rigid' in name else
                  'deformable master moving to the next facet: pattern rebuilt' if 'NewPattern' in name else
                  'deformable master: structured reduction, pattern kept')
        rows.append('| %s (%d dofs, %d slave dofs, %s; P^T A P + D, P^T g, P dq) | %.3g %s | %.3g M dofs/s | - |' % (
            name, b['dofs'], b['slave_dofs'], master, b['real_time'], b['time_unit'],
            b['dofs'] / (b['real_time'] * {'ms': 1e-3, 'us': 1e-6, 'ns': 1e-9, 's': 1}[b['time_unit']]) / 1e6))
        continue
    rate = b.get('tets_per_s') or b.get('queries_per_s') or b.get('facets_per_s')
    unit = 'tets/s' if 'tets_per_s' in b else ('queries/s' if 'queries_per_s' in b else 'facets/s')
    notes = {'BM_ContactSearch': 'grid rebuilt for every 100k random queries', 'BM_ContactQueries': 'random order',
             'BM_ContactGridBuild': 'parallel build from Views',
             'BM_ContactQueriesOrdered': 'queries in spatial order',
             'BM_ContactQueriesBatch': 'random order, batch query cell by cell, sort included',
             'BM_ContactLocateAll': 'random order, parallel locate_all on Views, sort by cell included'}
    extra = ' (%d tets)' % b['tets'] if 'tets' in b else (
        ' (%d facets, %s)' % (b['facets'], notes.get(name.split('/')[0], '')) if 'facets' in b else '')
    rows.append('| %s%s | %.3g %s | %.3gM %s | %s |' % (name, extra, b['real_time'], b['time_unit'], rate / 1e6, unit,
                                                      targets.get(name, targets.get(name.split('/')[0], '-'))))
text = '\n'.join(rows)
print(text)
replace_section(os.path.join(ROOT, 'perf', 'README.md'), 'kernels', text)
