#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Plot f_SIM against f_THR on two spheres on a prescribed approach (the seed's Fig. 6.4) from an `imcol flow` run.

Usage: /usr/bin/python3 scripts/plot_force_vs_gap.py DIR
Reads DIR/forces.csv (columns gap_D, F1, F2, F_THR1, F_THR2) and DIR/summary.json (the forces' units, as
plot_flow.py draws them); writes DIR/forces_vs_gap.png and
DIR/forces_vs_gap.csv (gap from 2 D to the end of the run). Needs Debian's python3-matplotlib.
"""
import csv
import json
import sys

import numpy as np

from imcol_plot import out_dir, plt, save_png, write_text
from plot_flow import scene_units


def main() -> int:
    out = out_dir(__doc__)
    if out is None:
        return 2
    with open(out / "forces.csv", newline="") as f:
        rows = [r for r in csv.DictReader(f) if "gap_D" in r and 0 < float(r["gap_D"]) <= 2.0]
    if not rows:
        print("forces.csv has no two-sphere rows with a gap below 2 D", file=sys.stderr)
        return 1
    gap = np.array([float(r["gap_D"]) for r in rows])
    units = scene_units(json.loads((out / "summary.json").read_text()))
    lines = ["gap_D,F_SIM1,F_THR1,F_SIM2,F_THR2"]
    for r in rows:
        lines.append(",".join(r[k] for k in ("gap_D", "F1", "F_THR1", "F2", "F_THR2")))
    write_text(out / "forces_vs_gap.csv", "\n".join(lines) + "\n")
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    for ax, b, name in zip(axes, (1, 2), ("impact sphere", "target sphere")):
        ax.plot(gap, [float(r[f"F{b}"]) / units.force for r in rows], label="f_SIM (flow kernel)")
        ax.plot(gap, [float(r[f"F_THR{b}"]) / units.force for r in rows], "--", label="f_THR (analytic, no history)")
        ax.axvline(0.05, color="grey", lw=0.8, ls=":", label="0.05 D (seed: the two part below)")
        ax.set_xscale("log")
        ax.invert_xaxis()
        ax.set_xlabel("gap / D")
        ax.set_ylabel(units.force_label)
        ax.set_title(f"({'ab'[b - 1]}) hydrodynamic force on the {name}")
        ax.grid(alpha=0.3)
        ax.legend()
    fig.tight_layout()
    save_png(fig, out / "forces_vs_gap.png", dpi=130)
    return 0


if __name__ == "__main__":
    sys.exit(main())
