#!/usr/bin/env python3
"""The module graph, as CMakeLists.txt declares it, against the includes of the sources.

Reads the emc_module(<m> PUBLIC ... PRIVATE ...) lines of CMakeLists.txt (bottom to top) and
fails (exit 1, one line per problem) if
  - a module includes a header of a module it does not link, or of a module above it;
  - a public header (include/emcontact/<m>/) includes a module its target links only PRIVATE;
  - a file includes <gmsh.h> or <hdf5.h> in a module that does not link emc_gmsh / emc_hdf5;
  - a file of the kernel library (kernels/: its headers, tests and benchmarks) includes
    anything of emcontact's but the library's own ("kernels/...", or a test's or benchmark's
    files next to it or under kernels/tests), or a third-party header other than Kokkos',
    the standard library's, gtest's and Google Benchmark's (the library needs Kokkos alone);
  - anything includes a private header through the source root ("src/...");
  - a test, benchmark or tool includes a header that is neither public (emcontact/...,
    kernels/...) nor its own (next to it or under tests/).
Usage: module_graph.py [SOURCE_DIR] [--mermaid]  (--mermaid prints the graph for the docs).
"""
import pathlib
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]', re.M)
THIRD_PARTY = {"gmsh.h": "emc_gmsh", "hdf5.h": "emc_hdf5"}
# What the kernel library may include in <>: Kokkos, the standard library, gtest, benchmark.
KERNELS_SYSTEM = re.compile(r"^(Kokkos\w*\.hpp|KokkosCore\w*\.h|gtest/.*|benchmark/.*|[a-z_]+)$")


def modules(root):
    """[(name, public deps, private deps)] in CMakeLists.txt's order, bottom to top."""
    text = (root / "CMakeLists.txt").read_text()
    out = []
    for m in re.finditer(r"^emc_module\((\w+)([^)]*)\)", text, re.M):
        public, private, part = [], [], None
        for tok in m.group(2).split():
            if tok in ("PUBLIC", "PRIVATE"):
                part = public if tok == "PUBLIC" else private
            elif part is not None:
                part.append(tok)
        out.append((m.group(1), public, private))
    return out


def module_of(header):
    """The module a quoted include names, or None (a private header, by its bare name)."""
    m = re.match(r"emcontact/(\w+)/", header)
    if m:
        return m.group(1)
    if re.match(r"emcontact/\w+\.hpp$", header):
        return "base"
    if header.startswith("kernels/"):
        return "kernels"
    return None


def includes(path):
    return INCLUDE.findall(path.read_text(errors="replace"))


def sources(root, m):
    if m == "base":
        files = list((root / "include/emcontact").glob("*.hpp"))
    else:
        files = list((root / "include/emcontact" / m).rglob("*.hpp"))
    files += [p for p in (root / "src" / m).rglob("*") if p.suffix in (".cpp", ".hpp")]
    return files


def check(root):
    mods = modules(root)
    if not mods:
        return ["CMakeLists.txt: no emc_module(...) lines"]
    rank = {name: i for i, (name, _, _) in enumerate(mods)}
    rank["kernels"] = -1  # header-only, below base: includes only other kernels
    problems = []
    for name, public, private in mods:
        linked = set(public) | set(private)
        for f in sources(root, name):
            rel = f.relative_to(root)
            is_public = rel.parts[0] == "include"
            for kind, h in includes(f):
                if kind == "<":
                    lib = THIRD_PARTY.get(h)
                    if lib and lib not in linked:
                        problems.append(f"{rel}: <{h}> but emc_{name} does not link {lib}")
                    continue
                if h.startswith("src/"):
                    problems.append(f"{rel}: \"{h}\" through the source root (include it by name)")
                    continue
                dep = module_of(h)
                if dep is None or dep == name:
                    continue
                target = "emc_" + dep
                if dep not in rank:
                    problems.append(f"{rel}: \"{h}\": no module {dep}")
                elif rank[dep] >= rank[name]:
                    problems.append(f"{rel}: \"{h}\": {name} reaches up to {dep}")
                elif target not in linked and dep != "base":
                    problems.append(f"{rel}: \"{h}\": emc_{name} does not link {target}")
                elif is_public and target not in public and dep != "base":
                    problems.append(f"{rel}: \"{h}\" in a public header: link {target} PUBLIC")
        if "emc_base" not in public and name != "base":
            problems.append(f"CMakeLists.txt: emc_{name} does not link emc_base PUBLIC")
    problems += check_kernels(root)
    for top in ("tests", "perf", "tools"):
        for f in (root / top).rglob("*"):
            if f.suffix not in (".cpp", ".hpp"):
                continue
            rel = f.relative_to(root)
            for kind, h in includes(f):
                if kind == "<" or h.startswith(("emcontact/", "kernels/")):
                    continue
                if (f.parent / h).exists() or (root / "tests" / h).exists():
                    if not h.startswith("src/"):
                        continue
                problems.append(f"{rel}: \"{h}\" is not a public header")
    return problems


def check_kernels(root):
    """The kernel library (kernels/) includes its own headers and Kokkos only."""
    problems = []
    for f in sorted((root / "kernels").rglob("*")):
        if f.suffix not in (".cpp", ".hpp"):
            continue
        rel = f.relative_to(root)
        own = rel.parts[1] in ("tests", "bench")  # a test's or benchmark's own files
        for kind, h in includes(f):
            if kind == "<":
                if not KERNELS_SYSTEM.match(h):
                    problems.append(f"{rel}: <{h}>: the kernel library includes Kokkos only")
            elif h.startswith("kernels/"):
                if own and not (root / h).exists():
                    problems.append(f"{rel}: \"{h}\": no such kernel")
            elif not (own and ((f.parent / h).exists() or (root / "kernels/tests" / h).exists())):
                problems.append(f"{rel}: \"{h}\": a kernel includes only kernels")
    return problems


def mermaid(root):
    lines = ["graph BT"]
    for name, public, private in modules(root):
        for dep in public + private:
            if dep.startswith("emc_") and dep[4:] in [m for m, _, _ in modules(root)] + ["kernels"]:
                if dep == "emc_base" and name != "input":
                    continue  # everything uses base: drawn once
                style = "-->" if dep in public else "-.->"
                lines.append(f"  {name} {style} {dep[4:]}")
    return "\n".join(lines)


def main(argv):
    args = [a for a in argv[1:] if not a.startswith("--")]
    root = pathlib.Path(args[0] if args else pathlib.Path(__file__).resolve().parent.parent)
    if "--mermaid" in argv:
        print(mermaid(root))
        return 0
    problems = check(root)
    for p in problems:
        print(p)
    if problems:
        print(f"module_graph: {len(problems)} include(s) against the graph of CMakeLists.txt")
        return 1
    print("module_graph: " + " <- ".join(m for m, _, _ in modules(root)) + ": ok")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
