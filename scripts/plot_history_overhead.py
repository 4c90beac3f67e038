#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Work-precision with and without the history force on one figure, from imcol_bench_history_overhead's CSV.

Usage: plot_history_overhead.py CSV PNG
One panel per scene: the error in e against the integration's median time, with history (solid) and without (dashed),
each rung labelled by its rtol; the title gives the largest time ratio at equal error.
"""
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import imcol_plot as ip  # noqa: E402


def by_scene(rows):
    scenes = {}
    for r in rows:
        scenes.setdefault(r["scene"], []).append(r)
    return scenes


def panel(ax, name, rows):
    def f(r, k):
        return float(r[k])
    for key, style, label in (("with", "-o", "with history"), ("without", "--s", "without history")):
        pts = [(f(r, "ms_" + key), f(r, "err_" + key), r["rtol"]) for r in rows if f(r, "err_" + key) > 0]
        ax.loglog([p[0] for p in pts], [p[1] for p in pts], style, label=label)
        for ms, err, rtol in pts[:: 2]:
            ax.annotate(rtol, (ms, err), fontsize=7, xytext=(3, 3), textcoords="offset points")
    ratios = [f(r, "ratio_equal_error") for r in rows if not math.isnan(f(r, "ratio_equal_error"))]
    worst = f"; at equal error with history costs {min(ratios):.2f}-{max(ratios):.2f}x" if ratios else ""
    ax.set_title(f"{name}{worst}", fontsize=9)
    ax.set_xlabel("integration time, ms (median)")
    for axis in (ax.xaxis,):
        axis.set_major_formatter(ip.matplotlib.ticker.FormatStrFormatter("%g"))
        axis.set_minor_formatter(ip.matplotlib.ticker.FormatStrFormatter("%g"))
    ax.set_ylabel("|e - e_ref|")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)


def main() -> int:
    if len(sys.argv) != 3:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    rows = ip.read_rows(Path(sys.argv[1]))
    scenes = by_scene(rows)
    fig, axes = ip.plt.subplots(1, len(scenes), figsize=(5.5 * len(scenes), 4.5), squeeze=False)
    for ax, (name, rs) in zip(axes[0], scenes.items()):
        panel(ax, name, rs)
    fig.suptitle("What the history force costs: work-precision with and without it (same run)")
    fig.tight_layout()
    ip.save_png(fig, Path(sys.argv[2]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
