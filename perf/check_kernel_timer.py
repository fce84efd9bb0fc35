#!/usr/bin/python3
"""The kernel timer (perf/kernel_timer.cpp) loaded into a short run of tests/regression/drop.xml:
its table must list the element kernel and contact's activation kernel with calls > 0, and the
kernels' seconds must add up to less than the run's wall time (they are parts of it).

    /usr/bin/python3 perf/check_kernel_timer.py BINARY LIBRARY WORKDIR
"""
import os, subprocess, sys, time

binary, library, work = sys.argv[1:4]
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
os.makedirs(work, exist_ok=True)
times = os.path.join(work, 'kernel_times.txt')
if os.path.exists(times):
    os.remove(times)  # a table left by an earlier run must not pass for this one's
env = dict(os.environ, KOKKOS_PROFILE_LIBRARY=library, KOKKOS_TOOLS_LIBS=library, EMC_KERNEL_TIMES=times)
start = time.monotonic()
subprocess.run([binary, os.path.join(root, 'tests', 'regression', 'drop.xml'), '--output', os.path.join(work, 'out'),
                '--overwrite', '--set', 'Output/plot=false', '--set', 'Output/progress=false'],
               env=env, check=True, capture_output=True)
wall = time.monotonic() - start
if not os.path.exists(times):
    sys.exit('no %s: the kernel timer %s was not loaded' % (times, library))
rows = {}
for line in open(times):
    if line.startswith('#'):
        continue
    seconds, calls, name = line.split(None, 2)
    rows[name.strip()] = (float(seconds), int(calls))
ok = True
for label in ('emcontact::fem::em_tet4', 'emcontact::contact::detect'):
    if rows.get(label, (0, 0))[1] <= 0:
        print('no calls of %s in %s' % (label, times))
        ok = False
total = sum(s for s, _ in rows.values())
if not 0 < total < wall:
    print('kernels %.3f s against a wall time of %.3f s' % (total, wall))
    ok = False
print('%d kernels, %.3f s of %.3f s' % (len(rows), total, wall))
sys.exit(0 if ok else 1)
