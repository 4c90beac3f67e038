#!/usr/bin/python3
"""Plot e against St for `imcol sweep`, with the seed's Table 6.1 overlaid for a sphere pair.

Usage: /usr/bin/python3 scripts/plot_sweep.py DIR   (reads DIR/sweep.csv and DIR/sweep.json, writes DIR/sweep.png)
"""
import csv
import json
import sys
from pathlib import Path

from imcol_plot import out_dir, plt, save_png

SEED_TABLE = Path(__file__).resolve().parent.parent / "data" / "reference" / "li_2010_table_6_1.csv"


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def main() -> int:
    out = out_dir(__doc__)
    if out is None:
        return 2
    meta = json.loads((out / "sweep.json").read_text())
    rows = [r for r in read_csv(out / "sweep.csv") if r["status"] == "ok" and r["St"] and r["e"]]
    rows.sort(key=lambda r: float(r["St"]))
    fig, ax = plt.subplots(figsize=(8, 5.5))
    ax.semilogx([float(r["St"]) for r in rows], [float(r["e"]) for r in rows], "o-", ms=4,
                label="imcol e (fit over measure.window): %s swept (%s)" % (meta["vary"], ", ".join(meta.get("effects", []))))
    # The other named measures of e (docs/bounces.md), where the sweep has them.
    for key, label, mk in (("e_instant", "e_instant (at measure.instant_gap)", "x"),
                           ("e_fit_distance", "fit over measure.fit_distance", "^"),
                           ("e_at_gap", "velocities at measure.at_gap", "v"),
                           ("e_peak_rebound", "largest rebound / largest approach speed", "d")):
        pts = [(float(r["St"]), float(r[key])) for r in rows if r.get(key)]
        if pts:
            ax.semilogx(*zip(*pts), mk + "--", ms=4, lw=0.8, label=label)
    if meta["configuration"] == "sphere-sphere" and SEED_TABLE.exists():
        seed = read_csv(SEED_TABLE)
        ax.semilogx([float(r["St_B"]) for r in seed], [float(r["e"]) for r in seed], "s", color="k", mfc="none", ms=7,
                    label="Li (2010) Table 6.1, simulated (St_B; run numbers)")
        # run numbers, alternately above and below their points so that neighbours' labels do not overlap
        for i, r in enumerate(sorted(seed, key=lambda r: float(r["St_B"]))):
            ax.annotate(f"run {r['run']}", (float(r["St_B"]), float(r["e"])), fontsize=7,
                        xytext=(4, 8 if i % 2 else -12), textcoords="offset points")
    ax.set_xlabel("St (%s)" % (meta.get("St_convention") or "see summary"), fontsize=8)
    ax.set_ylabel("e")
    ax.set_ylim(-0.02, 1.02)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    n_fail = len(meta["failures"])
    ax.set_title("%s: e vs St, %d points%s" % (meta["scene"], meta["points"], ", %d failed" % n_fail if n_fail else ""))
    fig.tight_layout()
    save_png(fig, out / "sweep.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
