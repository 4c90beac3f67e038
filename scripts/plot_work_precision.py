#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Work-precision plot of `imcol work-precision`: error against median wall time, log-log.

Usage: /usr/bin/python3 scripts/plot_work_precision.py DIR
Reads DIR/work_precision.csv and DIR/work_precision.json, writes DIR/work_precision.png.
Left: error in e (or the final velocity); right: max trajectory error. One line per integrator /
history evaluator, each point labelled with its rtol (or the direct evaluator's step).
"""
import csv
import json
import sys
from collections import defaultdict

from imcol_plot import out_dir, plt, save_png

FLOOR = 1e-16  # an error of exactly zero is drawn here


def main() -> int:
    out = out_dir(__doc__)
    if out is None:
        return 2
    meta = json.loads((out / "work_precision.json").read_text())
    metric = meta["metric"]
    series = defaultdict(list)
    with open(out / "work_precision.csv", newline="") as f:
        for row in csv.DictReader(f):
            if row["status"] != "ok":
                continue
            label = row["integrator"] + ("" if row["evaluator"] == "none" else " / " + row["evaluator"])
            tag = ("dt %.1e" % float(row["direct_step_s"])) if row["direct_step_s"] else ("%.0e" % float(row["rtol"]))
            series[label].append((float(row["median_wall_ms"]), max(float(row["err_" + metric]), FLOOR),
                                  max(float(row["err_trajectory"] or "nan"), FLOOR), tag))
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.5))
    for ax, k, title in ((axes[0], 1, "error in " + metric), (axes[1], 2, "max trajectory error (gap/D, u/U)")):
        for label, pts in series.items():
            ms = [p[0] for p in pts]
            err = [p[k] for p in pts]
            (line,) = ax.loglog(ms, err, "o-", label=label)
            for p in pts[:: max(1, len(pts) // 5)] + [pts[-1]]:
                ax.annotate(p[3], (p[0], p[k]), fontsize=7, color=line.get_color(), xytext=(3, 3), textcoords="offset points")
        for target in (1e-3, 1e-6, 1e-9):
            ax.axhline(target, color="0.7", lw=0.8, ls="--")
        ax.set_xlabel("median wall time per run (ms)")
        ax.set_ylabel(title)
        ax.grid(True, which="major", alpha=0.3)
        ax.legend(fontsize=8)
    ref = meta["reference"]
    fig.suptitle("%s: work-precision against %s, rtol %.0e (%s = %.10g)" %
                 (meta["scene"], ref["integrator"] + ("" if ref["evaluator"] == "none" else " / " + ref["evaluator"]),
                  ref["rtol"], metric, ref["value"]))
    fig.tight_layout()
    save_png(fig, out / "work_precision.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
