#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Plot an `imcol flow` run: vorticity and streamlines of each snapshot, and the force history.

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

import contourpy
import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.ticker import MaxNLocator

from imcol_plot import out_dir, plt, save_png, write_text, read_rows


class Units:
    """How the pictures scale and label values that the CSV files hold in the scene's units (SI for real scenes):
    a length x is drawn as x / length, a time as t / time, and so on."""

    def __init__(self, length, length_name, time, time_name, omega, omega_name, force, force_name, pressure, pressure_name):
        self.length, self.time, self.omega, self.force, self.pressure = length, time, omega, force, pressure
        self.z = f"z {length_name}"
        self.r = f"r {length_name}"
        self.t = f"t {time_name}"
        self.omega_name, self.pressure_name = omega_name, pressure_name
        self.force_label = "force along +z" + force_name

    def time_text(self, t: float) -> str:
        """'t = 0.0123 s' or 't U/D = 1.5'."""
        return self.t.replace(" [s]", "") + f" = {t / self.time:.4g}" + (" s" if self.t.endswith("[s]") else "")


def si_units(D: float) -> "Units":
    """SI, lengths in mm for a sphere smaller than 5 cm (tick labels of a 2 mm sphere in metres overlap)."""
    mm = D < 0.05
    return Units(1e-3 if mm else 1.0, "[mm]" if mm else "[m]", 1.0, "[s]", 1.0, "ω [1/s]", 1.0, " [N]", 1.0, "p − p∞ [Pa]")


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


def outside_fluid(r, z, spheres, wall=None, margin=0.0):
    """True at the points (r, z) (arrays of one shape, the CSV's units) inside a sphere, or beyond the wall: on its
    side without spheres; with a margin, also that close to them. spheres: a list of (z, D)."""
    r, z = np.broadcast_arrays(np.asarray(r, float), np.asarray(z, float))
    out = np.zeros(r.shape, bool)
    for zc, d in spheres:
        out |= (z - zc) ** 2 + r**2 < (0.5 * d + margin) ** 2
    if wall is not None:
        side = 1.0 if not spheres or spheres[0][0] >= wall else -1.0  # the fluid's side
        out |= (z - wall) * side < margin
    return out


def streamlines(z, R, P, levels, spheres, wall=None):
    """ψ contours of P (rows at R, the mirrored r; columns at z) at the given levels, with ψ masked inside the spheres
    and beyond the wall and every line cut where it enters one: a list of (level, vertices N×2 as (z, R))."""
    Z, RR = np.meshgrid(z, R)
    masked = np.ma.masked_array(P, outside_fluid(np.abs(RR), Z, spheres, wall))
    gen = contourpy.contour_generator(z, R, masked, line_type="Separate")
    lines = []
    for level in levels:
        for seg in gen.lines(level):
            keep = ~outside_fluid(np.abs(seg[:, 1]), seg[:, 0], spheres, wall)
            edges = np.flatnonzero(np.diff(np.concatenate(([0], keep.astype(np.int8), [0]))))
            lines += [(level, seg[a:b]) for a, b in zip(edges[0::2], edges[1::2]) if b - a >= 2]
    return lines


def read_snapshot(path: Path):
    """The comment line and the levels of a snapshot CSV (rows 'level,r,z,psi,omega,...', z fastest): the comment
    and a list of (level, r, z, {column: array (len(r), len(z))}), finest first."""
    with open(path) as f:
        comment = f.readline().lstrip("# ").strip()
        names = f.readline().strip().split(",")
    rows = np.loadtxt(path, delimiter=",", comments="#", skiprows=2, ndmin=2)
    levels = []
    for level in np.unique(rows[:, 0]).astype(int):
        sel = rows[rows[:, 0] == level]
        r, z = np.unique(sel[:, 1]), np.unique(sel[:, 2])
        shape = (len(r), len(z))
        fields = {n: sel[:, k].reshape(shape) for k, n in enumerate(names) if n not in ("level", "r", "z")}
        levels.append((int(level), r, z, fields))
    return comment, levels


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


def snapshot_time(comment: str):
    """The time in a snapshot's comment line ('LABEL, t = T s; ...' or 't = T s; ...'), or None."""
    try:
        return float(comment.split(";")[0].split("t =")[1].split()[0])
    except (IndexError, ValueError):
        return None


def streamline_levels(psi, n=29):
    """ψ values of the streamlines: even in sqrt|ψ| (ψ ~ r²), n on the side of ψ's larger extreme and 5 on the
    other side when its extreme is at least 1 % of that (below, the other side is the smeared sphere surface's
    noise), and ψ = 0."""
    hi, lo = max(float(np.max(psi)), 0.0), max(-float(np.min(psi)), 0.0)
    big = max(hi, lo)
    if big == 0:
        return np.array([0.0])

    def side(extreme):
        if extreme < 0.01 * big:
            return np.empty(0)
        return np.linspace(0, np.sqrt(extreme), n + 2 if extreme == big else 7)[1:-1] ** 2

    return np.unique(np.concatenate([-side(lo), [0.0], side(hi)]))


def thin_ticks(ax) -> None:
    """Ticks at 1, 2 or 5 × 10^k on both axes, as many as fit: fewer until the widest label, with a gap of one
    character, fits between two neighbours (the axes' size as laid out now)."""
    ax.apply_aspect()  # the box an equal-aspect axes is drawn in
    box = ax.get_window_extent()
    for axis, (lo, hi), size in ((ax.xaxis, ax.get_xlim(), box.width), (ax.yaxis, ax.get_ylim(), box.height)):
        for n in (9, 7, 6, 5, 4, 3, 2):
            locator = MaxNLocator(nbins=n, steps=[1, 2, 5, 10])
            ticks = [t for t in locator.tick_values(lo, hi) if min(lo, hi) <= t <= max(lo, hi)]
            labels = axis.get_major_formatter().format_ticks(ticks) if len(ticks) > 1 else [""]
            font = axis.get_ticklabels()[0].get_fontsize() if axis.get_ticklabels() else 10.0
            # the room a label needs along the axis: its width and a character (x), or 2.5 lines (y)
            extent = (0.62 * max(len(t) for t in labels) + 1) if axis is ax.xaxis else 2.5
            step = abs(ticks[1] - ticks[0]) / abs(hi - lo) * size if len(ticks) > 1 else size
            if step >= extent * font * ax.figure.dpi / 72:
                break
        axis.set_major_locator(locator)


def draw_level(fig, ax, z, r, fields, key, spheres, wall, units, stacked):
    """One level's picture: the field `key` in colour (ω, or p − p∞), streamlines, the spheres and the wall, mirrored
    about the axis. Returns whether any dashed (ψ < 0) streamline was drawn."""
    R = np.concatenate([-r[:0:-1], r])
    P = np.concatenate([fields["psi"][:0:-1], fields["psi"]])
    sign = -1.0 if key == "omega" else 1.0  # ω_θ changes sign with e_θ across the axis; p does not
    F = np.concatenate([sign * fields[key][:0:-1], fields[key]]) / (units.omega if key == "omega" else units.pressure)
    Z, RR = np.meshgrid(z, R)
    fluid = ~outside_fluid(np.abs(RR), Z, spheres, wall)
    # the colour scale: ω over the fluid (its largest values, at the surfaces, are the boundary layers); p more than
    # two cells from the bodies (in the kernel's smeared surface layer p is not resolved)
    scaled = fluid if key == "omega" else ~outside_fluid(np.abs(RR), Z, spheres, wall, 2 * (r[1] - r[0]))
    scaled = scaled if scaled.any() else fluid
    lim = (np.nanpercentile(np.abs(F[scaled]), 99.5) if scaled.any() else 0.0) or 1.0
    L = units.length
    ax.set_facecolor("0.88")  # the cells masked at a sphere's edge in the bodies' grey
    cmap = "RdBu_r" if key == "omega" else "PuOr_r"
    mesh = ax.pcolormesh(z / L, R / L, np.ma.masked_array(F, ~fluid | np.isnan(F)), cmap=cmap, vmin=-lim, vmax=lim,
                         shading="auto")
    cb = fig.colorbar(mesh, ax=ax, shrink=0.9, pad=0.01 if stacked else 0.03)
    cb.set_label(units.omega_name if key == "omega" else units.pressure_name)
    # fewer and lighter streamlines over the pressure, whose largest values lie where the streamlines crowd
    n, ink, width = (29, "k", 0.5) if key == "omega" else (15, "0.3", 0.4)
    lines = streamlines(z, R, P, streamline_levels(P[fluid] if fluid.any() else P.ravel(), n), spheres, wall)
    solid = [seg / L for level, seg in lines if level >= 0]
    dashed = [seg / L for level, seg in lines if level < 0]
    ax.add_collection(LineCollection(solid, colors=ink, linewidths=width))
    if dashed:
        ax.add_collection(LineCollection(dashed, colors=ink, linewidths=width + 0.1, linestyles=(0, (3, 2))))
    for zc, d in spheres:
        ax.add_patch(plt.Circle((zc / L, 0), 0.5 * d / L, facecolor="0.88", edgecolor="g", lw=1.2))
    if wall is not None:
        far = z[0] if not spheres or spheres[0][0] >= wall else z[-1]
        ax.axvspan(min(wall, far) / L, max(wall, far) / L, facecolor="0.88", edgecolor="0.55", hatch="///", lw=0)
        ax.axvline(wall / L, color="m", lw=1.5)
    ax.set_xlim(z[0] / L, z[-1] / L)
    ax.set_ylim(R[0] / L, R[-1] / L)
    ax.set_aspect("equal")
    ax.set_xlabel(units.z)
    ax.set_ylabel(units.r + " (mirrored)")
    return bool(dashed)


def plot_snapshot(path: Path, spheres, wall=None, title=None, sphere_label="sphere surface", units=None) -> None:
    """spheres: a list of (z, D), or a function of the snapshot's time t giving it (moving spheres);
    wall: the wall's z in the snapshot's coordinates (or None); title: replaces the CSV's own label; units: Units
    (default SI). Writes PATH.png (vorticity) and, when the CSV has a pressure column `p`, PATH_pressure.png.
    Levels 0 and 1 side by side, or one above the other when the level is a long flat strip (a sphere
    falling onto a wall from far away); the legend sits below the pictures, not over the flow. Streamlines stop
    at the spheres and the wall, and ω and p are not drawn inside them (not fluid)."""
    comment, levels = read_snapshot(path)
    if callable(spheres):
        spheres = spheres(snapshot_time(comment))
    levels = [lv for lv in levels if lv[0] in (0, 1) and len(lv[1])]
    if not levels:
        return
    if units is None:
        units = si_units(spheres[0][1] if spheres else 1.0)
    _, r0, z0, _ = levels[0]
    aspect = (z0[-1] - z0[0]) / max(2 * r0[-1], 1e-300)  # length / height of the finest level
    stacked = aspect > 4
    keys = ["omega"] + (["p"] if all("p" in f for *_, f in levels) else [])
    for key in keys:
        if stacked:
            fig, axes = plt.subplots(len(levels), 1, figsize=(13, len(levels) * (10.5 / aspect + 1.1) + 1.3), squeeze=False)
        else:
            fig, axes = plt.subplots(1, len(levels), figsize=(6 * len(levels), 5.0 / aspect + 2.6), squeeze=False)
        any_dashed = False
        what = "vorticity ω" if key == "omega" else "pressure p − p∞"
        for ax, (level, r, z, fields) in zip(axes.flat, levels):
            any_dashed |= draw_level(fig, ax, z, r, fields, key, spheres, wall, units, stacked)
            ax.set_title(f"level {level}: {what} (colour, clipped at 99.5 %), streamlines", fontsize=9 if stacked or aspect > 1.6 else 8)
        ink = "k" if key == "omega" else "0.3"  # as draw_level draws them
        handles = [plt.Line2D([], [], color=ink, lw=0.5, label="streamlines (ψ = const" + (" ≥ 0)" if any_dashed else ")"))]
        if any_dashed:
            handles.append(plt.Line2D([], [], color=ink, lw=0.6, ls=(0, (3, 2)), label="streamlines with ψ < 0 (circulating the other way)"))
        handles.append(plt.Line2D([], [], color="g", lw=1.2, label=sphere_label))
        if wall is not None:
            handles.append(plt.Line2D([], [], color="m", lw=1.5, label="wall (hatched: beyond it)"))
        fig.legend(handles=handles, fontsize=8, loc="lower center", ncol=len(handles), frameon=False)
        fig.suptitle(title or comment.split(";")[0], fontsize=11)
        fig.tight_layout(rect=(0, 0.05 if stacked else 0.07, 1, 1))
        for ax in axes.flat:
            thin_ticks(ax)
        save_png(fig, path.with_suffix(".png") if key == "omega" else path.with_name(path.stem + "_pressure.png"), dpi=130)


# One function (66 lines): the figure's panels share one layout and its axes; split, each would pass them all.
def main() -> int:
    out = out_dir(__doc__)
    if out is None:
        return 2
    rows = read_rows(out / "forces.csv")
    nb = sum(1 for k in rows[0] if k.startswith("F") and k[1:].isdigit())
    summary = json.loads((out / "summary.json").read_text())
    units = scene_units(summary)
    d = summary["grid"]["h"] * summary["grid"]["cells_per_diameter"]

    def spheres_at(ts):  # the spheres at the forces.csv row nearest to the snapshot's time (moving spheres)
        row = rows[-1] if ts is None else min(rows, key=lambda r: abs(float(r["t"]) - ts))
        return [(float(row[f"z{b + 1}"]), d) for b in range(nb)]

    wall = summary.get("wall", {}).get("position")
    for snap in sorted(out.glob("snapshot_*.csv")):
        with open(snap) as f:
            t = snapshot_time(f.readline())
        title = f"{summary['name']}: " + (units.time_text(t) if t is not None else snap.stem) + f", Re = {summary['Re']:.3g}"
        plot_snapshot(snap, spheres_at, wall, title, units=units)

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
        # reference curves only where they apply (the summary says so) and where they lie on the axes
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
    ax.set_xlabel(units.t)
    ax.set_ylabel(units.force_label)
    ax.set_title(f"{summary['name']}: Re = {summary['Re']:.3g}")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    save_png(fig, out / "forces.png", dpi=130)
    if "wall_gap_D" in rows[0]:
        plot_wall_gap(out, rows, summary, units)
    return 0


if __name__ == "__main__":
    sys.exit(main())
