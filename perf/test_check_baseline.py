#!/usr/bin/python3
"""The comparison of perf/check_baseline.py, so that it cannot silently pass: the script runs on
stand-ins (a calibration and a Google Benchmark binary written here, whose times this test sets)
and on hand-made solver results. A normalised time 10x the baseline's fails, 1.5x passes, a
machine 10x slower in everything (calibration included) passes, a missing or new benchmark fails,
a changed counter fails, a Krylov count within one iteration per solve passes.

    /usr/bin/python3 perf/test_check_baseline.py
"""
import contextlib
import io
import json
import os
import subprocess
import sys
import tempfile
import textwrap
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.dont_write_bytecode = True  # nothing written into the source tree
import check_baseline  # noqa: E402

SCRIPT = os.path.join(HERE, "check_baseline.py")

# emc_calibrate's stand-in: prints FAKE_CAL_JSON (shell scripts: a Python start-up per call
# would take seconds on a busy machine)
FAKE_CALIBRATE = 'printf "%s\\n" "$FAKE_CAL_JSON"\n'
# a Google Benchmark binary's stand-in: writes FAKE_BENCH_JSON to its --benchmark_out file
FAKE_BENCH = textwrap.dedent("""\
    for a in "$@"; do
      case "$a" in --benchmark_out=*) printf "%s\\n" "$FAKE_BENCH_JSON" > "${a#*=}" ;; esac
    done
    """)


def run_script(args, env=None):
    """check_baseline.main() on args in this process; returns (exit code, stdout)."""
    out = io.StringIO()
    saved_argv, saved_env = sys.argv, dict(os.environ)
    sys.argv = ["check_baseline.py"] + args
    os.environ.update(env or {})
    try:
        with contextlib.redirect_stdout(out):
            rc = check_baseline.main()
    except SystemExit as e:
        rc = e.code
    finally:
        sys.argv = saved_argv
        os.environ.clear()
        os.environ.update(saved_env)
    return rc, out.getvalue()


class CheckBaseline(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        d = self.tmp.name
        self.baseline = os.path.join(d, "baseline.json")
        self.results = os.path.join(d, "results")
        for name, text in (("cal", FAKE_CALIBRATE), ("bench", FAKE_BENCH)):
            path = os.path.join(d, name)
            with open(path, "w") as f:
                f.write("#!/bin/sh\n" + text)
            os.chmod(path, 0o755)

    def tearDown(self):
        self.tmp.cleanup()

    def bench(self, times, cal=0.01, regenerate=False):
        """Runs check_baseline.py bench on the stand-ins; returns (exit code, result JSON)."""
        d = self.tmp.name
        cal_json = {"kernel": "triad", "doubles_per_array": 1, "sweeps": 1,
                    "bytes_per_sweep": 24.0, "median_cpu_s": cal, "min_cpu_s": cal,
                    "gbytes_per_s": 24e-9 / cal, "checksum": 0}
        rows = [{"name": n, "run_type": "iteration", "iterations": 10, "real_time": ms,
                 "cpu_time": ms, "time_unit": "ms"} for n, ms in times.items()]
        env = {"FAKE_CAL_JSON": json.dumps(cal_json),
               "FAKE_BENCH_JSON": json.dumps({"context": {}, "benchmarks": rows}),
               "EMC_REGENERATE_BASELINE": "1" if regenerate else "0"}
        rc, out = run_script(["bench", "k", "--binary", os.path.join(d, "bench"), "--filter", ".",
                              "--calibrate", os.path.join(d, "cal"), "--baseline", self.baseline,
                              "--results", self.results, "--work", os.path.join(d, "work")], env)
        with open(os.path.join(self.results, "ci-k.json")) as f:
            return rc, json.load(f), out

    def regenerate(self):
        rc, res, _ = self.bench({"BM_A": 2.0, "BM_B": 5.0}, regenerate=True)
        self.assertEqual(rc, 0)
        with open(self.baseline) as f:
            case = json.load(f)["cases"]["k"]
        self.assertAlmostEqual(case["calibration_s"], 0.01)
        self.assertAlmostEqual(case["times"]["BM_A"]["cpu_s"], 2e-3)

    def test_same_passes(self):
        self.regenerate()
        rc, res, out = self.bench({"BM_A": 2.0, "BM_B": 5.0})
        self.assertEqual(rc, 0, out)
        self.assertTrue(res["passed"])
        self.assertAlmostEqual(res["ratios"]["BM_A"], 1.0)
        self.assertAlmostEqual(res["times"]["BM_B"]["normalised"], 5e-3 / 0.01)

    def test_1_5x_slower_passes(self):
        self.regenerate()
        rc, res, out = self.bench({"BM_A": 3.0, "BM_B": 5.0})
        self.assertEqual(rc, 0, out)
        self.assertAlmostEqual(res["ratios"]["BM_A"], 1.5)

    def test_10x_slower_fails(self):
        self.regenerate()
        rc, res, out = self.bench({"BM_A": 2.0, "BM_B": 50.0})
        self.assertEqual(rc, 1, out)
        self.assertFalse(res["passed"])
        self.assertIn("BM_B normalised time 10 x", out)
        self.assertAlmostEqual(res["ratios"]["BM_B"], 10.0)

    def test_slower_machine_passes(self):
        # everything 10x slower, the calibration too: the normalised times are the baseline's
        self.regenerate()
        rc, res, out = self.bench({"BM_A": 20.0, "BM_B": 50.0}, cal=0.1)
        self.assertEqual(rc, 0, out)
        self.assertAlmostEqual(res["ratios"]["BM_B"], 1.0)

    def test_faster_calibration_fails(self):
        # the same times on a machine whose calibration runs 10x faster: 10x slower normalised
        self.regenerate()
        rc, _, out = self.bench({"BM_A": 2.0, "BM_B": 5.0}, cal=0.001)
        self.assertEqual(rc, 1, out)

    def test_missing_or_new_benchmark_fails(self):
        self.regenerate()
        rc, _, out = self.bench({"BM_A": 2.0})
        self.assertEqual(rc, 1, out)
        self.assertIn("BM_B of the baseline did not run", out)
        rc, _, out = self.bench({"BM_A": 2.0, "BM_B": 5.0, "BM_C": 1.0})
        self.assertEqual(rc, 1, out)
        self.assertIn("BM_C is not in the baseline", out)

    def test_no_baseline_fails(self):
        rc, _, out = self.bench({"BM_A": 2.0})
        self.assertEqual(rc, 1, out)
        self.assertIn("no entry in the baseline", out)


def solver_result(newton, linear, resolves, active, cpu=1.0):
    return {"name": "s", "kind": "solver", "calibration": {"seconds": 0.01, "gbytes_per_s": 1},
            "times": {"run": {"cpu_s": cpu, "real_s": cpu, "iterations": 1,
                              "normalised": cpu / 0.01}},
            "counters": {"newton_iterations": newton, "linear_iterations": linear,
                         "contact_resolves": resolves, "active_contacts": active,
                         "steps": len(newton)}}


class CompareCounters(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        base = solver_result([1, 3, 4], [10, 30, 40], [0, 1, 2], [0, 5, 7])
        case = {"calibration_s": 0.01, "times": {"run": base["times"]["run"]},
                "counters": base["counters"]}
        self.baseline = os.path.join(self.tmp.name, "baseline.json")
        with open(self.baseline, "w") as f:
            json.dump({"cases": {"s": case}}, f)

    def tearDown(self):
        self.tmp.cleanup()

    def compare(self, result):
        path = os.path.join(self.tmp.name, "ci-s.json")
        with open(path, "w") as f:
            json.dump(result, f)
        return run_script(["compare", path, self.baseline])

    def test_same_passes(self):
        self.assertEqual(self.compare(solver_result([1, 3, 4], [10, 30, 40], [0, 1, 2],
                                                    [0, 5, 7]))[0], 0)

    def test_command_line(self):
        # the comparison through the command line, as ctest runs it
        path = os.path.join(self.tmp.name, "ci-s.json")
        with open(path, "w") as f:
            json.dump(solver_result([1, 3, 4], [10, 30, 40], [0, 1, 2], [0, 5, 8]), f)
        p = subprocess.run([sys.executable, SCRIPT, "compare", path, self.baseline],
                           capture_output=True, text=True)
        self.assertEqual(p.returncode, 1, p.stdout + p.stderr)
        self.assertIn("active_contacts at step 3 = 8, baseline 7", p.stdout)

    def test_changed_newton_fails(self):
        rc, out = self.compare(solver_result([1, 4, 4], [10, 30, 40], [0, 1, 2], [0, 5, 7]))
        self.assertEqual(rc, 1)
        self.assertIn("newton_iterations at step 2 = 4, baseline 3", out)

    def test_changed_active_set_fails(self):
        self.assertEqual(self.compare(solver_result([1, 3, 4], [10, 30, 40], [0, 1, 2],
                                                    [0, 5, 6]))[0], 1)
        self.assertEqual(self.compare(solver_result([1, 3, 4], [10, 30, 40], [0, 0, 2],
                                                    [0, 5, 7]))[0], 1)

    def test_other_step_count_fails(self):
        rc, out = self.compare(solver_result([1, 3], [10, 30], [0, 1], [0, 5]))
        self.assertEqual(rc, 1)
        self.assertIn("steps = 2, baseline 3", out)

    def test_krylov_within_one_per_solve_passes(self):
        # step 3 has 4 Newton iterations (4 solves): up to 4 Krylov iterations more or fewer
        self.assertEqual(self.compare(solver_result([1, 3, 4], [11, 27, 44], [0, 1, 2],
                                                    [0, 5, 7]))[0], 0)

    def test_krylov_beyond_fails(self):
        rc, out = self.compare(solver_result([1, 3, 4], [10, 30, 45], [0, 1, 2], [0, 5, 7]))
        self.assertEqual(rc, 1)
        self.assertIn("linear_iterations at step 3 = 45, baseline 40 (allowed: +-4)", out)

    def test_slow_run_fails(self):
        rc, out = self.compare(solver_result([1, 3, 4], [10, 30, 40], [0, 1, 2], [0, 5, 7],
                                             cpu=10.0))
        self.assertEqual(rc, 1)
        self.assertIn("run normalised time 10 x", out)


if __name__ == "__main__":
    unittest.main()
