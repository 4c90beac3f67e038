#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Plot e against St for `imcol sweep`, with the seed's Table 6.1 overlaid for a sphere pair.

Usage: /usr/bin/python3 scripts/plot_sweep.py DIR [--compare DIR2]... [--out PNG]
(reads DIR/sweep.csv and DIR/sweep.json, writes DIR/sweep.png; --compare draws another sweep dashed beside it;
points without e are red x marks on the bottom axis and gaps in the lines; DIR/dem.json's fits are drawn when present)
"""
import argparse
import json
import math
import sys
from pathlib import Path

from imcol_plot import has_e, plt, positions, read_rows, save_png

SEED_TABLE = Path(__file__).resolve().parent.parent / "data" / "reference" / "li_2010_table_6_1.csv"
# Legendre, Zenit, Daniel & Guiraud (2006), Chem. Eng. Sci. 61, 3543: e/e_dry = exp(-35/St_L),
# St_L = (rho_p + rho_f/2) U d / (9 mu), a correlation of sphere-wall experiments (incl. Joseph et al. 2001, Gondret et al. 2002).
LEGENDRE_ST_C = 35.0


MEASURES = (("e", "e (the measure e_is names: joseph_2001 for a wall, yang_hunt_2006 for a pair by default)", "o"),
            ("e_fit_time", "fit_time (lines over measure.window)", "s"),
            ("e_instant", "e_instant (at measure.instant_gap)", "x"),
            ("e_fit_distance", "fit over measure.fit_distance", "^"),
            ("e_at_gap", "velocities at measure.at_gap", "v"),
            ("e_peak_rebound", "largest rebound / largest approach speed", "d"))


def sweep_label(meta) -> str:
    effects = meta.get("effects", [])
    return ("coupled" if "flow" in effects else "reduced-order") + " (%s swept)" % meta["vary"]


def mark_failed(ax, rows, xs, label_prefix: str = "") -> None:
    """Points without e (the run failed, or e was not measured): a red x on the bottom axis at their St, and a gap in
    the lines (drawn by the callers through NaN)."""
    fx = [x for r, x in zip(rows, xs) if not has_e(r) and math.isfinite(x)]
    if fx:
        ax.plot(fx, [0.0] * len(fx), "x", color="red", ms=9, mew=2, clip_on=False, zorder=5,
                transform=ax.get_xaxis_transform(),
                label="%sfailed (no e): %d point%s, a gap in the lines" % (label_prefix, len(fx), "s" if len(fx) > 1 else ""))


def plot_sweep(ax, folder: Path, meta, style: str, tag: str) -> None:
    """Every named measure of one sweep: one colour per measure, `style` per sweep; failed points as marked gaps."""
    rows = read_rows(folder / "sweep.csv")
    if not rows:
        return
    xs = positions(rows, meta, "St")
    for i, (key, label, mk) in enumerate(MEASURES):
        pts = sorted((x, float(r[key]) if has_e(r) else float("nan")) for r, x in zip(rows, xs)
                     if math.isfinite(x) and (not has_e(r) or r.get(key)))
        if any(math.isfinite(y) for _, y in pts):
            ax.semilogx(*zip(*pts), mk + style, color="C%d" % i, ms=4, lw=1.2 if key == "e" else 0.8,
                        mfc="none" if tag else None, label=(tag + label) if tag else label)
    mark_failed(ax, rows, xs, tag)


def plot_fits(ax, folder: Path, meta) -> None:
    """With --export dem: the best fit of e(St) and the exponential one (dem.json), over the St range they hold."""
    path = folder / "dem.json"
    if not path.exists():
        return
    dem = json.loads(path.read_text())
    pair = dem.get("configuration") == "sphere-sphere"
    chosen = []
    for which in (dem.get("best"), dem.get("exp")):  # the best fit, and the exponential one if it is another
        chosen += [f for f in dem["fits"] if which and (f["form"], f["e_dry_is"]) == (which["form"], which["e_dry_is"]) and f not in chosen]
    for f, (ls, colour) in zip(chosen, ((":", "k"), ("-.", "0.45"))):
        lo, hi = f["valid_St"]
        st = [lo * (hi / lo) ** (i / 199) for i in range(200)]
        g = (lambda x: math.exp(-f["St_c"] / x)) if f["form"] == "exp" else (lambda x: max(0.0, 1 - f["St_c"] / x))
        # a pair's bottom axis is the summary's St, half the DEM St of the fit
        ax.semilogx([x / 2 if pair else x for x in st], [f["e_dry"] * g(x) for x in st], ls, color=colour,
                    lw=1.6, label="fit %s: St_c = %.3g%s, e_dry = %.3f%s, rms %.3f" % (
                        "exp(-St_c/St)" if f["form"] == "exp" else "(1 - St_c/St)", f["St_c"], " (top axis)" if pair else "",
                        f["e_dry"], "" if f["e_dry_is"] == "fitted" else " fixed", f["rms_residual"]))


def plot_legendre(ax, folder: Path, meta) -> bool:
    """Sphere-wall sweeps: e/e_dry of the default measure against St_L, with Legendre et al. (2006)'s correlation."""
    e_dry = meta.get("e_dry")
    rows = read_rows(folder / "sweep.csv")
    if not e_dry or not any(has_e(r) and r.get("St_L") for r in rows):
        return False
    xs = positions(rows, meta, "St_L")
    pts = sorted((x, float(r["e"]) / e_dry if has_e(r) else float("nan")) for r, x in zip(rows, xs) if math.isfinite(x))
    ax.semilogx(*zip(*pts), "o-", color="C0", ms=4, label="imcol: e / e_dry (%s)" % str(meta.get("e_is") or "e").split(" (")[0])
    finite = [p[0] for p in pts if math.isfinite(p[1])]
    lo, hi = min(finite), max(finite)
    xs_c = [lo * (hi / lo) ** (i / 199) for i in range(200)] if hi > lo else [lo]
    ax.semilogx(xs_c, [math.exp(-LEGENDRE_ST_C / x) for x in xs_c], "k--", lw=1.2,
                label="Legendre et al. (2006): exp(-35/St_L), a correlation of experiments")
    mark_failed(ax, rows, xs)
    ax.set_xlabel("St_L = (rho_p + rho_f/2) U d / (9 mu)", fontsize=8)
    ax.set_ylabel("e / e_dry")
    ax.set_ylim(-0.02, 1.05)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    return True


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.strip().splitlines()[0])
    ap.add_argument("dir", type=Path, help="a sweep's output folder (sweep.csv, sweep.json)")
    ap.add_argument("--compare", type=Path, action="append", default=[],
                    help="another sweep's folder, drawn dashed in the same axes (e.g. coupled beside reduced-order)")
    ap.add_argument("--out", type=Path, help="the PNG to write (default DIR/sweep.png)")
    args = ap.parse_args()
    out = args.dir
    meta = json.loads((out / "sweep.json").read_text())
    # the legend goes below the axes (it would cover the rise of e at St 10-30 or the high-St plateau):
    # a taller figure for two sweeps, whose ten entries stand in two columns (one per sweep)
    # sphere-wall: a second panel, e/e_dry against St_L beside Legendre et al.'s correlation of experiments
    wall = meta["configuration"] == "sphere-wall" and meta.get("e_dry")
    if wall:
        fig, (ax, ax_l) = plt.subplots(1, 2, figsize=(15, 7) if args.compare else (14, 6.4))
    else:
        fig, ax = plt.subplots(figsize=(9, 7) if args.compare else (8, 6.4))
    others = [(d, json.loads((d / "sweep.json").read_text())) for d in args.compare]
    plot_sweep(ax, out, meta, "-", sweep_label(meta) + ": " if others else "")
    for d, m in others:
        plot_sweep(ax, d, m, "--", sweep_label(m) + ": ")
    plot_fits(ax, out, meta)
    if meta["configuration"] == "sphere-sphere" and SEED_TABLE.exists():
        seed = read_rows(SEED_TABLE)
        ax.semilogx([float(r["St_B"]) for r in seed], [float(r["e"]) for r in seed], "s", color="k", mfc="none", ms=7,
                    label="Li (2010) Table 6.1, simulated (St_B; run numbers)")
        # run numbers, alternately above and below their points so that neighbours' labels do not overlap
        for i, r in enumerate(sorted(seed, key=lambda r: float(r["St_B"]))):
            ax.annotate(f"run {r['run']}", (float(r["St_B"]), float(r["e"])), fontsize=7,
                        xytext=(4, 8 if i % 2 else -12), textcoords="offset points")
    ax.set_xlabel("St (%s)" % (meta.get("St_convention") or "see summary"), fontsize=8)
    if meta["configuration"] == "sphere-sphere":
        # the other pair convention, named: St_B by eq. (6.2) is twice the Table 6.1 St_B on the bottom axis
        top = ax.secondary_xaxis("top", functions=(lambda x: 2 * x, lambda x: x / 2))
        top.set_xlabel("St_B, eq. (6.2): m* U_rel / (6 pi mu a*^2) = 2 x St_B (Table 6.1)", fontsize=8)
    ax.set_ylabel("e")
    ax.set_ylim(-0.02, 1.02)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7 if others else 8, loc="upper center", bbox_to_anchor=(0.5, -0.11), ncol=2,
              frameon=False, columnspacing=1.5)
    n_fail = len(meta["failures"]) + sum(len(m["failures"]) for _, m in others)
    what = "%d points" % meta["points"] if not others else "%d sweeps" % (1 + len(others))
    ax.set_title("%s: e vs St (%s), %s%s" % (meta["scene"], ", ".join(meta.get("effects", [])) if not others else "each named measure",
                                             what, ", %d failed" % n_fail if n_fail else ""), fontsize=10)
    if wall and not plot_legendre(ax_l, out, meta):
        ax_l.set_axis_off()
    elif wall:
        ax_l.set_title("%s: e / e_dry vs St_L and a correlation of experiments" % meta["scene"], fontsize=10)
    fig.tight_layout()
    save_png(fig, args.out or out / "sweep.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
