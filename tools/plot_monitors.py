#!/usr/bin/python3
"""Plots an emcontact monitors.csv: energies, linear momentum L and angular momentum J.

Usage: plot_monitors.py DIR/monitors.csv [--out PNG] [--title T]

Columns are found by header name (extra columns are ignored); the PNG defaults to the CSV path
with a .png suffix. Panels: kinetic/elastic/potential/total vs time; Lx/Ly/Lz vs time; and
Jx/Jy/Jz vs time if those columns are present. With friction (a `dissipated` column that is not
all zero, docs/THEORY.md §11.2) the energy panel also shows `dissipated` (D, the energy
dissipated by friction since t = 0) and `total + dissipated` (E + D, the conserved quantity),
and a second panel shows them on D's scale: D, E0 - E (the energy lost) and E + D - E0.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ENERGIES = ("kinetic", "elastic", "potential", "total")
L_COLUMNS = ("Lx", "Ly", "Lz")
J_COLUMNS = ("Jx", "Jy", "Jz")


def read_csv(path):
    """Returns {column name: float array}; numeric columns only, by header name."""
    with open(path, newline="") as f:
        header = f.readline().strip().split(",")
        if not header or header == [""]:
            sys.exit(f"{path}: empty file")
        data = np.genfromtxt(f, delimiter=",", dtype=float, ndmin=2)
    if data.size == 0:
        data = np.zeros((0, len(header)))
    if data.shape[1] != len(header):
        sys.exit(f"{path}: {data.shape[1]} columns for a header of {len(header)}")
    return {name: data[:, i] for i, name in enumerate(header)}


STYLES = {
    "total": {"color": "k", "linewidth": 2},
    "dissipated": {"color": "tab:purple", "linestyle": "--"},
    "total + dissipated": {"color": "tab:gray", "linewidth": 2, "linestyle": ":"},
    "E0 - total": {"color": "k", "linewidth": 2},
    "total + dissipated - E0": {"color": "tab:gray", "linewidth": 2, "linestyle": ":"},
}
FRICTION = ("E0 - total", "dissipated", "total + dissipated - E0")


def plot_group(ax, cols, names, ylabel):
    """Draws every column of `names` present in `cols` against time on `ax`."""
    t = cols["time"]
    for name in names:
        if name in cols:
            ax.plot(t, cols[name], label=name, **STYLES.get(name, {}))
    ax.set_ylabel(ylabel)
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize="small")


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("csv", help="monitors.csv written by emcontact")
    p.add_argument("--out", help="PNG to write (default: the CSV path with .png)")
    p.add_argument("--title", help="figure title (default: the CSV path)")
    args = p.parse_args()

    cols = read_csv(args.csv)
    missing = [c for c in ("time",) + ENERGIES + L_COLUMNS if c not in cols]
    if missing:
        sys.exit(f"{args.csv}: missing columns {', '.join(missing)}")
    energies = ENERGIES
    if "dissipated" in cols and np.any(cols["dissipated"] != 0):
        cols["total + dissipated"] = cols["total"] + cols["dissipated"]
        energies = ENERGIES + ("dissipated", "total + dissipated")
        e0 = cols["total"][0] if cols["total"].size else 0.0
        cols["E0 - total"] = e0 - cols["total"]
        cols["total + dissipated - E0"] = cols["total + dissipated"] - e0
    groups = [(energies, "energy")]
    if energies != ENERGIES:
        groups.append((FRICTION, "friction"))
    groups.append((L_COLUMNS, "L"))
    if any(c in cols for c in J_COLUMNS):
        groups.append((J_COLUMNS, "J"))

    fig, axes = plt.subplots(len(groups), 1, sharex=True, figsize=(9, 3.2 * len(groups)))
    for ax, (names, ylabel) in zip(axes, groups):
        plot_group(ax, cols, names, ylabel)
    axes[-1].set_xlabel("time")
    fig.suptitle(args.title if args.title else args.csv)
    fig.tight_layout()
    out = args.out if args.out else os.path.splitext(args.csv)[0] + ".png"
    fig.savefig(out, dpi=110)
    print(out)


if __name__ == "__main__":
    main()
