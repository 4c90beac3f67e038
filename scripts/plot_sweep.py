#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Plot e against St for `imcol sweep`: every named measure in plain words, the seed's Table 6.1 for a sphere pair,
e/e_dry against St_L beside Legendre et al. (2006) with the deviation for a wall.

Usage: /usr/bin/python3 scripts/plot_sweep.py DIR [--compare DIR2]... [--out PNG]
(reads DIR/sweep.csv and DIR/sweep.json, writes DIR/sweep.png; --compare draws another sweep dashed beside it;
points without e are red x marks on the bottom axis and gaps in the lines; DIR/dem.json's fits are drawn when present, with its `liggghts` block)
"""
import argparse
import json
import math
import sys
from pathlib import Path

from imcol_plot import (EFFECT_WORDS, deviation_text, has_e, plt, positions, read_rows, read_scene, save_png,
                        sweep_scene_text)

SEED_TABLE = Path(__file__).resolve().parent.parent / "data" / "reference" / "li_2010_table_6_1.csv"
# Legendre, Zenit, Daniel & Guiraud (2006), Chem. Eng. Sci. 61, 3543: e/e_dry = exp(-35/St_L),
# St_L = (rho_p + rho_f/2) U d / (9 mu), a correlation of sphere-wall experiments (incl. Joseph et al. 2001, Gondret et al. 2002).
LEGENDRE_ST_C = 35.0


# The named measures of e (sweep.csv columns): plain words ({window_ms}, {fit_distance}, {at_gap}: the scene's
# measure settings), marker, line style (a single sweep) and colour.
MEASURES = (("e_fit_distance", "e from lines fitted over {fit_distance:g} D before and after contact (Joseph et al. 2001)", "^", "-", "C0"),
            ("e_fit_time", "e from lines fitted over {window_ms:g} ms (Yang & Hunt 2006)", "s", "--", "C1"),
            ("e_instant", "e at the ends of contact (speeds at gap = δ_SS)", "x", ":", "C2"),
            ("e_at_gap", "e from the speeds at a set gap ({at_gap:g} D)", "v", "-.", "C3"),
            ("e_peak_rebound", "e from the largest speeds (Gondret et al. 2002)", "d", (0, (5, 1, 1, 1)), "C4"))
# The measure settings' defaults (core/scene.hpp: measure.window in s, fit_distance and at_gap in units of D).
MEASURE_DEFAULTS = {"window": 0.010, "fit_distance": 0.1, "at_gap": 0.1}
# imcol's e in plain words when it is none of the columns above.
E_IS_PLAIN = {"contact_ends": "e from the speeds at the ends of the model's contact zone"}
# The measure e_is names and the column holding the same values.
E_IS_COLUMN = {"joseph_2001": "e_fit_distance", "fit_distance": "e_fit_distance", "yang_hunt_2006": "e_fit_time",
               "fit_time": "e_fit_time", "instant": "e_instant", "at_gap": "e_at_gap", "gondret_2002": "e_peak_rebound",
               "peak_rebound": "e_peak_rebound"}
ST_LABELS = {"sphere-wall": r"St $= m\,U\,/\,(6\pi\mu a^2)$  (m, a: the sphere's mass and radius; U: impact speed)",
             "sphere-sphere": r"St$_B$ (Li 2010, Table 6.1) $= m^* U\,/\,(12\pi\mu a^{*2})$  (m*, a*: reduced mass and radius)"}


def sweep_label(meta) -> str:
    """'reduced-order model' or 'coupled to the flow solver'."""
    return "coupled to the flow solver" if "flow" in meta.get("effects", []) else "reduced-order model"


def mark_failed(ax, rows, xs, label_prefix: str = "") -> None:
    """Points without e (the run failed, or e was not measured): a red x on the bottom axis at their St, and a gap in
    the lines (drawn by the callers through NaN)."""
    fx = [x for r, x in zip(rows, xs) if not has_e(r) and math.isfinite(x)]
    if fx:
        ax.plot(fx, [0.0] * len(fx), "x", color="red", ms=9, mew=2, clip_on=False, zorder=5,
                transform=ax.get_xaxis_transform(),
                label="%sfailed (no e): %d point%s, a gap in the lines" % (label_prefix, len(fx), "s" if len(fx) > 1 else ""))


def measure_settings(meta) -> dict:
    """The measure settings a sweep ran with: the sweep's --set overrides, else the scene file's [measure], else the
    defaults; {window_ms, fit_distance, at_gap}."""
    scene = (read_scene(meta.get("scene_file")) or {}).get("measure", {})
    over = meta.get("overrides") or {}
    got = {k: float(over.get("measure." + k, scene.get(k, v))) for k, v in MEASURE_DEFAULTS.items()}
    return {"window_ms": 1e3 * got["window"], "fit_distance": got["fit_distance"], "at_gap": got["at_gap"]}


def measure_label(key: str, meta) -> str:
    """A sweep.csv column of e in plain words, with the values of its settings."""
    return next(label for k, label, *_ in MEASURES if k == key).format(**measure_settings(meta))


def e_is_text(meta) -> str:
    """imcol's e of a sweep in plain words."""
    e_is = str(meta.get("e_is") or "").split(" ")[0]
    key = E_IS_COLUMN.get(e_is)
    return measure_label(key, meta) if key else E_IS_PLAIN.get(e_is, "e")


def measure_groups(rows, meta) -> list:
    """The measures to draw as [(columns, label, marker, line style, colour)]: measures equal at every point (to 1e-9)
    are one entry whose label says so; the one e_is names is marked as imcol's e."""
    chosen = E_IS_COLUMN.get(str(meta.get("e_is") or "").split(" ")[0])
    values = {k: [float(r[k]) if has_e(r) and r.get(k) else None for r in rows] for k, *_ in MEASURES}
    groups = []
    for key, _, mk, ls, colour in MEASURES:
        label = measure_label(key, meta)
        if not any(v is not None for v in values[key]):
            continue
        same = next((g for g in groups if all((a is None) == (b is None) and (a is None or abs(a - b) < 1e-9)
                                              for a, b in zip(values[g[0][0]], values[key]))), None)
        if same:
            same[0].append(key)
            same[1].append(label)
        else:
            groups.append(([key], [label], mk, ls, colour))
    out = [] if chosen else [(["e"], "imcol's e: " + e_is_text(meta), "o", "-", "k")]
    for keys, labels, mk, ls, colour in groups:
        text = labels[0] if len(labels) == 1 else " and ".join(labels) + " (identical here: one curve)"
        if chosen in keys:
            text = "imcol's e: " + text
        out.append((keys, text, mk, ls, colour))
    return out


def plot_sweep(ax, folder: Path, meta, look: str) -> dict:
    """Every named measure of one sweep, a colour and marker per measure; look: 'single' (a line style per measure),
    'solid' (filled markers) or 'dashed' (hollow markers): the sweeps of a comparison. Coinciding measures are one
    curve, failed points marked gaps. Returns {label: handle} of the measures drawn."""
    rows = read_rows(folder / "sweep.csv")
    if not rows:
        return {}
    xs = positions(rows, meta, "St")
    drawn = {}
    for keys, label, mk, ls, colour in measure_groups(rows, meta):
        key = keys[0]
        pts = sorted((x, float(r[key]) if has_e(r) and r.get(key) else float("nan")) for r, x in zip(rows, xs) if math.isfinite(x))
        main = label.startswith("imcol's e")
        line, = ax.semilogx(*zip(*pts), marker=mk, ls={"single": ls, "solid": "-", "dashed": "--"}[look], color=colour,
                            ms=6 if main else 4.5, lw=2.0 if main else 1.0, mfc="none" if look == "dashed" else None,
                            zorder=4 if main else 3)
        drawn[label] = line
    mark_failed(ax, rows, xs, "" if look != "dashed" else sweep_label(meta) + ": ")
    return drawn


def measure_legend_handles(drawn: dict, look: str) -> dict:
    """{label: handle} for the measures' legend: a comparison's show colour and marker on a plain solid line."""
    if look == "single":
        return drawn
    return {label: plt.Line2D([], [], color=h.get_color(), marker=h.get_marker(), lw=h.get_linewidth(), ms=h.get_markersize())
            for label, h in drawn.items()}


def style_legend(ax, metas) -> None:
    """A comparison's second legend (lower right, where e against St is empty): which sweep is solid and filled,
    which dashed and hollow."""
    handles = [plt.Line2D([], [], color="0.3", marker="o", ls=ls, mfc=mfc, label=sweep_label(m) + ": " + what)
               for m, ls, mfc, what in zip(metas, ("-", "--"), (None, "none"), ("solid, filled", "dashed, hollow"))]
    ax.add_artist(ax.legend(handles=handles, loc="lower right", fontsize=8, framealpha=0.9))


def residuals_text(f) -> str:
    return "residual rms %.3f, max %.3f" % (f["rms_residual"], f.get("max_residual", float("nan")))


def plot_fits(ax, folder: Path, meta) -> None:
    """With --export dem: the best fit of e(St) and the exponential one (dem.json) over the St range they hold, with
    their residuals; dem.json's `liggghts` block when present."""
    path = folder / "dem.json"
    if not path.exists():
        return
    dem = json.loads(path.read_text())
    pair = dem.get("configuration") == "sphere-sphere"
    chosen = []
    for which in (dem.get("best"), dem.get("exp")):  # the best fit, and the exponential one if it is another
        chosen += [f for f in dem["fits"] if which and (f["form"], f["e_dry_is"]) == (which["form"], which["e_dry_is"]) and f not in chosen]
    for f, (ls, colour) in zip(chosen, ((":", "k"), ((0, (6, 2)), "0.4"))):
        lo, hi = f["valid_St"]
        st = [lo * (hi / lo) ** (i / 199) for i in range(200)]
        g = (lambda x: math.exp(-f["St_c"] / x)) if f["form"] == "exp" else (lambda x: max(0.0, 1 - f["St_c"] / x))
        form = r"$e_{dry}\,\exp(-St_c/St)$" if f["form"] == "exp" else r"$e_{dry}\,(1 - St_c/St)$"
        # a pair's bottom axis is the summary's St, half the DEM St of the fit
        ax.semilogx([x / 2 if pair else x for x in st], [f["e_dry"] * g(x) for x in st], ls=ls, color=colour, lw=1.8,
                    label="DEM formula fit (dem.json) %s: St$_c$ = %.3g%s, e$_{dry}$ = %.3f%s; %s" % (
                        form, f["St_c"], " (DEM St = 2 St$_B$)" if pair else "", f["e_dry"],
                        "" if f["e_dry_is"] == "fitted" else " fixed", residuals_text(f)))
    plot_liggghts(ax, dem.get("liggghts"), pair)


def find_key(block: dict, *words):
    """The value of the first key of `block` whose lower-case name contains every word, or None."""
    for k, v in block.items():
        if all(w in k.lower() for w in words):
            return v
    return None


def plot_liggghts(ax, block, pair: bool) -> None:
    """dem.json's `liggghts` block (optional): its parameters and replay residuals as a legend entry, and its replayed
    points (a list of objects with St and e) when it has them."""
    if not isinstance(block, dict):
        return
    stc, emax = find_key(block, "criticalstokes"), find_key(block, "maximumrestitution")
    rms, worst = find_key(block, "rms"), find_key(block, "max", "res")
    parts = ["LIGGGHTS hooke/viscous (dem.json liggghts)"]
    if isinstance(stc, (int, float)) and isinstance(emax, (int, float)):
        parts.append("CriticalStokes = %.3g, MaximumRestitution = %.3f" % (stc, emax))
    if isinstance(rms, (int, float)):
        parts.append("replay residual rms %.3f" % rms + (", max %.3f" % worst if isinstance(worst, (int, float)) else ""))
    pts = next((v for v in block.values() if isinstance(v, list) and v and isinstance(v[0], dict)
                and find_key(v[0], "st") is not None and find_key(v[0], "e") is not None), None)
    xs = [find_key(p, "st") for p in pts] if pts else []
    ys = [next((p[k] for k in p if "replay" in k.lower() or k.lower() == "e"), None) for p in pts] if pts else []
    xy = [(x / 2 if pair else x, y) for x, y in zip(xs, ys) if isinstance(x, (int, float)) and isinstance(y, (int, float))]
    if xy:
        ax.semilogx(*zip(*sorted(xy)), "*", color="m", ms=8, ls="none", label=": ".join([parts[0], "; ".join(parts[1:])]))
    else:
        ax.plot([], [], " ", label=": ".join([parts[0], "; ".join(parts[1:])]))


def legendre_points(folder: Path, meta):
    """(rows, St_L of each row, sorted [(St_L, e / e_dry)] with NaN where e is missing), or None without e_dry or St_L."""
    e_dry = meta.get("e_dry")
    rows = read_rows(folder / "sweep.csv")
    if not e_dry or not any(has_e(r) and r.get("St_L") for r in rows):
        return None
    xs = positions(rows, meta, "St_L")
    return rows, xs, sorted((x, float(r["e"]) / e_dry if has_e(r) else float("nan")) for r, x in zip(rows, xs) if math.isfinite(x))


def plot_legendre(ax, folder: Path, meta, others=()) -> bool:
    """Sphere-wall sweeps: e/e_dry of imcol's e against St_L (compared sweeps dashed and hollow), with Legendre et
    al. (2006)'s correlation and the first sweep's deviation from it at the ends of the swept range."""
    sweeps = [(folder, meta, "-", None)] + [(d, m, "--", "none") for d, m in others]
    drawn = []
    for d, m, ls, mfc in sweeps:
        got = legendre_points(d, m)
        if got is None:
            continue
        rows, xs, pts = got
        who = sweep_label(m) if others else e_is_text(m)
        ax.semilogx(*zip(*pts), marker="o", ls=ls, mfc=mfc, color="C0", ms=5, lw=1.8 if ls == "-" else 1.2,
                    label="imcol: e / e$_{dry}$, " + who)
        mark_failed(ax, rows, xs)
        drawn.append(pts)
    if not drawn:
        return False
    finite = [x for pts in drawn for x, y in pts if math.isfinite(y)]
    lo, hi = min(finite), max(finite)
    xs_c = [lo * (hi / lo) ** (i / 199) for i in range(200)] if hi > lo else [lo]
    ax.semilogx(xs_c, [math.exp(-LEGENDRE_ST_C / x) for x in xs_c], "k:", lw=1.6,
                label=r"Legendre et al. (2006): $\exp(-35/St_L)$, fitted to experiments")
    pts = drawn[0]
    text = deviation_text("Legendre (2006)", [x for x, _ in pts], [y for _, y in pts],
                          [math.exp(-LEGENDRE_ST_C / x) for x, _ in pts], "St$_L$")
    if text:
        text = text.replace("imcol − ", sweep_label(meta) + " − ", 1) if others else text
        ax.text(0.03, 0.97, text.replace(": ", ":\n", 1), transform=ax.transAxes, va="top", fontsize=9,
                bbox=dict(facecolor="white", edgecolor="0.6", alpha=0.9))
    ax.set_xlabel(r"St$_L = (\rho_p + \rho_f/2)\,U d\,/\,(9\mu)$")
    ax.set_ylabel(r"e / e$_{dry}$")
    ax.set_ylim(-0.02, 1.05)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.1), frameon=False)  # below, as the left panel's
    return True


def draw_seed_table(ax) -> None:
    """Li (2010) Table 6.1 (simulated e of six runs) with the run numbers, alternately above and below."""
    seed = read_rows(SEED_TABLE)
    ax.semilogx([float(r["St_B"]) for r in seed], [float(r["e"]) for r in seed], "s", color="k", mfc="none", ms=8,
                label="Li (2010) Table 6.1, simulated (run numbers)")
    for i, r in enumerate(sorted(seed, key=lambda r: float(r["St_B"]))):
        ax.annotate(f"run {r['run']}", (float(r["St_B"]), float(r["e"])), fontsize=7,
                    xytext=(4, 8 if i % 2 else -12), textcoords="offset points")


def sweep_title(meta, others) -> str:
    """The scene, its bodies and liquid (from the scene file), what is swept over which range, and the failures."""
    unit = {"velocity": "m/s", "viscosity": "Pa s", "diameter": "m", "density": "kg/m³"}.get(meta["vary"], "")
    n_fail = len(meta["failures"]) + sum(len(m["failures"]) for _, m in others)
    what = "%d points" % meta["points"] + ("" if not others else " in each of %d sweeps" % (1 + len(others)))
    head = sweep_scene_text(meta)
    if meta.get("overrides"):
        head += " (scene changed: " + ", ".join(f"{k} = {v}" for k, v in meta["overrides"].items()) + ")"
    effects = meta.get("effects", [])
    added = sorted({e for _, m in others for e in m.get("effects", []) if e not in effects})
    return "%s\ne against St, %s from %g to %g %s, %s%s; effects: %s%s" % (
        head, meta["vary"], meta["from"], meta["to"], unit, what, ", %d failed" % n_fail if n_fail else "",
        ", ".join(EFFECT_WORDS.get(e, e) for e in effects),
        "; the dashed sweep adds " + ", ".join(EFFECT_WORDS.get(e, e) for e in added) if added else "")


def draw_sweeps(ax, out: Path, meta, others) -> None:
    """e against St: the sweep (and the compared ones, dashed and hollow, with a legend of their own), the DEM fits,
    the seed's table for a pair; the measures' legend below the axes."""
    look = "single" if not others else "solid"
    handles = measure_legend_handles(plot_sweep(ax, out, meta, look), look)
    for d, m in others:
        for label, h in measure_legend_handles(plot_sweep(ax, d, m, "dashed"), "dashed").items():
            handles.setdefault(label, h)
    if others:
        style_legend(ax, [meta] + [m for _, m in others])
    plot_fits(ax, out, meta)
    if meta["configuration"] == "sphere-sphere" and SEED_TABLE.exists():
        draw_seed_table(ax)
    for h, label in zip(*ax.get_legend_handles_labels()):
        handles.setdefault(label, h)
    ax.set_xlabel(ST_LABELS.get(meta["configuration"], "St (%s)" % meta.get("St_convention")), fontsize=9)
    if meta["configuration"] == "sphere-sphere":
        top = ax.secondary_xaxis("top", functions=(lambda x: 2 * x, lambda x: x / 2))
        top.set_xlabel(r"St$_B$, eq. (6.2): $m^* U / (6\pi\mu a^{*2})$ = 2 St$_B$ (Table 6.1)", fontsize=8)
    ax.set_ylabel("coefficient of restitution e")
    ax.set_ylim(-0.02, 1.02)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(list(handles.values()), list(handles), fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=1,
              frameon=False)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.strip().splitlines()[0])
    ap.add_argument("dir", type=Path, help="a sweep's output folder (sweep.csv, sweep.json)")
    ap.add_argument("--compare", type=Path, action="append", default=[],
                    help="another sweep's folder, drawn dashed and hollow in the same axes (e.g. coupled beside reduced-order)")
    ap.add_argument("--out", type=Path, help="the PNG to write (default DIR/sweep.png)")
    args = ap.parse_args()
    out = args.dir
    meta = json.loads((out / "sweep.json").read_text())
    # sphere-wall: a second panel, e/e_dry against St_L beside Legendre et al.'s correlation of experiments;
    # the legend below the axes (it would cover the rise of e at St 10-30 or the high-St plateau)
    wall = meta["configuration"] == "sphere-wall" and meta.get("e_dry")
    fig, axes = plt.subplots(1, 2 if wall else 1, figsize=(15, 8.25) if wall else (9.5, 8.25), squeeze=False)
    ax, ax_l = axes[0][0], (axes[0][1] if wall else None)
    others = [(d, json.loads((d / "sweep.json").read_text())) for d in args.compare]
    draw_sweeps(ax, out, meta, others)
    fig.suptitle(sweep_title(meta, others), fontsize=10)
    if wall and not plot_legendre(ax_l, out, meta, others):
        ax_l.set_axis_off()
    elif wall:
        ax_l.set_title("imcol against a correlation of experiments", fontsize=10)
    fig.tight_layout()
    save_png(fig, args.out or out / "sweep.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
