#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Plot the history force against time for each kernel and evaluator of `imcol history`.

Usage: /usr/bin/python3 scripts/plot_history.py DIR   (reads DIR/history_forces.csv, writes DIR/history.png)
Needs Debian's python3-matplotlib (importable from /usr/bin/python3 only).
"""
import csv
import sys
from collections import defaultdict

from imcol_plot import out_dir, plt, save_png


def main() -> int:
    out = out_dir(__doc__)
    if out is None:
        return 2
    series = defaultdict(lambda: ([], []))
    with open(out / "history_forces.csv", newline="") as f:
        for row in csv.DictReader(f):
            t, fh = series[row["label"]]
            t.append(1e3 * float(row["t"]))
            fh.append(float(row["f_hist1"]))
    fig, ax = plt.subplots(figsize=(9, 5.5))
    for label, (t, fh) in sorted(series.items()):
        style = "--" if label.endswith("direct") else "-"
        ax.plot(t, fh, style, lw=1.4 if style == "-" else 1.0, label=label)
    ax.set_xlabel("t [ms]")
    ax.set_ylabel("history force on sphere 1, f_H [N]")
    ax.set_title("History force by kernel (solid: sum of exponentials, dashed: direct quadrature)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    save_png(fig, out / "history.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
