#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Plot `imcol laws`: for one scene the first contact of each law (U_rel and the gap against time: where each law stops
the pair); for a sweep (--vary) e against St per law.

Usage: /usr/bin/python3 scripts/plot_laws.py DIR
(reads DIR/laws.json and DIR/laws_traces.csv or, for a sweep, DIR/laws.csv; writes DIR/laws.png)
Needs Debian's python3-matplotlib (importable from /usr/bin/python3 only).
"""
import json
import sys
from collections import defaultdict

from imcol_plot import out_dir, plt, read_rows, save_png


def plot_sweep(out, meta) -> int:
    """e against St, one line per law; e_dry dashed."""
    series = defaultdict(lambda: ([], []))
    for r in read_rows(out / "laws.csv"):
        if r["status"] == "ran" and r["St"] and r["e"]:
            st, e = series[r["law"]]
            st.append(float(r["St"]))
            e.append(float(r["e"]))
    if not series:
        print("laws.csv has no point with St and e", file=sys.stderr)
        return 1
    fig, ax = plt.subplots(figsize=(8, 5.5))
    for law, (st, e) in sorted(series.items()):
        pts = sorted(zip(st, e))
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", ms=4, lw=1.2, label=law)
    if meta.get("e_dry"):
        ax.axhline(meta["e_dry"], color="grey", lw=0.8, ls="--", label="e_dry")
    ax.set_xscale("log")
    ax.set_xlabel("St")
    ax.set_ylabel(f"e ({meta.get('e_is', 'e')})")
    ax.set_title(f"{meta['scene']}: e against St per contact law ({meta['vary']} swept)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    fig.tight_layout()
    save_png(fig, out / "laws.png")
    return 0


def main() -> int:
    out = out_dir(__doc__)
    if out is None:
        return 2
    meta = json.loads((out / "laws.json").read_text())
    if "vary" in meta:
        return plot_sweep(out, meta)
    e_of = {row["law"]: row.get("e") for row in meta["laws"]}
    series = defaultdict(lambda: ([], [], [], []))
    for r in read_rows(out / "laws_traces.csv"):
        t, gap, u, f = series[r["law"]]
        t.append(1e3 * float(r["t_s"]))
        gap.append(1e6 * float(r["gap_m"]))
        u.append(float(r["u_rel_m_s"]))
        f.append(abs(float(r["f_contact_N"])))
    if not series:
        print("laws_traces.csv has no samples near a contact", file=sys.stderr)
        return 1
    fig, (ax_u, ax_g) = plt.subplots(1, 2, figsize=(12, 4.8))
    for law, (t, gap, u, f) in sorted(series.items()):
        e = e_of.get(law)
        label = f"{law}: e = {e:.4f}" if isinstance(e, (int, float)) else f"{law}: e undefined"
        ax_u.plot(t, u, ".-", ms=3, lw=1.2, label=label)
        ax_g.plot(t, gap, ".-", ms=3, lw=1.2, label=f"{law}: min gap {min(gap):.1f} um")
    dss = meta.get("delta_ss_m")
    if dss:
        ax_g.axhline(1e6 * dss, color="grey", lw=0.8, ls=":", label="delta_SS (the laws act below it)")
    ax_u.axhline(0, color="grey", lw=0.6)
    ax_g.axhline(0, color="grey", lw=0.6)
    ax_u.set_ylabel("U_rel [m/s] (> 0 approaching)")
    ax_u.set_title("(a) relative velocity near contact (gap < 3 delta_SS)")
    ax_g.set_ylabel("gap [um]")
    ax_g.set_title("(b) gap: where each law stops the pair")
    for ax in (ax_u, ax_g):
        ax.set_xlabel("t [ms] (output samples and events)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(f"{meta['scene']}: contact laws")
    fig.tight_layout()
    save_png(fig, out / "laws.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
