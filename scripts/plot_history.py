#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Plot `imcol history`: for one scene the history force against time per kernel and evaluator (the whole run, and
around its peak); for a sweep (--vary) e against St per kernel. One colour per kernel in both pictures.

Usage: /usr/bin/python3 scripts/plot_history.py DIR
(reads DIR/history.csv and DIR/history_forces.csv, writes DIR/history.png; or, for a sweep, reads
DIR/history_sweep.json and DIR/history_sweep.csv and writes DIR/history_sweep.png)
Needs Debian's python3-matplotlib (importable from /usr/bin/python3 only).
"""
import json
import math
import sys
from collections import defaultdict

from matplotlib import ticker

from imcol_plot import has_e, kernel_colour, out_dir, plt, positions, read_rows, save_png

# Line style per evaluator: the sums of exponentials solid and dotted, the direct quadrature (reference) dashed.
STYLE = {"soe-step": "-", "soe": ":", "direct": "--", "-": "-"}


def number(text):
    return float(text) if text not in ("", None) else None


def plot_runs(out) -> int:
    """history.png: f_H of sphere 1 against time, (a) the whole run, (b) around the peak (every sample)."""
    table = {(r["kernel"], r["evaluator"]): r for r in read_rows(out / "history.csv")}
    metric = "e" if "e" in next(iter(table.values()), {}) else "u_end_m_s"
    series = defaultdict(lambda: ([], []))
    for r in read_rows(out / "history_forces.csv"):
        kernel, evaluator = (r["kernel"], r["evaluator"]) if "kernel" in r else r["label"].rsplit(" ", 1)
        t, fh = series[(kernel, evaluator)]
        t.append(1e3 * float(r["t"]))
        fh.append(float(r["f_hist1"]))
    if not series:
        print("history_forces.csv has no samples", file=sys.stderr)
        return 1
    # Around the peak of the first series: from where it rises through half its peak, over a few of those rise times.
    t0, f0 = next(iter(series.values()))
    k = max(range(len(f0)), key=lambda i: abs(f0[i]))
    j = k
    while j > 0 and abs(f0[j]) > 0.5 * abs(f0[k]):
        j -= 1
    rise = max(t0[k] - t0[j], 1e-6)
    lo, hi = t0[k] - 4 * rise, t0[k] + 16 * rise
    fig, (ax_a, ax_b) = plt.subplots(1, 2, figsize=(14, 5.5))
    name = "e" if metric == "e" else "u_end"
    for (kernel, evaluator), (t, fh) in series.items():
        row = table.get((kernel, evaluator), {})
        value = number(row.get(metric))
        peak = max(abs(f) for f in fh)
        label = f"{kernel} {evaluator}: {name} = {value:.6f}" if value is not None else f"{kernel} {evaluator}: {name} undefined"
        label += f", peak {peak:.4g} N"
        style = dict(color=kernel_colour(kernel), ls=STYLE.get(evaluator, "-."), lw=1.3 if evaluator != "direct" else 1.0)
        ax_a.plot(t, [abs(f) for f in fh], **style)
        near = [(x, y) for x, y in zip(t, fh) if lo <= x <= hi]
        ax_b.plot([x for x, _ in near], [y for _, y in near], marker=".", ms=3, label=label, **style)
    none = table.get(("none", "-"))
    if none and number(none.get(metric)) is not None:
        ax_b.plot([], [], color=kernel_colour("none"), label=f"none (no history force): {name} = {number(none[metric]):.6f}")
    ax_a.set_title("(a) the whole run, |f_H| on a log scale (where the kernels' memories differ)", fontsize=10)
    ax_a.set_yscale("log")
    ax_a.set_ylim(bottom=1e-5 * max(max(abs(f) for f in fh) for _, fh in series.values()))
    ax_a.set_ylabel("|f_H| on sphere 1 [N]")
    ax_b.set_title("(b) around the peak: every sample", fontsize=10)
    ax_b.set_xlim(lo, hi)
    ax_b.set_ylabel("history force on sphere 1, f_H [N]")
    for ax in (ax_a, ax_b):
        ax.set_xlabel("t [ms]")
        ax.grid(alpha=0.3)
    style_names = {"soe-step": "solid", "soe": "dotted", "direct": "dashed"}
    ran = [f"{style_names[ev]} {ev}" for ev in style_names if any(e == ev for _, e in series)]
    ax_b.legend(fontsize=7.5, loc="upper left", bbox_to_anchor=(1.02, 1.0), title="colour: kernel; " + ", ".join(ran), title_fontsize=7.5)
    fig.suptitle("History force by kernel and evaluator (peak |f_H| over the samples drawn, as in history.csv)")
    fig.tight_layout()
    save_png(fig, out / "history.png")
    return 0


def plot_sweep(out) -> int:
    """history_sweep.png: e against St, a line per kernel (and evaluator); runs without e marked."""
    meta = json.loads((out / "history_sweep.json").read_text())
    rows = read_rows(out / "history_sweep.csv")
    if not rows:
        print("history_sweep.csv has no rows", file=sys.stderr)
        return 1
    n = meta["points"]
    # Where a run has no St (it failed), the St of the other runs at its point, else interpolated from its neighbours.
    for r, x in zip(rows, positions(rows, meta, "St")):
        r["x"] = x
    fig, (ax, ax_d) = plt.subplots(2, 1, figsize=(9.5, 8), sharex=True, gridspec_kw={"height_ratios": [2, 1]})
    series = defaultdict(list)
    for r in rows:
        series[(r["kernel"], r["evaluator"])].append(r)
    evaluators = {ev for _, ev in series if ev != "-"}
    # (b): each kernel's e minus Basset's (the first listed kernel's if Basset did not run) at the same point.
    ref_key = next((k for k in series if k[0] == "basset"), next((k for k in series if k[0] != "none"), None))
    ref = {int(r["point"]): number(r["e"]) for r in series.get(ref_key, []) if r["status"] == "ok" and r["e"]}
    failed, missing = [], []  # (St, e) where a run has no e: a gap in its line, marked at the neighbours' mean
    for (kernel, evaluator), rs in series.items():
        rs = sorted(rs, key=lambda r: int(r["point"]))
        label = kernel if kernel == "none" or len(evaluators) == 1 else f"{kernel} {evaluator}"
        if kernel == "none":
            label = "none (no history force)"
        style = dict(marker="o", ms=4, lw=1.3, color=kernel_colour(kernel), ls=STYLE.get(evaluator, "-."))
        ok = [has_e(r) and bool(r["St"]) for r in rs]
        xs = [r["x"] for r in rs]
        es = [number(r["e"]) if good else float("nan") for r, good in zip(rs, ok)]
        ax.plot(xs, es, label=label, **style)
        if kernel != "none":
            ax_d.plot(xs, [e - ref.get(int(r["point"]), float("nan")) for r, e in zip(rs, es)], **style)
        for i, (r, good) in enumerate(zip(rs, ok)):
            if good or not math.isfinite(xs[i]):
                continue
            near = [es[j] for j in (i - 1, i + 1) if 0 <= j < len(es) and ok[j]]
            (failed if r["status"] != "ok" else missing).append((xs[i], sum(near) / len(near) if near else None))
    for marks, symbol, colour, what in ((failed, "x", "red", "run failed"), (missing, "+", "darkorange", "e not measured")):
        placed = [(x, y) for x, y in marks if y is not None]
        if marks:
            ax.plot([x for x, _ in placed], [y for _, y in placed], symbol, color=colour, ms=10, mew=2.2, ls="none",
                    label=f"{what} ({len(marks)}; reasons in history_sweep.csv)")
    if meta.get("e_dry"):
        ax.axhline(meta["e_dry"], color="grey", lw=0.8, ls="--", label=f"e_dry = {meta['e_dry']:g}")
    ax.set_xscale("log")
    ax_d.xaxis.set_major_formatter(ticker.LogFormatter(labelOnlyBase=False, minor_thresholds=(3, 1)))
    ax_d.xaxis.set_minor_formatter(ticker.LogFormatter(labelOnlyBase=False, minor_thresholds=(3, 1)))
    ax_d.set_xlabel("St (measured at impact, each run's own)")
    ref_name = " ".join(ref_key) if ref_key and len(evaluators) > 1 else (ref_key[0] if ref_key else "")
    ax_d.set_ylabel(f"e - e({ref_name})")
    ax_d.axhline(0, color="grey", lw=0.6)
    ax_d.set_title(f"each kernel's e minus {ref_name}'s at the same point", fontsize=9)
    ax_d.grid(alpha=0.3, which="both")
    ax.set_ylabel(f"e ({meta.get('e_is') or 'e'})")
    ax.set_title(f"{meta['scene']}: e against St per history kernel ({meta['vary']} from {meta['from']:g} to {meta['to']:g}, "
                 f"{n} points)", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.02, 1.0), title="history kernel", title_fontsize=8)
    fig.tight_layout()
    save_png(fig, out / "history_sweep.png")
    return 0


def main() -> int:
    out = out_dir(__doc__)
    if out is None:
        return 2
    if (out / "history_sweep.json").exists():
        return plot_sweep(out)
    return plot_runs(out)


if __name__ == "__main__":
    sys.exit(main())
