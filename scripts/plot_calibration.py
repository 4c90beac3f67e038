#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Plot `imcol calibrate`: the measurement and the fitted model, and the objective's profile of each parameter.

Usage: /usr/bin/python3 scripts/plot_calibration.py DIR
(reads DIR/calibration.json, DIR/measured.csv, DIR/best.csv and DIR/calibration.csv; writes DIR/calibration.png)

A trajectory: the measured z of each sphere (points) and the fitted run on the measurement's clock (lines, shifted
by the fitted offset tau), the fitted window shaded, as the seed's Fig. 6.8. An e table: e against the varied key,
measured and fitted. Then one panel per parameter: the objective along it (the profile; without profiles, every
evaluation), the line factor x best (its confidence, if that set it) and the interval where the objective stays
below it.
"""
import bisect
import json
import math
import sys

from imcol_plot import out_dir, plt, read_rows, save_png


def num(r, key):
    try:
        v = float(r.get(key, ""))
    except ValueError:
        return math.nan
    return v


def plot_trajectory(ax, folder, meta):
    m = meta["measurement"]
    measured = read_rows(folder / "measured.csv")
    best = read_rows(folder / "best.csv")
    w = m["window"]
    ax.axvspan(w["from_s"] * 1e3, w["to_s"] * 1e3, color="0.9", label="fitted window")
    ax.axvline(w["t_contact_s"] * 1e3, color="0.6", lw=0.8, ls=":", label="measured contact")
    for i, col in enumerate(m["columns"]):
        t = [num(r, "t") * 1e3 for r in measured]
        z = [num(r, col) * 1e3 for r in measured]
        ax.plot(t, z, "o", ms=3, mfc="none", color="C%d" % i, label="measured %s" % col)
        if best and col in best[0]:
            ax.plot([num(r, "t") * 1e3 for r in best], [num(r, col) * 1e3 for r in best], "-", lw=1.3, color="C%d" % i,
                    label="fitted %s" % col)
    # the measured record's span (the fitted run may go on past it)
    ts = [num(r, "t") * 1e3 for r in measured]
    pad = 0.03 * (max(ts) - min(ts))
    ax.set_xlim(min(ts) - pad, max(ts) + pad)
    zs = [num(r, c) * 1e3 for r in measured for c in m["columns"]]
    zpad = 0.05 * (max(zs) - min(zs) or 1)
    ax.set_ylim(min(zs) - zpad, max(zs) + zpad)
    ax.set_xlabel("t (ms, the measurement's clock)")
    ax.set_ylabel("z (mm)")
    b = meta["best"]
    tau = b.get("tau_s")
    title = "%s: measured and fitted" % meta["scene"]
    if b.get("ok"):
        title += " (rms %.3g µm%s)" % (b["rms"] * 1e6, ", τ = %.3g ms" % (tau * 1e3) if tau is not None else "")
    ax.set_title(title, fontsize=10)
    ax.legend(fontsize=7, loc="best")


def plot_residuals(ax, folder, meta):
    """Measured minus fitted z of each column at the measured times (µm), the window shaded: what the fit leaves."""
    m = meta["measurement"]
    measured = read_rows(folder / "measured.csv")
    best = read_rows(folder / "best.csv")
    w = m["window"]
    ax.axvspan(w["from_s"] * 1e3, w["to_s"] * 1e3, color="0.9")
    ax.axhline(0, color="0.5", lw=0.8)
    if len(best) < 2:
        return
    tb = [num(r, "t") for r in best]
    for i, col in enumerate(m["columns"]):
        if col not in best[0]:
            continue
        zb = [num(r, col) for r in best]
        ts, res = [], []
        for r in measured:
            t = num(r, "t")
            j = min(max(bisect.bisect_right(tb, t) - 1, 0), len(tb) - 2)
            f = (t - tb[j]) / (tb[j + 1] - tb[j])
            ts.append(t * 1e3)
            res.append((num(r, col) - (zb[j] + f * (zb[j + 1] - zb[j]))) * 1e6)
        ax.plot(ts, res, ".", ms=2, color="C%d" % i, label="%s measured - fitted" % col)
    ax.set_xlabel("t (ms, the measurement's clock)")
    ax.set_ylabel("residual (µm)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, loc="best")


def plot_table(ax, folder, meta):
    key = meta["measurement"].get("varied")
    rows = read_rows(folder / "best.csv")
    pts = sorted((num(r, key), num(r, "e_meas"), num(r, "e_sim")) for r in rows)
    x = [p[0] for p in pts]
    ax.plot(x, [p[1] for p in pts], "o", mfc="none", color="C0", label="measured e")
    ax.plot(x, [p[2] for p in pts], "s-", ms=4, color="C1", label="fitted e_sim")
    if len(x) > 1 and min(x) > 0 and max(x) / min(x) > 10:
        ax.set_xscale("log")
    ax.set_xlabel(key)
    ax.set_ylabel("e")
    b = meta["best"]
    ax.set_title("%s: e measured and fitted%s" % (meta["scene"], " (rms %.3g)" % b["rms"] if b.get("ok") else ""), fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)


def plot_profile(ax, meta, k, evaluations):
    p = meta["parameters"][k]
    key = p["key"]
    best = meta["best"]
    profiles = meta.get("profiles") or []
    log = p["scale"] == "log"
    # every evaluation, faint: what the search saw along this parameter
    ev = [(num(r, key), num(r, "objective")) for r in evaluations if r.get("status") == "ok"]
    ev = [(x, y) for x, y in ev if math.isfinite(x) and math.isfinite(y) and y > 0]
    if ev:
        ax.plot(*zip(*ev), ".", ms=3, color="0.7", label="evaluations")
    if k < len(profiles):
        pr = profiles[k]
        pts = [(x, y) for x, y in zip(pr["values"], pr["objective"]) if y is not None and y > 0]
        if pts:
            ax.plot(*zip(*pts), "o-", ms=3, color="C0", label="profile")
        if pr.get("threshold"):
            rule = pr.get("factor_rule") or {}
            label = "%.6g x best" % pr["factor"]
            if rule.get("kind") == "confidence":
                label = "%g %% confidence: %s" % (100 * rule["confidence"], label)
            ax.axhline(pr["threshold"], color="C3", lw=0.9, ls="--", label=label)
        lo = pr["interval"]["lo"]
        hi = pr["interval"]["hi"]
        ax.axvspan(p["lo"] if lo is None else lo, p["hi"] if hi is None else hi, color="C2", alpha=0.12,
                   label="interval [%s, %s]" % ("open" if lo is None else "%.4g" % lo, "open" if hi is None else "%.4g" % hi))
    if best.get("ok"):
        ax.plot([best["values"][key]], [best["objective"]], "*", ms=11, color="C3", label="best %.5g" % best["values"][key])
    ax.axvline(p["start"], color="0.5", lw=0.8, ls=":", label="start %.4g" % p["start"])
    ax.set_xlim(p["lo"], p["hi"])
    if log:
        ax.set_xscale("log")
    lo_y, hi_y = ax.get_ylim()
    if lo_y > 0 and hi_y > 3 * lo_y:  # a log axis only where the objective spans more than a factor of 3
        ax.set_yscale("log")
    else:  # a narrow range: linear, the power of ten once at the top
        ax.ticklabel_format(axis="y", style="sci", scilimits=(0, 0), useMathText=True)
    ax.set_xlabel(key)
    ax.set_ylabel("objective (%s)" % meta["objective"]["unit"])
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)


def main() -> int:
    folder = out_dir(__doc__)
    if folder is None:
        return 2
    meta = json.loads((folder / "calibration.json").read_text())
    evaluations = read_rows(folder / "calibration.csv")
    n = len(meta["parameters"])
    trajectory = meta["measurement"]["kind"] == "trajectory"
    fig = plt.figure(figsize=(6.5 + 4.2 * n, 6.4 if trajectory else 4.6))
    grid = fig.add_gridspec(2 if trajectory else 1, 1 + n, height_ratios=[2, 1] if trajectory else [1])
    if trajectory:
        top = fig.add_subplot(grid[0, 0])
        plot_trajectory(top, folder, meta)
        bottom = fig.add_subplot(grid[1, 0], sharex=top)
        plot_residuals(bottom, folder, meta)
        top.set_xlabel("")
    else:
        plot_table(fig.add_subplot(grid[0, 0]), folder, meta)
    for k in range(n):
        plot_profile(fig.add_subplot(grid[:, 1 + k]), meta, k, evaluations)
    fig.tight_layout()
    save_png(fig, folder / "calibration.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
