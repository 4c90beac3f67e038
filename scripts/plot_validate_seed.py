#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Plot `imcol validate seed`: e against St_B in both conventions, the seed's Table 6.1 beside imcol's models.

Usage: /usr/bin/python3 scripts/plot_validate_seed.py DIR
(reads DIR/validate_seed.csv, writes DIR/validate_seed.png)
Left: St_B as the seed's Table 6.1 gives it, half of eq. (6.2); right: St_B by eq. (6.2), m* U_rel / (6 pi mu a*^2),
where the seed's points stand at twice their printed St_B (every Table 6.1 pair has equal radii).
"""
import sys

from imcol_plot import out_dir, plt, save_png, read_rows

# Only the gap law differs between the models (docs/model-notes.md, "Pairs").
MODELS = {"seed": ("seed's gap law (lubrication \"seed\")", "C0", "o"),
          "asymptotic": ("asymptotic gap law, exact as h -> 0 (lubrication \"asymptotic\")", "C1", "^")}


def num(row, key):
    v = row.get(key, "")
    return float(v) if v not in ("", None) else None


def main() -> int:
    folder = out_dir(__doc__)
    if folder is None:
        return 2
    rows = read_rows(folder / "validate_seed.csv")
    coupled = bool(rows) and "e_reduced_order" in rows[0]
    fig, axes = plt.subplots(1, 2, figsize=(11, 5.2), sharey=True)
    panels = ((axes[0], "St_B_table_6_1", "St_B_table_6_1_reduced_order", 1.0, "St_B, seed Table 6.1 convention (half of eq. 6.2)"),
              (axes[1], "St_B_eq_6_2", "St_B_eq_6_2_reduced_order", 2.0, "St_B, eq. (6.2): m* U_rel / (6 pi mu a*^2)"))
    seed = {}
    for r in rows:
        seed[r["run"]] = (float(r["St_B_seed"]), float(r["e_seed"]))
    for ax, st_key, st_red_key, seed_factor, xlabel in panels:
        xs = [seed_factor * st for st, _ in seed.values()]
        ax.semilogx(xs, [e for _, e in seed.values()], "s", color="k", mfc="none", ms=8,
                    label="Li (2010) Table 6.1" + (" at 2 x its St_B" if seed_factor != 1 else ""))
        for run, (st, e) in sorted(seed.items(), key=lambda kv: kv[1][0]):
            ax.annotate("run " + run, (seed_factor * st, e), fontsize=7, xytext=(5, -11), textcoords="offset points")
        for name, (label, colour, marker) in MODELS.items():
            mine = [r for r in rows if r["model"] == name]
            pts = [(num(r, st_key), num(r, "e")) for r in mine if num(r, st_key) is not None and num(r, "e") is not None]
            if pts:
                ax.semilogx(*zip(*sorted(pts)), marker, color=colour, ms=6,
                            label=("coupled, " if coupled else "reduced-order, ") + label)
            if coupled:
                red = [(num(r, st_red_key), num(r, "e_reduced_order")) for r in mine
                       if num(r, st_red_key) is not None and num(r, "e_reduced_order") is not None]
                if red:
                    ax.semilogx(*zip(*sorted(red)), marker, color=colour, mfc="none", ms=7,
                                label="reduced-order, " + label)
        ax.set_xlabel(xlabel, fontsize=9)
        ax.set_ylim(-0.03, 1.0)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("e")
    axes[0].legend(fontsize=7, loc="upper left")
    fig.suptitle("imcol validate seed%s: e against St_B in both conventions" % (" --flow" if coupled else ""), fontsize=10)
    fig.tight_layout()
    save_png(fig, folder / "validate_seed.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
