#!/usr/bin/env python3
"""The include walls of the modules (CMakeLists.txt, emc_module): the sources of a module find
exactly the public headers of the module, of base, of the modules it links (PUBLIC or PRIVATE)
and of their PUBLIC dependencies, in turn; the header of any other module is not found.

For each module, the compiler preprocesses `#if __has_include("<a header of each module>")`
with that module's include directories (its target's INCLUDE_DIRECTORIES, which CMake passes)
and the answers are compared with the closure of the emc_module lines of CMakeLists.txt.
Fails (exit 1) with one line per module whose walls differ.
Usage: module_walls.py SOURCE_DIR CXX <module>=<dir>:<dir>... ...
"""
import pathlib
import subprocess
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import module_graph  # noqa: E402  (the emc_module lines)


def probe_header(root, module):
    """One public header of a module, as it is included."""
    if module == "kernels":
        return "kernels/" + sorted(p.name for p in (root / "kernels").glob("*.hpp"))[0]
    if module == "base":
        return "emcontact/" + sorted(p.name for p in (root / "include/emcontact").glob("*.hpp"))[0]
    d = root / "include/emcontact" / module
    return f"emcontact/{module}/" + sorted(p.name for p in d.glob("*.hpp"))[0]


def expected(mods, name):
    """What the sources of emc_<name> may find: itself, base, its links and their PUBLIC ones."""
    public = {m: [t[4:] for t in pub if t.startswith("emc_")] for m, pub, _ in mods}
    _, pub, priv = next(m for m in mods if m[0] == name)
    seen, stack = {name, "base"}, [t[4:] for t in pub + priv if t.startswith("emc_")]
    while stack:
        m = stack.pop()
        if m not in seen:
            seen.add(m)
            stack += public.get(m, [])
    return seen & (set(public) | {"kernels"})


def visible(cxx, dirs, headers):
    probe = "".join(f'#if __has_include("{h}")\nfound {m}\n#endif\n' for m, h in headers.items())
    args = [cxx, "-E", "-P", "-x", "c++", "-"] + [f"-I{d}" for d in dirs if d]
    out = subprocess.run(args, input=probe, capture_output=True, text=True, check=True).stdout
    return {line.split()[1] for line in out.splitlines() if line.startswith("found ")}


def main(argv):
    root, cxx = pathlib.Path(argv[1]), argv[2]
    mods = module_graph.modules(root)
    headers = {m: probe_header(root, m) for m in [m for m, _, _ in mods] + ["kernels"]}
    given = dict(a.split("=", 1) for a in argv[3:])
    problems = []
    for name, _, _ in mods:
        if name not in given:
            problems.append(f"{name}: no include directories given")
            continue
        want = expected(mods, name)
        got = visible(cxx, given[name].split(":"), headers)
        if got != want:
            extra = ", ".join(sorted(got - want)) or "-"
            missing = ", ".join(sorted(want - got)) or "-"
            problems.append(f"emc_{name}: finds headers of {extra} (not linked); misses {missing}")
    for p in problems:
        print(p)
    print(f"module_walls: {len(mods)} modules, {len(problems)} with walls against the graph")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
