#!/usr/bin/python3
"""Summarises an emcontact monitors.csv: steps, Newton iterations per step, the largest
relative drifts of E, L and J, and the contact periods (impacts). With friction (a
`dissipated` column D, docs/THEORY.md §11.2) also the largest |E + D - E0| / |E0| (the
conserved quantity) and the final D.

    /usr/bin/python3 tools/summarize_run.py DIR/monitors.csv [--json] [--markdown NAME]
"""
import argparse, csv, json, math, sys


def load(path):
    with open(path) as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def summarize(rows):
    r0 = rows[0]
    norm = lambda v: math.sqrt(sum(x * x for x in v))
    vec = lambda r, q: [r[q + c] for c in 'xyz']
    escale = abs(r0['total']) or max(r['kinetic'] + r['elastic'] + abs(r['potential']) for r in rows)
    s = dict(steps=len(rows) - 1, end_time=rows[-1]['time'])
    s['newton_per_step'] = sum(r['newton_iterations'] for r in rows[1:]) / max(1, len(rows) - 1)
    s['max_newton'] = max(int(r['newton_iterations']) for r in rows[1:]) if len(rows) > 1 else 0
    s['E_drift'] = max(abs(r['total'] - r0['total']) for r in rows) / escale
    # E + D: D (energy dissipated by friction) is 0 without friction, or in older files
    s['ED_drift'] = max(abs(r['total'] + r.get('dissipated', 0.0) - r0['total']) for r in rows) / escale
    s['dissipated'] = rows[-1].get('dissipated', 0.0)
    for q in 'LJ':
        ref = norm(vec(r0, q))
        d = max(norm([a - b for a, b in zip(vec(r, q), vec(r0, q))]) for r in rows)
        s[q + '_drift_abs'] = d
        s[q + '_initial'] = ref
        s[q + '_drift'] = d / ref if ref > 0 else float('nan')
        for c in 'xyz':
            s[q + c + '_drift_abs'] = max(abs(r[q + c] - r0[q + c]) for r in rows)
    periods, start = [], None
    for r in rows[1:]:
        if r['active_contacts'] > 0 and start is None:
            start = r['time']
        if r['active_contacts'] == 0 and start is not None:
            periods.append((start, r['time']))
            start = None
    if start is not None:
        periods.append((start, rows[-1]['time']))
    s['contact_periods'] = periods
    act = [r for r in rows[1:] if r['active_contacts'] > 0]
    s['max_active'] = int(max((r['active_contacts'] for r in act), default=0))
    s['gap_min'] = min((r['gap_min'] for r in act), default=0.0)
    s['gap_max'] = max((r['gap_max'] for r in act), default=0.0)
    s['resolves'] = int(sum(r.get('contact_resolves', 0) for r in rows))
    return s


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('csv')
    ap.add_argument('--json', action='store_true')
    a = ap.parse_args()
    s = summarize(load(a.csv))
    if a.json:
        json.dump(s, sys.stdout, indent=1)
        print()
        return
    print('%d steps to t = %g; Newton iterations per step %.2f (max %d)' % (
        s['steps'], s['end_time'], s['newton_per_step'], s['max_newton']))
    print('max |E-E0|/|E0| = %.2e; max |L-L0| = %.2e (relative %.2e); max |J-J0| = %.2e (relative %.2e)' % (
        s['E_drift'], s['L_drift_abs'], s['L_drift'], s['J_drift_abs'], s['J_drift']))
    if s['dissipated'] != 0:
        print('dissipated by friction D = %.6g; max |E+D-E0|/|E0| = %.2e' % (s['dissipated'], s['ED_drift']))
    print('contact periods: ' + ', '.join('%.3f-%.3f s' % p for p in s['contact_periods']))
    print('max active slave nodes %d; active gaps in [%.2e, %.2e] m; active-set re-solves %d' % (
        s['max_active'], s['gap_min'], s['gap_max'], s['resolves']))


if __name__ == '__main__':
    main()
