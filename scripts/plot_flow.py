#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Plot an `imcol flow` run: vorticity and streamlines of each snapshot (every grid level composed, one colour scale
per quantity for the run: scripts/flow_field.py), and the force history.

Usage: /usr/bin/python3 scripts/plot_flow.py DIR
Reads DIR/snapshot_NN.csv, DIR/forces.csv and DIR/summary.json (and the scene file it names, for ρ and the speed
U); writes DIR/snapshot_NN.png and DIR/forces.png, DIR/snapshot_NN_pressure.png when the snapshots have a pressure
column `p`, and for a sphere approaching a wall also DIR/forces_vs_gap.png and DIR/forces_vs_gap.csv (f_SIM against
Brenner's f_THR, like the seed's Fig. 6.4 for pairs). A scene with D = 1 and ρ = 1 is dimensionless: its pictures
are in units of D, U and ρ; any other scene is in SI (lengths in mm below a 5 cm sphere).
Needs Debian's python3-matplotlib and numpy (importable from /usr/bin/python3 only).
"""
import json
import math
import sys
from pathlib import Path

import numpy as np

from flow_field import (Units, outside_fluid, plot_snapshot, read_snapshot, run_limits, si_units,  # noqa: F401 (re-exported)
                        snapshot_limits, snapshot_time, streamline_levels, streamlines, thin_ticks)
from imcol_plot import out_dir, plt, read_rows, save_png, write_text


def scaled_units(D: float, U: float, rho: float) -> "Units":
    """A dimensionless scene: lengths in D, times in D/U, ω in U/D, forces in ρU²D², pressure in ρU²."""
    return Units(D, "/ D", D / U, "U / D", U / D, "ω D / U", rho * U * U * D * D, ", F / (ρ U² D²)", rho * U * U,
                 "(p − p∞) / (ρ U²)")


def scene_units(summary) -> "Units":
    """The units of an `imcol flow` run's pictures: dimensionless (D, U, ρ) when the scene has D = 1 and ρ = 1, else
    SI. ρ and U come from the scene file summary.json names (U = |stream − sphere 1's velocity|, or its oscillation
    speed 2πfA if larger, as the run defines it); without that file, D = 1 alone decides, with U = ρ = 1."""
    D = summary["grid"]["h"] * summary["grid"]["cells_per_diameter"]
    rho, U = None, None
    try:
        import tomllib

        with open(summary["scene"], "rb") as f:
            scene = tomllib.load(f)
        rho = float(scene["fluid"]["density"])
        s = scene["sphere"][0]
        U = max(abs(float(scene.get("stream", {}).get("velocity", 0.0)) - float(s.get("velocity", 0.0))),
                2 * math.pi * float(s.get("frequency", 0.0)) * abs(float(s.get("amplitude", 0.0))))
    except (ImportError, OSError, KeyError, IndexError, TypeError, ValueError):
        pass
    if abs(D - 1) < 1e-9 and (rho is None or abs(rho - 1) < 1e-9):
        return scaled_units(1.0, U if U else 1.0, 1.0)
    return si_units(D)


def plot_wall_gap(out: Path, rows, summary, units) -> None:
    """f_SIM against f_THR (Brenner) and the force on the wall, against the wall gap (gap <= 2 D)."""
    rows = [r for r in rows if 0 < float(r["wall_gap_D"]) <= 2.0]
    if not rows:
        return
    keys = ("wall_gap_D", "F1", "F_THR_wall", "F_wall")
    write_text(out / "forces_vs_gap.csv", "\n".join([",".join(keys)] + [",".join(r[k] for k in keys) for r in rows]) + "\n")
    gap = np.array([float(r["wall_gap_D"]) for r in rows])
    fs, ft, fw = (np.array([float(r[k]) for r in rows]) / units.force for k in ("F1", "F_THR_wall", "F_wall"))
    h = 1.0 / summary["grid"]["cells_per_diameter"]  # cell / D
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    ax = axes[0]
    ax.plot(gap, fs, label="f_SIM (flow kernel)")
    ax.plot(gap, ft, "--", label="f_THR: Brenner λ(h/a) 6πμaU (quasi-steady Stokes)")
    ax.plot(gap, -fw, ":", label="−(force on the wall)")
    ax.axvline(3 * h, color="grey", lw=0.8, ls=":", label="3 cells (below: not resolved)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.invert_xaxis()
    ax.set_xlabel("gap / D")
    ax.set_ylabel(units.force_label)
    ax.set_title("(a) hydrodynamic force on the sphere approaching the wall")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    ax = axes[1]
    ax.plot(gap, 100 * (fs / ft - 1))
    ax.axvline(3 * h, color="grey", lw=0.8, ls=":")
    ax.set_xscale("log")
    ax.invert_xaxis()
    ax.set_xlabel("gap / D")
    ax.set_ylabel("f_SIM / f_THR − 1 [%]")
    ax.set_title(f"(b) difference ({summary['grid']['cells_per_diameter']} cells/D)")
    ax.grid(alpha=0.3, which="both")
    fig.suptitle(f"{summary['name']}: Re = {summary['Re']:.3g}")
    fig.tight_layout()
    save_png(fig, out / "forces_vs_gap.png", dpi=130)


def plot_snapshots(out: Path, rows, summary, units) -> None:
    """snapshot_NN.png (and _pressure.png) of every snapshot_NN.csv, one colour scale per quantity for the run."""
    nb = sum(1 for k in rows[0] if k.startswith("F") and k[1:].isdigit())
    d = summary["grid"]["h"] * summary["grid"]["cells_per_diameter"]

    def spheres_at(ts):  # the spheres at the forces.csv row nearest to the snapshot's time (moving spheres)
        row = rows[-1] if ts is None else min(rows, key=lambda r: abs(float(r["t"]) - ts))
        return [(float(row[f"z{b + 1}"]), d) for b in range(nb)]

    wall = summary.get("wall", {}).get("position")
    snaps = sorted(out.glob("snapshot_*.csv"))
    limits = run_limits([snapshot_limits(s, spheres_at, wall, units) for s in snaps])
    for snap in snaps:
        with open(snap) as f:
            t = snapshot_time(f.readline())
        title = f"{summary['name']}: " + (units.time_text(t) if t is not None else snap.stem) + f", Re = {summary['Re']:.3g}"
        plot_snapshot(snap, spheres_at, wall, title, units=units, limits=limits)


def draw_references(ax, t, column, rows, summary, units) -> None:
    """One sphere: the reference curves that apply (the summary says so) and lie on the axes (set from F1 here)."""
    f1 = column("F1") / units.force
    lo, hi = np.percentile(f1, [2, 98])
    pad = 0.3 * (hi - lo) + 1e-12 * max(abs(lo), abs(hi), 1e-300)
    ylo, yhi = lo - pad, hi + pad
    ax.set_ylim(ylo, yhi)
    sign = np.sign(np.mean(f1))

    def on_axes(y):
        y = np.atleast_1d(y)
        return np.any((y > ylo) & (y < yhi))

    if "impulsive_start" in summary:
        fsb = sign * column("F_stokes_basset") / units.force
        if on_axes(fsb):
            ax.plot(t, fsb, "--", label="Stokes + Basset, impulsive start")
    if "F_stokes_oscillating" in rows[0]:
        fo = column("F_stokes_oscillating") / units.force
        if on_axes(fo):
            ax.plot(t, fo, "--", label="unsteady Stokes, oscillating sphere")
    if summary.get("drag_coefficient_standard") is not None:
        q = abs(f1[-1] / float(rows[-1]["C_D"]))
        y = sign * summary["drag_coefficient_standard"] * q
        if on_axes(y):
            ax.axhline(y, color="k", ls=":", label="standard drag curve (steady)")


def plot_forces(out: Path, rows, summary, units) -> None:
    """forces.png: the force on each sphere against time, f_THR beside it and the references that apply."""
    nb = sum(1 for k in rows[0] if k.startswith("F") and k[1:].isdigit())

    def column(key):
        return np.array([float(r[key]) for r in rows])

    t = column("t") / units.time
    fig, ax = plt.subplots(figsize=(9, 5))
    for b in range(nb):
        ax.plot(t, column(f"F{b + 1}") / units.force, label=f"F{b + 1} (simulation)")
    if "F_THR1" in rows[0]:
        for b in range(nb):
            ax.plot(t, column(f"F_THR{b + 1}") / units.force, "--", label=f"F{b + 1}: f_THR (reduced-order, no history)")
    if nb == 1:
        draw_references(ax, t, column, rows, summary, units)
    ax.set_xlabel(units.t)
    ax.set_ylabel(units.force_label)
    ax.set_title(f"{summary['name']}: Re = {summary['Re']:.3g}")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    save_png(fig, out / "forces.png", dpi=130)


def main() -> int:
    out = out_dir(__doc__)
    if out is None:
        return 2
    rows = read_rows(out / "forces.csv")
    summary = json.loads((out / "summary.json").read_text())
    units = scene_units(summary)
    plot_snapshots(out, rows, summary, units)
    plot_forces(out, rows, summary, units)
    if "wall_gap_D" in rows[0]:
        plot_wall_gap(out, rows, summary, units)
    return 0


if __name__ == "__main__":
    sys.exit(main())
