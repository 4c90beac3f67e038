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

from imcol_plot import (KERNEL_MARKS, has_e, kernel_colour, kernel_label, kernel_style, out_dir, plt, positions, read_rows,
                        save_png, sweep_scene_text)

# Line style per evaluator: the sums of exponentials solid and dotted, the direct quadrature (reference) dashed.
STYLE = {"soe-step": "-", "soe": ":", "direct": "--", "-": "-"}


def number(text):
    return float(text) if text not in ("", None) else None


def read_series(out):
    """history_forces.csv as {(kernel, evaluator): (t in ms, f_hist1 in N)}, in the file's order."""
    series = defaultdict(lambda: ([], []))
    for r in read_rows(out / "history_forces.csv"):
        kernel, evaluator = (r["kernel"], r["evaluator"]) if "kernel" in r else r["label"].rsplit(" ", 1)
        t, fh = series[(kernel, evaluator)]
        t.append(1e3 * float(r["t"]))
        fh.append(float(r["f_hist1"]))
    return series


def peak_window(t, f):
    """Around the peak of f: from where it rises through half its peak, over a few of those rise times."""
    k = max(range(len(f)), key=lambda i: abs(f[i]))
    j = k
    while j > 0 and abs(f[j]) > 0.5 * abs(f[k]):
        j -= 1
    rise = max(t[k] - t[j], 1e-6)
    return t[k] - 4 * rise, t[k] + 16 * rise


def run_style(kernel: str, evaluator: str) -> dict:
    """A curve of history.png: the kernel's colour, marker and draw order, the evaluator's line style; markers a tenth
    of the panel apart along the curve, shifted per kernel so that curves on top of each other show every kernel."""
    style = kernel_style(kernel)
    shift = list(KERNEL_MARKS).index(kernel) if kernel in KERNEL_MARKS else 0
    style.update(ls=STYLE.get(evaluator, "-."), markevery=(0.02 * shift, 0.1), ms=min(style["ms"], 7))
    if evaluator != "soe-step":
        style.update(lw=1.0, zorder=style["zorder"] - 1)
    return style


def plot_runs(out) -> int:
    """history.png: f_H of sphere 1 against time, (a) the whole run, (b) around the peak."""
    table = {(r["kernel"], r["evaluator"]): r for r in read_rows(out / "history.csv")}
    metric = "e" if "e" in next(iter(table.values()), {}) else "u_end_m_s"
    series = read_series(out)
    if not series:
        print("history_forces.csv has no samples", file=sys.stderr)
        return 1
    lo, hi = peak_window(*next(iter(series.values())))
    fig, (ax_a, ax_b) = plt.subplots(1, 2, figsize=(14, 6.2))
    name = "e" if metric == "e" else "u_end"
    for (kernel, evaluator), (t, fh) in series.items():
        value = number(table.get((kernel, evaluator), {}).get(metric))
        label = f"{kernel} {evaluator}: {name} = {value:.6f}" if value is not None else f"{kernel} {evaluator}: {name} undefined"
        label += f", peak {max(abs(f) for f in fh):.4g} N"
        ax_a.plot(t, [abs(f) for f in fh], **run_style(kernel, evaluator))
        near = [(x, y) for x, y in zip(t, fh) if lo <= x <= hi]
        ax_b.plot([x for x, _ in near], [y for _, y in near], label=label, **run_style(kernel, evaluator))
    none = table.get(("none", "-"))
    if none and number(none.get(metric)) is not None:
        ax_b.plot([], [], color=kernel_colour("none"), label=f"none (no history force): {name} = {number(none[metric]):.6f}")
    ax_a.set_title("(a) the whole run, |f_H| on a log scale (where the kernels' memories differ)", fontsize=10)
    ax_a.set_yscale("log")
    ax_a.set_ylim(bottom=1e-5 * max(max(abs(f) for f in fh) for _, fh in series.values()))
    ax_a.set_ylabel("|f_H| on sphere 1 (N)")
    ax_b.set_title("(b) around the peak", fontsize=10)
    ax_b.set_xlim(lo, hi)
    ax_b.set_ylabel("history force on sphere 1, f_H (N)")
    for ax in (ax_a, ax_b):
        ax.set_xlabel("t (ms)")
        ax.grid(alpha=0.3)
    style_names = {"soe-step": "solid", "soe": "dotted", "direct": "dashed"}
    ran = [f"{style_names[ev]} {ev}" for ev in style_names if any(e == ev for _, e in series)]
    ax_b.legend(fontsize=7.5, loc="upper left", bbox_to_anchor=(1.02, 1.0), title="colour and marker: kernel; " + ", ".join(ran),
                title_fontsize=7.5)
    fig.suptitle("History force by kernel and evaluator (peak |f_H| over the samples drawn, as in history.csv)")
    kernels = list(dict.fromkeys(k for k, _ in series))
    fig.text(0.01, 0.01, "kernels: " + "; ".join(kernel_label(k) for k in kernels), fontsize=8.5)
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    save_png(fig, out / "history.png")
    return 0


def sweep_series(rows, evaluators):
    """history_sweep.csv's rows by (kernel, evaluator), Basset last (drawn on top), each sorted by point."""
    series = defaultdict(list)
    for r in rows:
        series[(r["kernel"], r["evaluator"])].append(r)
    order = sorted(series, key=lambda k: KERNEL_MARKS.get(k[0], ("", "", 2))[2])
    return {k: sorted(series[k], key=lambda r: int(r["point"])) for k in order}


def draw_kernel(ax, ax_d, key, rs, ref, evaluators, marks) -> None:
    """One kernel's e against St (top) and its e minus the reference's (bottom); appends its runs without e to
    marks: {"failed"|"missing": [(St, e of the neighbours)]}."""
    kernel, evaluator = key
    gap = [abs(number(r["e"]) - ref[int(r["point"])]) for r in rs if has_e(r) and int(r["point"]) in ref]
    label = kernel_label(kernel) if len(evaluators) <= 1 or kernel == "none" else f"{kernel_label(kernel)}, {evaluator}"
    if kernel not in ("none", "basset") and gap:
        label += f" (|e − e_basset| ≤ {max(gap):.3f})"
    style = kernel_style(kernel)
    if len(evaluators) > 1:
        style["ls"] = STYLE.get(evaluator, "-.")
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
        marks["failed" if r["status"] != "ok" else "missing"].append((xs[i], sum(near) / len(near) if near else None))


def plot_sweep(out) -> int:
    """history_sweep.png: e against St, a line per kernel (and evaluator); runs without e marked."""
    meta = json.loads((out / "history_sweep.json").read_text())
    rows = read_rows(out / "history_sweep.csv")
    if not rows:
        print("history_sweep.csv has no rows", file=sys.stderr)
        return 1
    # Where a run has no St (it failed), the St of the other runs at its point, else interpolated from its neighbours.
    for r, x in zip(rows, positions(rows, meta, "St")):
        r["x"] = x
    fig, (ax, ax_d) = plt.subplots(2, 1, figsize=(11.5, 8.5), sharex=True, gridspec_kw={"height_ratios": [2, 1]})
    evaluators = {r["evaluator"] for r in rows if r["evaluator"] != "-"}
    series = sweep_series(rows, evaluators)
    # (b): each kernel's e minus Basset's (the first listed kernel's if Basset did not run) at the same point.
    ref_key = next((k for k in series if k[0] == "basset"), next((k for k in series if k[0] != "none"), None))
    ref = {int(r["point"]): number(r["e"]) for r in series.get(ref_key, []) if has_e(r)}
    marks = {"failed": [], "missing": []}
    for key, rs in series.items():
        draw_kernel(ax, ax_d, key, rs, ref, evaluators, marks)
    for what, symbol, colour, text in (("failed", "x", "red", "run failed"), ("missing", "+", "darkorange", "e not measured")):
        placed = [(x, y) for x, y in marks[what] if y is not None]
        if marks[what]:
            ax.plot([x for x, _ in placed], [y for _, y in placed], symbol, color=colour, ms=10, mew=2.2, ls="none",
                    label=f"{text} ({len(marks[what])}; reasons in history_sweep.csv)")
    if meta.get("e_dry"):
        ax.axhline(meta["e_dry"], color="grey", lw=0.8, ls="--", label=f"e_dry = {meta['e_dry']:g}")
    ax.set_xscale("log")
    ax_d.xaxis.set_major_formatter(ticker.LogFormatter(labelOnlyBase=False, minor_thresholds=(3, 1)))
    ax_d.xaxis.set_minor_formatter(ticker.LogFormatter(labelOnlyBase=False, minor_thresholds=(3, 1)))
    ax_d.set_xlabel(r"St $= m\,U\,/\,(6\pi\mu a^2)$ at impact, each run's own")
    ref_name = " ".join(ref_key) if ref_key and len(evaluators) > 1 else (ref_key[0] if ref_key else "")
    ax_d.set_ylabel(f"e − e({ref_name})")
    ax_d.axhline(0, color="grey", lw=0.6)
    ax_d.set_title(f"each kernel's e minus {ref_name}'s at the same point", fontsize=9)
    ax_d.grid(alpha=0.3, which="both")
    ax.set_ylabel(f"coefficient of restitution e ({meta.get('e_is') or 'e'})")
    ax.set_title(f"{sweep_scene_text(meta)}\ne against St per history kernel ({meta['vary']} from {meta['from']:g} to "
                 f"{meta['to']:g}, {meta['points']} points)", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.02, 1.0), title="history kernel (source)", title_fontsize=8)
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
