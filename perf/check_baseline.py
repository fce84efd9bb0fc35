#!/usr/bin/python3
"""Benchmarks in CI against a baseline (perf/README.md, "Benchmarks in CI against a baseline").

Runs one case, writes its result as JSON and compares it with the case's entry of the committed
baseline (perf/baseline.json):

    check_baseline.py bench NAME --binary B --filter REGEX [--min-time S] COMMON
        a Google Benchmark binary, its selected benchmarks, CPU time per iteration
    check_baseline.py solver NAME --binary emcontact --input XML [--set K=V ...] COMMON
        one run of the solver on one rank: its CPU time and its monitors' per-step counters
    check_baseline.py compare RESULT BASELINE
        the comparison alone, of a result file written by the two above

    COMMON: --calibrate emc_calibrate --baseline perf/baseline.json --results DIR --work DIR

Times are normalised by a calibration measured in the same run (emc_calibrate, a STREAM-triad
sweep over arrays far larger than the cache: CPU seconds per sweep, the median of its sweeps,
taken before and after the case and averaged): normalised = CPU time / calibration. A case
fails when a normalised time exceeds TIME_RATIO times the baseline's, when a benchmark is missing
or new, or when a counter differs (Krylov iterations: within a tolerance, see COUNTERS). CPU
time, not wall time: a process that waits for a core on a busy machine is not charged for it.

With EMC_REGENERATE_BASELINE=1 the case's entry of the baseline is rewritten from this run
(nothing is compared). The result is written to DIR/ci-NAME.json in every mode.
Only the standard library; exit 0 pass, 1 fail, 2 usage or a run that failed.
"""
import argparse
import csv
import datetime
import fcntl
import json
import os
import platform
import re
import resource
import subprocess
import sys
import time

# A normalised time may be this many times the baseline's. The calibration removes the machine's
# speed (a memory-bound loop: the benchmarks here are memory- and cache-bound as much as
# compute-bound); what remains on a shared machine (other processes' cache and memory traffic,
# frequency changes, a calibration and a case that see different load) put the ratios between
# 0.65 and 1.6 in repeated runs on the project's busy 2-core VM. 2x leaves room for that; a
# regression of 3x or more fails.
TIME_RATIO = 2.0

# The monitors.csv columns compared per step (docs/user-guide.md, "Output"): name -> tolerance.
# None: exactly. "solves": |result - baseline| <= the step's Newton iterations, i.e. at most one
# Krylov iteration per linear solve (each Newton iteration is one solve). GMRES stops at the first
# iteration whose residual falls below its tolerance; the residual history carries the round-off
# of the BLAS/LAPACK and compiler the binary runs with (another CPU's vector width, another
# OpenBLAS kernel), which can move that crossing by one iteration on another machine. The other
# counts are the method's decisions (Newton's convergence, the active set) and must not move.
COUNTERS = {
    "newton_iterations": None,
    "linear_iterations": "solves",
    "contact_resolves": None,
    "active_contacts": None,
}


# Google Benchmark's own fields of a benchmark's JSON entry; the other numbers are its counters:
# those named *_per_s are rates (timings), the rest sizes that the benchmark fixes (compared
# exactly, as a changed problem would make its time meaningless).
GB_FIELDS = {"family_index", "per_family_instance_index", "repetitions", "repetition_index",
             "threads", "iterations", "real_time", "cpu_time"}


def cpu_children():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run(cmd, **kw):
    """Runs cmd; returns its CPU seconds, wall seconds and stdout; exits 2 if it fails."""
    c0, w0 = cpu_children(), time.monotonic()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, **kw)
    except OSError as e:
        print("check_baseline: cannot run %s: %s" % (cmd[0], e.strerror))
        sys.exit(2)
    cpu, wall = cpu_children() - c0, time.monotonic() - w0
    if p.returncode != 0:
        sys.stderr.write(p.stdout[-4000:] + p.stderr[-4000:])
        print("check_baseline: %s exited %d" % (" ".join(cmd), p.returncode))
        sys.exit(2)
    return cpu, wall, p.stdout


def calibrate(binary):
    """The calibration loop's JSON (emc_calibrate)."""
    return json.loads(run([binary])[2])


def bench_case(a):
    """Runs the benchmarks; returns (times, counters, command)."""
    out = os.path.join(a.work, "benchmark.json")
    if os.path.exists(out):
        os.remove(out)  # an earlier run's output must not pass for this one's
    cmd = [os.path.abspath(a.binary), "--benchmark_filter=" + a.filter,
           "--benchmark_min_time=%g" % a.min_time, "--benchmark_out=" + os.path.basename(out),
           "--benchmark_out_format=json"]
    run(cmd, cwd=a.work)
    with open(out) as f:
        data = json.load(f)
    times, counters = {}, {}
    for b in data["benchmarks"]:
        if b.get("run_type", "iteration") != "iteration":
            continue
        if b.get("error_occurred"):
            print("check_baseline: %s: %s" % (b["name"], b.get("error_message", "failed")))
            sys.exit(2)
        scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b["time_unit"]]
        times[b["name"]] = {"cpu_s": b["cpu_time"] * scale, "real_s": b["real_time"] * scale,
                            "iterations": b["iterations"]}
        for key, value in b.items():  # the benchmark's sizes (tets, facets, colours, nnz, ...)
            number = isinstance(value, (int, float)) and not isinstance(value, bool)
            if number and key not in GB_FIELDS and not key.endswith("_per_s"):
                counters["%s:%s" % (b["name"], key)] = value
    if not times:
        print("check_baseline: %s ran no benchmark (filter %r)" % (a.binary, a.filter))
        sys.exit(2)
    return times, counters, cmd


def read_monitors(path):
    """The per-step columns of COUNTERS from a monitors.csv (its rows: step 0, the initial state,
    then one per accepted step) and the last step's number."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    counters = {k: [int(r[k]) for r in rows] for k in COUNTERS}
    counters["steps"] = int(rows[-1]["step"]) if rows else 0
    return counters


def solver_case(a):
    """Runs the solver once; returns (times, counters, command)."""
    out = os.path.join(a.work, "out")
    cmd = [a.binary, a.input, "--output", out, "--overwrite", "--set", "Output/plot=false",
           "--set", "Output/progress=false", "--set", "Output/every=0"]
    for s in a.set:
        cmd += ["--set", s]
    monitors = os.path.join(out, "monitors.csv")
    if os.path.exists(monitors):
        os.remove(monitors)
    cpu, wall, stdout = run(cmd)
    counters = read_monitors(monitors)
    m = re.search(r"^emcontact: (\d+) tets, (\d+) nodes on (\d+) rank", stdout, re.M)
    if not m:
        print("check_baseline: no 'emcontact: N tets, M nodes on R rank(s)' line in its output")
        sys.exit(2)
    counters.update(tets=int(m.group(1)), nodes=int(m.group(2)), ranks=int(m.group(3)))
    return {"run": {"cpu_s": cpu, "real_s": wall, "iterations": 1}}, counters, cmd


def compare(result, base):
    """The problems of result against the baseline's entry base (a list of lines; empty: pass)."""
    name = result["name"]
    problems = []
    if base is None:
        return ["%s: no entry in the baseline (regenerate it: EMC_REGENERATE_BASELINE=1)" % name]
    cal, base_cal = result["calibration"]["seconds"], base["calibration_s"]
    for bench, t in sorted(result["times"].items()):
        if bench not in base["times"]:
            problems.append("%s: %s is not in the baseline (regenerate it)" % (name, bench))
    for bench, bt in sorted(base["times"].items()):
        t = result["times"].get(bench)
        if t is None:
            problems.append("%s: %s of the baseline did not run" % (name, bench))
            continue
        ratio = (t["cpu_s"] / cal) / (bt["cpu_s"] / base_cal)
        if not ratio <= TIME_RATIO:
            problems.append("%s: %s normalised time %.3g x the baseline's (allowed: at most %g)"
                            % (name, bench, ratio, TIME_RATIO))
    problems += compare_counters(name, result.get("counters", {}), base.get("counters", {}))
    return problems


def compare_counters(name, got, want):
    problems = []
    for key in sorted(set(got) | set(want)):
        if key not in got or key not in want:
            where = "result" if key in got else "baseline"
            problems.append("%s: counter %s only in the %s" % (name, key, where))
            continue
        g, w = got[key], want[key]
        if not isinstance(w, list):
            if g != w:
                problems.append("%s: %s = %s, baseline %s" % (name, key, g, w))
            continue
        if len(g) != len(w):
            problems.append("%s: %s has %d steps, baseline %d" % (name, key, len(g), len(w)))
            continue
        solves = want.get("newton_iterations", [0] * len(w))
        for step, (x, y) in enumerate(zip(g, w), 1):
            allowed = solves[step - 1] if COUNTERS.get(key) == "solves" else 0
            if abs(x - y) > allowed:
                problems.append("%s: %s at step %d = %d, baseline %d (allowed: +-%d)"
                                % (name, key, step, x, y, allowed))
                break
    return problems


def ratios(result, base):
    if base is None:
        return {}
    cal, base_cal = result["calibration"]["seconds"], base["calibration_s"]
    return {b: (t["cpu_s"] / cal) / (base["times"][b]["cpu_s"] / base_cal)
            for b, t in result["times"].items() if b in base["times"]}


def machine():
    model = ""
    try:
        with open("/proc/cpuinfo") as f:
            model = next((l.split(":", 1)[1].strip() for l in f if l.startswith("model name")), "")
    except OSError:
        pass
    return {"host": platform.node(), "cpu": model, "cpus": os.cpu_count(),
            "load": list(os.getloadavg()), "date": datetime.date.today().isoformat()}


def write_json(path, data):
    tmp = path + ".tmp.%d" % os.getpid()
    with open(tmp, "w") as f:
        json.dump(data, f, indent=1, sort_keys=True)
        f.write("\n")
    os.replace(tmp, path)


def regenerate(path, result, lock_dir):
    """Rewrites the case's entry of the baseline (other cases kept; locked, in lock_dir, against
    the other cases' tests running beside this one)."""
    with open(os.path.join(lock_dir, "baseline.lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        data = {"cases": {}}
        if os.path.exists(path):
            with open(path) as f:
                data = json.load(f)
        data["about"] = ("emcontact's benchmarks in CI: perf/check_baseline.py compares each "
                         "case's CPU times, normalised by the calibration, and its counters with "
                         "these; regenerate with EMC_REGENERATE_BASELINE=1 ctest -L perf "
                         "(perf/README.md)")
        data["cases"][result["name"]] = {
            "command": [os.path.basename(c) if os.path.isabs(c) else c for c in result["command"]],
            "calibration_s": result["calibration"]["seconds"],
            "calibration": result["calibration"], "machine": result["machine"],
            "times": {b: {"cpu_s": t["cpu_s"], "real_s": t["real_s"],
                          "normalised": t["normalised"]} for b, t in result["times"].items()},
            "counters": result["counters"]}
        write_json(path, data)


def load_baseline(path, name):
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f).get("cases", {}).get(name)


def report(result):
    for p in result["problems"]:
        print(p)
    for b, r in sorted(result["ratios"].items()):
        t = result["times"][b]
        print("%-50s cpu %.4g s  normalised %.4g  ratio %.3f" % (b, t["cpu_s"], t["normalised"], r))
    c = result["calibration"]
    print("calibration %.4g s per sweep (%.3g GB/s); %s: %s" % (
        c["seconds"], c["gbytes_per_s"], result["name"], "pass" if result["passed"] else "FAIL"))
    return 0 if result["passed"] else 1


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = p.add_subparsers(dest="mode", required=True)
    for mode in ("bench", "solver"):
        s = sub.add_parser(mode)
        s.add_argument("name")
        s.add_argument("--binary", required=True)
        s.add_argument("--calibrate", required=True)
        s.add_argument("--baseline", required=True)
        s.add_argument("--results", required=True)
        s.add_argument("--work", required=True)
        if mode == "bench":
            s.add_argument("--filter", required=True)
            s.add_argument("--min-time", type=float, default=0.05)
        else:
            s.add_argument("--input", required=True)
            s.add_argument("--set", action="append", default=[])
    c = sub.add_parser("compare")
    c.add_argument("result")
    c.add_argument("baseline")
    a = p.parse_args()

    if a.mode == "compare":
        with open(a.result) as f:
            result = json.load(f)
        base = load_baseline(a.baseline, result["name"])
        result["problems"] = compare(result, base)
        result["ratios"] = ratios(result, base)
        result["passed"] = not result["problems"]
        return report(result)

    os.makedirs(a.work, exist_ok=True)
    os.makedirs(a.results, exist_ok=True)
    before = calibrate(a.calibrate)
    times, counters, cmd = (bench_case if a.mode == "bench" else solver_case)(a)
    after = calibrate(a.calibrate)
    cal = dict(after, before_s=before["median_cpu_s"], after_s=after["median_cpu_s"],
               seconds=0.5 * (before["median_cpu_s"] + after["median_cpu_s"]))
    cal["gbytes_per_s"] = cal["bytes_per_sweep"] / cal["seconds"] * 1e-9
    for t in times.values():
        t["normalised"] = t["cpu_s"] / cal["seconds"]
    result = {"name": a.name, "kind": a.mode, "command": cmd, "calibration": cal,
              "times": times, "counters": counters, "machine": machine(),
              "time_ratio_allowed": TIME_RATIO}
    regen = os.environ.get("EMC_REGENERATE_BASELINE") == "1"
    base = None if regen else load_baseline(a.baseline, a.name)
    result["problems"] = [] if regen else compare(result, base)
    result["ratios"] = ratios(result, base)
    result["passed"] = not result["problems"]
    write_json(os.path.join(a.results, "ci-%s.json" % a.name), result)
    if regen:
        regenerate(a.baseline, result, a.results)
        print("check_baseline: %s rewritten in %s" % (a.name, a.baseline))
    return report(result)


if __name__ == "__main__":
    sys.exit(main())
