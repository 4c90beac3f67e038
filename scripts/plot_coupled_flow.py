#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Vorticity and streamline pictures of a coupled `imcol run` (the `flow` effect).

Usage: /usr/bin/python3 scripts/plot_coupled_flow.py DIR
Reads DIR/flow_*.csv (written at the first flow step with a gap of 1 D or less, at contact, one fit window
after separation and at the end), and DIR/trajectory.csv and DIR/summary.json when present (the true gap at
each snapshot's time unless the CSV's comment line gives it; the wall's position); writes DIR/flow_*.png (vorticity
and streamlines near the spheres and over the whole domain, every grid level composed, lengths in mm below a 5 cm
sphere) and, when the snapshots have a pressure column `p` (Pa), DIR/flow_*_pressure.png; one colour scale per
quantity for all of them (scripts/flow_field.py).
Needs Debian's python3-matplotlib.
"""
import json
import sys

import numpy as np

from flow_field import parse_comment, plot_snapshot, run_limits, si_units, snapshot_limits
from imcol_plot import out_dir, read_rows


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


def snapshot_title(snap, info, traj, D):
    """'contact, t = 0.0289 s: gap 0.0134 D': the true gap from the comment line when it gives one, else the
    trajectory's at the snapshot's time, else none."""
    label, t = label_and_time(snap)
    if snap.stem == "flow_gap_1D":
        label = "first flow step at a gap ≤ 1 D"
    gap = info.get("gap_m")
    if gap is None and traj is not None and t is not None:
        gap = float(np.interp(t, traj[0], traj[2]))
    head = f"{label}, t = {t:.4g} s" if t is not None else label
    return head + (f": gap {gap / D:.3g} D ({1e3 * gap:.3g} mm)" if gap is not None else "")


def main() -> int:
    out = out_dir(__doc__)
    if out is None:
        return 2
    snaps = sorted(out.glob("flow_*.csv"))
    if not snaps:
        print(f"no flow_*.csv in {out}", file=sys.stderr)
        return 1
    try:
        summary = json.loads((out / "summary.json").read_text())
    except (OSError, ValueError):
        summary = {}
    traj = read_trajectory(out)
    infos = []
    for snap in snaps:
        with open(snap) as f:
            infos.append(parse_comment(f.readline()))
    D = infos[0]["spheres"][0][1]  # the impact sphere's diameter
    wall = None
    if traj is not None and summary.get("configuration") == "sphere-wall":
        # the wall is at z1 + D/2 + gap (the sphere on its -z side); a sphere-wall run's snapshots are in the lab
        # frame (z_shift = 0), so this is also the wall's place in the picture
        wall = float(np.median(traj[1] + D / 2 + traj[2]))
    units = si_units(D)
    limits = run_limits([snapshot_limits(s, None, wall, units) for s in snaps])
    scene = summary.get("scene", out.name)
    for snap, info in zip(snaps, infos):
        title = f"{scene}: " + snapshot_title(snap, info, traj, D)
        plot_snapshot(snap, None, wall, title, "sphere surface", units, limits)
    return 0


if __name__ == "__main__":
    sys.exit(main())
