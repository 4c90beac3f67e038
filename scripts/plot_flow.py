#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Plot an `imcol flow` run: vorticity and streamlines of each snapshot, and the force history.

Usage: /usr/bin/python3 scripts/plot_flow.py DIR
Reads DIR/snapshot_NN.csv and DIR/forces.csv; writes DIR/snapshot_NN.png and DIR/forces.png; for a sphere
approaching a wall also DIR/forces_vs_gap.png and DIR/forces_vs_gap.csv (f_SIM against Brenner's f_THR, like the
seed's Fig. 6.4 for pairs).
Needs Debian's python3-matplotlib and numpy (importable from /usr/bin/python3 only).
"""
import sys
from pathlib import Path

import numpy as np

from imcol_plot import out_dir, plt, save_png, write_text, read_rows


def plot_wall_gap(out: Path, rows, summary) -> None:
    """f_SIM against f_THR (Brenner) and the force on the wall, against the wall gap (gap <= 2 D)."""
    rows = [r for r in rows if 0 < float(r["wall_gap_D"]) <= 2.0]
    if not rows:
        return
    keys = ("wall_gap_D", "F1", "F_THR_wall", "F_wall")
    write_text(out / "forces_vs_gap.csv", "\n".join([",".join(keys)] + [",".join(r[k] for k in keys) for r in rows]) + "\n")
    gap = np.array([float(r["wall_gap_D"]) for r in rows])
    fs, ft, fw = (np.array([float(r[k]) for r in rows]) for k in ("F1", "F_THR_wall", "F_wall"))
    h = summary["grid"]["h"] / (summary["grid"]["h"] * summary["grid"]["cells_per_diameter"])  # cell / D
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
    ax.set_ylabel("force along +z [N]")
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


def read_level(path: Path, level: int):
    rows = np.loadtxt(path, delimiter=",", comments="#", skiprows=2)
    rows = rows[rows[:, 0] == level]
    r, z = np.unique(rows[:, 1]), np.unique(rows[:, 2])
    shape = (len(r), len(z))  # written with z fastest
    return r, z, rows[:, 3].reshape(shape), rows[:, 4].reshape(shape)


def plot_snapshot(path: Path, spheres, wall=None, title=None, sphere_label="sphere surface") -> None:
    """spheres: a list of (z, D), or a function of the snapshot's time t giving it (moving spheres);
    wall: the wall's z in the snapshot's coordinates (or None); title: replaces the CSV's own label.
    Levels 0 and 1 side by side, or one above the other when the level is a long flat strip (a sphere
    falling onto a wall from far away); the legend sits below the pictures, not over the flow."""
    with open(path) as f:
        header = f.readline().lstrip("# ").split(";")[0]
    if callable(spheres):
        try:
            spheres = spheres(float(header.split("=")[1].split()[0]))
        except (IndexError, ValueError):
            spheres = spheres(None)
    levels = []
    for level in (0, 1):
        try:
            r, z, psi, om = read_level(path, level)
        except (ValueError, IndexError):
            continue
        if len(r):
            levels.append((level, r, z, psi, om))
    if not levels:
        return
    _, r0, z0, _, _ = levels[0]
    aspect = (z0[-1] - z0[0]) / max(2 * r0[-1], 1e-300)  # length / height of the finest level
    stacked = aspect > 4
    if stacked:
        fig, axes = plt.subplots(len(levels), 1, figsize=(13, len(levels) * (10.5 / aspect + 1.1) + 1.3), squeeze=False)
    else:
        fig, axes = plt.subplots(1, len(levels), figsize=(6 * len(levels), 5.0 / aspect + 2.6), squeeze=False)
    for ax, (level, r, z, psi, om) in zip(axes.flat, levels):
        R = np.concatenate([-r[:0:-1], r])  # mirror about the axis
        P = np.concatenate([psi[:0:-1], psi])
        W = np.concatenate([-om[:0:-1], om])
        lim = np.percentile(np.abs(W), 99.5) or 1.0
        mesh = ax.pcolormesh(z, R, W, cmap="RdBu_r", vmin=-lim, vmax=lim, shading="auto")
        cb = fig.colorbar(mesh, ax=ax, shrink=0.9, pad=0.01 if stacked else 0.03)
        cb.set_label("ω", rotation=0, labelpad=8)
        # streamlines: levels even in sqrt|psi| (psi ~ r^2), with the recirculation (psi < 0) and psi = 0
        pos = np.linspace(0, np.sqrt(max(P.max(), 0)), 31)[1:-1] ** 2
        neg = -(np.linspace(0, np.sqrt(max(-P.min(), 0)), 7)[1:-1] ** 2)
        ax.contour(z, R, P, levels=np.unique(np.concatenate([neg, [0.0], pos])), colors="k", linewidths=0.5)
        for zc, d in spheres:
            ax.add_patch(plt.Circle((zc, 0), d / 2, fill=False, color="g", lw=1.2))
        if wall is not None:
            ax.axvline(wall, color="m", lw=1.5)
        ax.set_aspect("equal")
        ax.set_xlabel("z")
        ax.set_ylabel("r (mirrored)")
        ax.set_title(f"level {level}: vorticity ω (colour, scale clipped at 99.5 %), streamlines", fontsize=9)
    handles = [plt.Line2D([], [], color="k", lw=0.5, label="streamlines (ψ = const)"),
               plt.Line2D([], [], color="g", lw=1.2, label=sphere_label)]
    if wall is not None:
        handles.append(plt.Line2D([], [], color="m", lw=1.5, label="wall"))
    fig.legend(handles=handles, fontsize=8, loc="lower center", ncol=len(handles), frameon=False)
    fig.suptitle(title or header, fontsize=11)
    fig.tight_layout(rect=(0, 0.05 if stacked else 0.07, 1, 1))
    save_png(fig, path.with_suffix(".png"), dpi=130)


def main() -> int:
    out = out_dir(__doc__)
    if out is None:
        return 2
    rows = read_rows(out / "forces.csv")
    nb = sum(1 for k in rows[0] if k.startswith("F") and k[1:].isdigit())
    t = np.array([float(r["t"]) for r in rows])
    last = rows[-1]
    spheres = [(float(last[f"z{b + 1}"]), None) for b in range(nb)]
    import json

    summary = json.loads((out / "summary.json").read_text())
    d = summary["grid"]["h"] * summary["grid"]["cells_per_diameter"]
    spheres = [(zc, d) for zc, _ in spheres]
    def spheres_at(ts):  # the spheres at the forces.csv row nearest to the snapshot's time (moving spheres)
        if ts is None:
            return spheres
        row = min(rows, key=lambda r: abs(float(r["t"]) - ts))
        return [(float(row[f"z{b + 1}"]), d) for b in range(nb)]

    wall = summary.get("wall", {}).get("position")
    for snap in sorted(out.glob("snapshot_*.csv")):
        plot_snapshot(snap, spheres_at, wall)
    fig, ax = plt.subplots(figsize=(9, 5))
    for b in range(nb):
        ax.plot(t, [float(r[f"F{b + 1}"]) for r in rows], label=f"F{b + 1} (simulation)")
    if "F_THR1" in rows[0]:
        for b in range(nb):
            ax.plot(t, [float(r[f"F_THR{b + 1}"]) for r in rows], "--", label=f"F{b + 1}: f_THR (reduced-order, no history)")
    if nb == 1:
        # reference curves only where they apply (the summary says so) and where they lie on the axes
        f1 = np.array([float(r["F1"]) for r in rows])
        lo, hi = np.percentile(f1, [2, 98])
        pad = 0.3 * (hi - lo) + 1e-12
        ylo, yhi = lo - pad, hi + pad
        ax.set_ylim(ylo, yhi)
        sign = np.sign(np.mean(f1))

        def on_axes(y):
            y = np.atleast_1d(y)
            return np.any((y > ylo) & (y < yhi))

        if "impulsive_start" in summary:
            fsb = sign * np.array([float(r["F_stokes_basset"]) for r in rows])
            if on_axes(fsb):
                ax.plot(t, fsb, "--", label="Stokes + Basset, impulsive start")
        if "F_stokes_oscillating" in rows[0]:
            fo = np.array([float(r["F_stokes_oscillating"]) for r in rows])
            if on_axes(fo):
                ax.plot(t, fo, "--", label="unsteady Stokes, oscillating sphere")
        if summary.get("drag_coefficient_standard") is not None:
            q = abs(float(last["F1"]) / float(last["C_D"]))
            y = sign * summary["drag_coefficient_standard"] * q
            if on_axes(y):
                ax.axhline(y, color="k", ls=":", label="standard drag curve (steady)")
    ax.set_xlabel("t")
    ax.set_ylabel("force along +z [N]")
    ax.set_title(f"{summary['name']}: Re = {summary['Re']:.3g}")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    save_png(fig, out / "forces.png", dpi=130)
    if "wall_gap_D" in rows[0]:
        plot_wall_gap(out, rows, summary)
    return 0


if __name__ == "__main__":
    sys.exit(main())
