#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Vorticity and streamline pictures of a coupled `imcol run` (the `flow` effect).

Usage: /usr/bin/python3 scripts/plot_coupled_flow.py DIR
Reads DIR/flow_*.csv (written at the first flow step with a gap of 1 D or less, at contact, one fit window
after separation and at the end), and DIR/trajectory.csv and DIR/summary.json when present (the true gap at
each snapshot's time; the wall's position); writes DIR/flow_*.png (vorticity and streamlines, lengths in mm below a
5 cm sphere) and, when the snapshots have a pressure column `p` (Pa), DIR/flow_*_pressure.png.
Needs Debian's python3-matplotlib.
"""
import json
import sys

import numpy as np

from imcol_plot import out_dir, read_rows
from plot_flow import plot_snapshot, si_units


def spheres_of(path):
    """Sphere centres and diameters from the CSV's first line: '...; spheres (z, d) = z1 d1 z2 d2; ...'."""
    with open(path) as f:
        head = f.readline()
    part = head.split("spheres (z, d) =")[1].split(";")[0].split()
    vals = [float(x) for x in part]
    return list(zip(vals[0::2], vals[1::2]))


def label_and_time(path):
    """The snapshot's label and time from its first line: '# LABEL, t = T s; ...'."""
    with open(path) as f:
        first = f.readline().lstrip("# ").split(";")[0]
    label, _, rest = first.rpartition(", t =")
    try:
        return label, float(rest.split()[0])
    except (IndexError, ValueError):
        return first, None


def read_trajectory(out):
    """t, z1 and gap from DIR/trajectory.csv (the run's true motion), or None."""
    try:
        rows = read_rows(out / "trajectory.csv")
        t = np.array([float(r["t"]) for r in rows])
        return t, np.array([float(r["z1"]) for r in rows]), np.array([float(r["gap"]) for r in rows])
    except (OSError, KeyError, ValueError):
        return None


def main() -> int:
    out = out_dir(__doc__)
    if out is None:
        return 2
    snaps = sorted(out.glob("flow_*.csv"))
    if not snaps:
        print(f"no flow_*.csv in {out}", file=sys.stderr)
        return 1
    try:
        configuration = json.loads((out / "summary.json").read_text()).get("configuration")
    except (OSError, ValueError):
        configuration = None
    traj = read_trajectory(out)
    for snap in snaps:
        spheres = spheres_of(snap)
        D = spheres[0][1]  # the impact sphere's diameter
        label, t = label_and_time(snap)
        if snap.stem == "flow_gap_1D":
            label = "first flow step at a gap ≤ 1 D"
        title, wall = None, None
        if traj is not None and t is not None:
            tt, z1, gap = traj
            g = float(np.interp(t, tt, gap))
            title = f"{label}, t = {t:.4g} s: gap {g / D:.3g} D"
            if configuration == "sphere-wall":
                # the wall is at z1 + D/2 + gap (the sphere on its -z side); a sphere-wall run's snapshots are
                # in the lab frame (z_shift = 0), so this is also the wall's place in the picture
                wall = float(np.median(z1 + D / 2 + gap))
        plot_snapshot(snap, spheres, wall, title, "sphere surface, where the kernel holds it", si_units(D))
    return 0


if __name__ == "__main__":
    sys.exit(main())
