#!/usr/bin/python3
"""Vorticity and streamline pictures of a coupled `imcol run` (the `flow` effect).

Usage: /usr/bin/python3 scripts/plot_coupled_flow.py DIR
Reads DIR/flow_*.csv (written at a gap of 1 D, at contact, one fit window after separation and at the end);
writes DIR/flow_*.png. Needs Debian's python3-matplotlib.
"""
import sys

from imcol_plot import out_dir
from plot_flow import plot_snapshot


def spheres_of(path):
    """Sphere centres and diameters from the CSV's first line: '...; spheres (z, d) = z1 d1 z2 d2; ...'."""
    with open(path) as f:
        head = f.readline()
    part = head.split("spheres (z, d) =")[1].split(";")[0].split()
    vals = [float(x) for x in part]
    return list(zip(vals[0::2], vals[1::2]))


def main() -> int:
    out = out_dir(__doc__)
    if out is None:
        return 2
    snaps = sorted(out.glob("flow_*.csv"))
    if not snaps:
        print(f"no flow_*.csv in {out}", file=sys.stderr)
        return 1
    for snap in snaps:
        plot_snapshot(snap, spheres_of(snap))
    return 0


if __name__ == "__main__":
    sys.exit(main())
