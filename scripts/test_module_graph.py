#!/usr/bin/env python3
"""The module graph check (scripts/module_graph.py) refuses what it must: on a scratch tree with
the emc_module lines of the real CMakeLists.txt, one include against the graph at a time
  - a module reaching up (mesh includes fem),
  - a module including one it does not link (output includes mesh),
  - a public header including a module its target links only PRIVATE (mesh includes input),
  - a module including <hdf5.h> without linking emc_hdf5 (fem),
must each fail with its line naming the file, and the tree without them must pass.
Usage: test_module_graph.py SOURCE_DIR
"""
import pathlib
import subprocess
import sys
import tempfile

CASES = [
    ("include/emcontact/mesh/wall.hpp", '#include "emcontact/fem/model.hpp"',
     "mesh reaches up to fem"),
    ("src/output/wall.cpp", '#include "emcontact/mesh/body_mesh.hpp"',
     "emc_output does not link emc_mesh"),
    ("include/emcontact/mesh/wall.hpp", '#include "emcontact/input/input.hpp"',
     "in a public header: link emc_input PUBLIC"),
    ("src/fem/wall.cpp", "#include <hdf5.h>", "emc_fem does not link emc_hdf5"),
]


def run(script, root):
    p = subprocess.run([sys.executable, str(script), str(root)], capture_output=True, text=True)
    return p.returncode, p.stdout + p.stderr


def main():
    source = pathlib.Path(sys.argv[1]).resolve()
    script = source / "scripts" / "module_graph.py"
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        root = pathlib.Path(tmp)
        (root / "CMakeLists.txt").write_text((source / "CMakeLists.txt").read_text())
        for d in ("include/emcontact", "src", "kernels", "tests", "perf", "tools"):
            (root / d).mkdir(parents=True, exist_ok=True)
        rc, out = run(script, root)
        if rc != 0:
            failures.append(f"the tree without a wrong include fails: {out.strip()}")
        for rel, line, expected in CASES:
            f = root / rel
            f.parent.mkdir(parents=True, exist_ok=True)
            f.write_text(line + "\n")
            rc, out = run(script, root)
            if rc != 1 or f"{rel}: " not in out or expected not in out:
                failures.append(f"{rel} with {line}: exit {rc}, expected 1 and '{expected}':\n{out}")
            f.unlink()
    for f in failures:
        print("test_module_graph: " + f)
    print(f"test_module_graph: {len(CASES)} wrong includes, {len(failures)} not refused as expected")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
