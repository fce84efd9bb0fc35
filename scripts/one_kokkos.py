#!/usr/bin/env python3
"""Each binary resolves exactly one Kokkos core library, the found Trilinos' own.

    one_kokkos.py LIBDIR BINARY...     (ctest `one_kokkos`)
    one_kokkos.py --self-test          (ctest `one_kokkos_refuses`)

LIBDIR: the directory of the found Trilinos' Kokkos libraries (Kokkos_LIBRARY_DIRS). A binary
that links two Kokkos runtimes (a distribution's Serial one beside an OpenMP build's) crashes at
the first threaded deallocation; one whose Kokkos core lies outside LIBDIR runs another
Trilinos' Kokkos than it was compiled against. `ldd` lists what the dynamic loader resolves.
"""
import os
import re
import subprocess
import sys

CORE = re.compile(r"^\s*(\S*kokkoscore\S*\.so[.\d]*)\s+=>\s+(\S+)")


def problems(ldd_text, libdir, binary):
    """The reasons `binary` (its ldd output `ldd_text`) fails the rule; empty if it passes."""
    cores = {}
    for line in ldd_text.splitlines():
        m = CORE.match(line)
        if m:
            cores[m.group(1)] = m.group(2)
    if not cores:
        return [f"{binary}: resolves no Kokkos core library"]
    out = []
    if len(cores) > 1:
        out.append(f"{binary}: resolves {len(cores)} Kokkos core libraries: "
                   + ", ".join(f"{k} => {v}" for k, v in sorted(cores.items())))
    want = os.path.realpath(libdir)
    for name, path in sorted(cores.items()):
        if path == "not" or not os.path.realpath(os.path.dirname(path)) == want:
            out.append(f"{binary}: {name} => {path} is outside the found Trilinos' Kokkos "
                       f"library directory {want}")
    return out


def self_test():
    """The rule refuses two cores, a core elsewhere and none, and passes one in LIBDIR."""
    lib = "/usr/lib/x86_64-linux-gnu"
    ok = f"\tlibtrilinos_kokkoscore.so.13.2 => {lib}/libtrilinos_kokkoscore.so.13.2 (0x1)\n"
    two = ok + "\tlibkokkoscore.so.13.2 => /opt/t/lib/libkokkoscore.so.13.2 (0x2)\n"
    other = "\tlibkokkoscore.so.13.2 => /opt/t/lib/libkokkoscore.so.13.2 (0x2)\n"
    cases = [(ok, 0), (two, 2), (other, 1), ("\tlibc.so.6 => /lib/libc.so.6 (0x3)\n", 1)]
    failed = 0
    for text, n in cases:
        got = problems(text, lib, "b")
        if len(got) != n:
            print(f"self-test: expected {n} problems, got {got} for {text!r}")
            failed += 1
    print(f"{len(cases) - failed} passed, {failed} failed")
    return 1 if failed else 0


def main(argv):
    if argv[1:] == ["--self-test"]:
        return self_test()
    if len(argv) < 3:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    libdir, found = argv[1], []
    for binary in argv[2:]:
        text = subprocess.run(["ldd", binary], check=True, capture_output=True,
                              text=True).stdout
        found += problems(text, libdir, binary)
    for p in found:
        print(p)
    if not found:
        print(f"{len(argv) - 2} binaries, each with one Kokkos core in {os.path.realpath(libdir)}")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
