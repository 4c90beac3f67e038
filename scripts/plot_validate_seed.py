#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Plot `imcol validate seed`: e against St_B in both conventions, the seed's Table 6.1 beside imcol's models.

Usage: /usr/bin/python3 scripts/plot_validate_seed.py DIR
(reads DIR/validate_seed.csv, writes DIR/validate_seed.png)
Left: St_B as the seed's Table 6.1 gives it, half of eq. (6.2); right: St_B by eq. (6.2), m* U_rel / (6 pi mu a*^2),
where the seed's points stand at twice their printed St_B (every Table 6.1 pair has equal radii).
Each model twice (the CSV's speed_set): at the printed approach speed V_Io (triangles) and at the speed that gives the
printed St_B (circles), joined by a thin line per run.
"""
import sys

from imcol_plot import out_dir, plt, save_png, read_rows

# Only the gap law differs between the models (docs/model-notes.md, "Pairs").
MODELS = {"seed": ("seed's gap law", "C0"),
          "asymptotic": ("asymptotic gap law (exact as h → 0)", "C1")}
# The approach speed each row ran at (CSV column speed_set; a CSV without it has V_Io rows only).
SPEED_SETS = {"V_Io": ("at the printed approach speed V_Io", "^"),
              "St_B": ("at the speed giving the printed St_B", "o")}


def num(row, key):
    v = row.get(key, "")
    return float(v) if v not in ("", None) else None


def points(rows, st_key, e_key):
    """(St_B, e) of the rows that have both, by St_B."""
    return sorted((num(r, st_key), num(r, e_key)) for r in rows if num(r, st_key) is not None and num(r, e_key) is not None)


def draw_model(ax, mine, label, colour, st_key, st_red_key, coupled):
    """One model's rows: a marker per speed set (hollow: reduced-order beside coupled), a thin line per run between sets."""
    for run in sorted({r["run"] for r in mine}):
        pts = points([r for r in mine if r["run"] == run], st_key, "e")
        if len(pts) == 2:
            ax.plot(*zip(*pts), "-", color=colour, lw=0.6, alpha=0.5)
    for speed_set, (set_label, marker) in SPEED_SETS.items():
        rows = [r for r in mine if r.get("speed_set", "V_Io") == speed_set]
        pts = points(rows, st_key, "e")
        if pts:
            ax.semilogx(*zip(*pts), marker, color=colour, ms=6,
                        label="imcol " + ("coupled" if coupled else "reduced-order") + ", " + label + ", " + set_label)
        red = points(rows, st_red_key, "e_reduced_order") if coupled else []
        if red:
            ax.semilogx(*zip(*red), marker, color=colour, mfc="none", ms=7,
                        label="imcol reduced-order, " + label + ", " + set_label)


def main() -> int:
    folder = out_dir(__doc__)
    if folder is None:
        return 2
    rows = read_rows(folder / "validate_seed.csv")
    coupled = bool(rows) and "e_reduced_order" in rows[0]
    fig, axes = plt.subplots(1, 2, figsize=(11, 6.2), sharey=True)
    panels = ((axes[0], "St_B_table_6_1", "St_B_table_6_1_reduced_order", 1.0, r"St$_B$, seed Table 6.1 convention (half of eq. 6.2)"),
              (axes[1], "St_B_eq_6_2", "St_B_eq_6_2_reduced_order", 2.0, r"St$_B$, eq. (6.2): $m^* U_{rel}\,/\,(6\pi\mu a^{*2})$"))
    seed = {}
    for r in rows:
        seed[r["run"]] = (float(r["St_B_seed"]), float(r["e_seed"]))
    for ax, st_key, st_red_key, seed_factor, xlabel in panels:
        xs = [seed_factor * st for st, _ in seed.values()]
        ax.semilogx(xs, [e for _, e in seed.values()], "s", color="k", mfc="none", ms=8,
                    label="Li (2010) Table 6.1, its printed e and St_B" + (" (St_B doubled)" if seed_factor != 1 else ""))
        for run, (st, e) in sorted(seed.items(), key=lambda kv: kv[1][0]):
            ax.annotate("run " + run, (seed_factor * st, e), fontsize=7, xytext=(5, -11), textcoords="offset points")
        for name, (label, colour) in MODELS.items():
            draw_model(ax, [r for r in rows if r["model"] == name], label, colour, st_key, st_red_key, coupled)
        ax.set_xlabel(xlabel, fontsize=9)
        ax.set_ylim(-0.03, 1.0)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("e")
    # The legend below both panels (inside, it would hide the points at large St_B).
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, fontsize=7, loc="lower center", ncol=2, frameon=False)
    fig.suptitle("imcol validate seed%s: e against St$_B$ in both conventions" % (" --flow" if coupled else ""), fontsize=10)
    fig.tight_layout(rect=(0, 0.02 + 0.035 * ((len(labels) + 1) // 2), 1, 1))
    save_png(fig, folder / "validate_seed.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
