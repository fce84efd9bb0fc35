#!/usr/bin/env python3
"""The rules every ctest entry follows (docs/developer-guide.md, "Tests"), checked on the list
ctest itself reports (`ctest -C long --show-only=json-v1`, the default and the long entries):
  - a TIMEOUT of at most 300 s (a net against hangs; no test waits longer);
  - PROCESSORS at least its rank count (mpiexec -np N, or -DRANKS=N of a run script), so that
    `ctest -j 2` never runs a 2-rank test beside another one;
  - the label `long` exactly on the entries registered for `ctest -C long` only (CONFIGURATIONS
    long): plain `ctest` leaves them out.
Fails (exit 1) with one line per entry that breaks a rule.
Usage: test_policy.py BUILD_DIR [CTEST]
"""
import json
import re
import subprocess
import sys

MAX_TIMEOUT = 300


def listing(build, ctest, config):
    args = [ctest, "--show-only=json-v1"] + (["-C", config] if config else [])
    out = subprocess.run(args, cwd=build, check=True, capture_output=True, text=True).stdout
    return json.loads(out)["tests"]


def ranks(command):
    text = " ".join(command)
    m = re.search(r"(?:^|\s)-(?:np|n)\s+(\d+)", text) or re.search(r"-DRANKS=(\d+)", text)
    return int(m.group(1)) if m else 1


def main():
    build = sys.argv[1]
    ctest = sys.argv[2] if len(sys.argv) > 2 else "ctest"
    every = listing(build, ctest, "long")
    default = {t["name"] for t in listing(build, ctest, None)}
    problems = []
    for t in every:
        props = {p["name"]: p["value"] for p in t.get("properties", [])}
        name = t["name"]
        timeout = props.get("TIMEOUT")
        if timeout is None or float(timeout) > MAX_TIMEOUT:
            problems.append(f"{name}: TIMEOUT {timeout} (allowed: set, at most {MAX_TIMEOUT} s)")
        n = ranks(t.get("command", []))
        procs = int(props.get("PROCESSORS", 1))
        if procs < n:
            problems.append(f"{name}: runs {n} ranks but PROCESSORS is {procs}")
        is_long = "long" in props.get("LABELS", [])
        if is_long == (name in default):
            where = "in the default run" if name in default else "only under -C long"
            problems.append(f"{name}: label long {'set' if is_long else 'missing'} but {where}")
    for p in problems:
        print(p)
    print(f"test_policy: {len(every)} entries ({len(default)} default), {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
