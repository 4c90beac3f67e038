# SPDX-License-Identifier: BSD-3-Clause
"""A flow-field snapshot (CSV written by flow/snapshot.cpp) drawn as one field: the grid levels composed (the finest
wins where levels overlap), masked inside the spheres and beyond the wall by geometry on a fine interpolation,
thinned streamlines (ψ contours), and one colour scale per quantity shared by every panel and snapshot of a run.

Used by scripts/plot_flow.py (`imcol flow`) and scripts/plot_coupled_flow.py (coupled runs).
Needs Debian's python3-matplotlib, python3-contourpy and numpy.
"""
import re
from pathlib import Path

import contourpy
import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.colors import Normalize, SymLogNorm
from matplotlib.patches import Rectangle
from matplotlib.ticker import FuncFormatter, MaxNLocator

from imcol_plot import plt, save_png

# The share of |field| over the fluid below the colour scale's limit (the largest values are the boundary layers).
CLIP_PERCENTILE = 99.5
# p is neither drawn nor scaled this many finest cells from a sphere's surface (the kernel's smeared surface layer).
P_MARGIN_CELLS = 2.0


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


NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"


def parse_comment(comment: str) -> dict:
    """What a snapshot's comment line says (flow/snapshot.hpp): 'LABEL, t = T s; level 0 is the finest; ...;
    z_shift = S m; spheres (z, d) = z1 d1 ...; trajectory spheres (z, d) = z1 d1 ...; gap = G m = G/D D'.
    Returns `spheres` [(z, d)] where the flow kernel holds them, `true_spheres` [(z, d)] where the trajectory has them,
    `gap_m` and `gap_D` the true surface gap (with a wall or a pair), `z_shift_m`; parts absent from the line (older
    files have no trajectory part) or not read as numbers are absent."""
    out = {}
    for part in comment.split(";"):
        name, sep, value = part.partition("=")
        name = name.strip()
        try:
            nums = [float(x) for x in value.replace("m =", " ").replace(" m", " ").replace(" D", " ").split()]
        except ValueError:
            continue
        if not sep or not nums:
            continue
        if name in ("spheres (z, d)", "trajectory spheres (z, d)") and len(nums) % 2 == 0:
            out["spheres" if name.startswith("spheres") else "true_spheres"] = list(zip(nums[0::2], nums[1::2]))
        elif name == "gap" and re.fullmatch(rf"\s*{NUMBER} m = {NUMBER} D\s*", value):
            out["gap_m"], out["gap_D"] = nums
        elif name == "z_shift" and len(nums) == 1:
            out["z_shift_m"] = nums[0]
    return out


def bilinear(r, z, F, rq, zq):
    """F (len(r) × len(z), a regular grid) interpolated bilinearly at the points (rq, zq) (arrays of one shape)."""
    hr, hz = r[1] - r[0], z[1] - z[0]
    fi = np.clip((rq - r[0]) / hr, 0, len(r) - 1 - 1e-9)
    fj = np.clip((zq - z[0]) / hz, 0, len(z) - 1 - 1e-9)
    i, j = np.floor(fi).astype(int), np.floor(fj).astype(int)
    a, b = fi - i, fj - j
    return ((1 - a) * (1 - b) * F[i, j] + a * (1 - b) * F[i + 1, j] + (1 - a) * b * F[i, j + 1] + a * b * F[i + 1, j + 1])


def compose_levels(levels, key: str, rq, zq):
    """One field from every level at the points (rq, zq): each point takes the finest level whose rectangle holds it
    (levels: read_snapshot's, finest first). Returns (field, level index); NaN and -1 outside every level."""
    rq, zq = np.broadcast_arrays(np.asarray(rq, float), np.asarray(zq, float))
    F = np.full(rq.shape, np.nan)
    L = np.full(rq.shape, -1, int)
    for level, r, z, fields in levels:  # finest first: each point taken by the first level holding it
        tol = 1e-9 * (r[-1] - r[0] + z[-1] - z[0])
        free = (L < 0) & (rq >= r[0] - tol) & (rq <= r[-1] + tol) & (zq >= z[0] - tol) & (zq <= z[-1] + tol)
        if free.any():
            F[free] = bilinear(r, z, fields[key], rq[free], zq[free])
            L[free] = level
    return F, L


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
    masked = np.ma.masked_array(P, outside_fluid(np.abs(RR), Z, spheres, wall) | np.isnan(P))
    gen = contourpy.contour_generator(z, R, masked, line_type="Separate")
    lines = []
    for level in levels:
        for seg in gen.lines(level):
            keep = ~outside_fluid(np.abs(seg[:, 1]), seg[:, 0], spheres, wall)
            edges = np.flatnonzero(np.diff(np.concatenate(([0], keep.astype(np.int8), [0]))))
            lines += [(level, seg[a:b]) for a, b in zip(edges[0::2], edges[1::2]) if b - a >= 2]
    return lines


def streamline_levels(psi, n=29):
    """ψ values of the streamlines: even in sqrt|ψ| (ψ ~ r²), n on the side of ψ's larger extreme and 5 on the
    other side when its extreme is at least 1 % of that (below, the other side is the smeared sphere surface's
    noise), and ψ = 0."""
    psi = np.asarray(psi)[np.isfinite(psi)]
    hi, lo = (max(float(np.max(psi)), 0.0), max(-float(np.min(psi)), 0.0)) if psi.size else (0.0, 0.0)
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


def snapshot_time(comment: str):
    """The time in a snapshot's comment line ('LABEL, t = T s; ...' or 't = T s; ...'), or None."""
    try:
        return float(comment.split(";")[0].split("t =")[1].split()[0])
    except (IndexError, ValueError):
        return None


# The near panel's width over its height (r mirrored) at least: the window is widened along z to it.
NEAR_ASPECT = 1.4


def near_window(levels, spheres, wall):
    """(r_max, z_min, z_max) around the spheres: 1.5 D beyond them along z and 2 D out in r, a wall and 0.4 D beyond
    it, widened along z (away from a wall) to NEAR_ASPECT, within the coarsest level's rectangle."""
    _, r, z, _ = levels[-1]
    if not spheres:
        return r[-1], z[0], z[-1]
    D = max(d for _, d in spheres)
    lo, hi = min(zc - 0.5 * d for zc, d in spheres) - 1.5 * D, max(zc + 0.5 * d for zc, d in spheres) + 1.5 * D
    if wall is not None:
        lo, hi = (min(lo, wall - 0.4 * D), min(hi, wall + 0.4 * D)) if wall > spheres[0][0] else (max(lo, wall - 0.4 * D), max(hi, wall + 0.4 * D))
    r_max = min(2 * D, r[-1])
    grow = max(0.0, NEAR_ASPECT * 2 * r_max - (hi - lo))  # wider along z, away from a wall (both ways without one)
    if wall is None:
        lo, hi = lo - grow / 2, hi + grow / 2
    elif wall > spheres[0][0]:
        lo -= grow
    else:
        hi += grow
    return r_max, max(lo, z[0]), min(hi, z[-1])


def window_grid(levels, window):
    """The points (r ≥ 0, z) a window is drawn at: a quarter of the finest level's cell, or 800 points along z (300 in
    r) if coarser."""
    r_max, z0, z1 = window
    h0 = levels[0][1][1] - levels[0][1][0]
    h = max(0.25 * h0, (z1 - z0) / 800, r_max / 300)
    return np.linspace(0, r_max, int(round(r_max / h)) + 1), np.linspace(z0, z1, int(round((z1 - z0) / h)) + 1)


def window_field(levels, key, window, units):
    """(z, R, F, P): the composed field `key` (scaled by units, mirrored about the axis: ω_θ changes sign with e_θ
    across it, p does not) and ψ on a window's grid, R the mirrored r."""
    r, z = window_grid(levels, window)
    ZZ, RR = np.meshgrid(z, r)
    F = compose_levels(levels, key, RR, ZZ)[0] / (units.omega if key == "omega" else units.pressure)
    P = compose_levels(levels, "psi", RR, ZZ)[0]
    sign = -1.0 if key == "omega" else 1.0
    return z, np.concatenate([-r[:0:-1], r]), np.concatenate([sign * F[:0:-1], F]), np.concatenate([P[:0:-1], P])


def field_limit(levels, key, spheres, wall, units) -> float:
    """The CLIP_PERCENTILE % point of |field| over the fluid near the spheres (p: more than P_MARGIN_CELLS finest cells
    from the spheres, where the kernel's smeared surface leaves p unresolved); the caller takes the largest over a run."""
    z, R, F, _ = window_field(levels, key, near_window(levels, spheres, wall), units)
    Z, RR = np.meshgrid(z, R)
    h0 = levels[0][1][1] - levels[0][1][0]
    fluid = ~outside_fluid(np.abs(RR), Z, spheres, wall) & np.isfinite(F)
    if key == "p":
        fluid &= ~outside_fluid(np.abs(RR), Z, spheres, None, P_MARGIN_CELLS * h0)
    return float(np.percentile(np.abs(F[fluid]), CLIP_PERCENTILE)) if fluid.any() else 0.0


def pixel_size(ax) -> float:
    """One pixel of the laid-out axes along z, in its data units."""
    lo, hi = ax.get_xlim()
    return abs(hi - lo) / max(ax.get_window_extent().width, 1.0)


def draw_bodies(ax, spheres, true_spheres, wall, z_far, L, margin=0.0) -> bool:
    """The spheres (grey discs where the trajectory has them, else where the kernel holds them; a margin: a grey ring
    that wide under the streamlines), the kernel's outline dashed where it lies more than a pixel from the trajectory's,
    and the wall (hatched beyond it). Returns whether a kernel outline was drawn."""
    shown = true_spheres or spheres
    for zc, d in (spheres + (true_spheres or [])) if margin else []:
        ax.add_patch(plt.Circle((zc / L, 0), (0.5 * d + margin) / L, facecolor="0.85", edgecolor="none", zorder=1.5))
    for zc, d in shown:
        ax.add_patch(plt.Circle((zc / L, 0), 0.5 * d / L, facecolor="0.85", edgecolor="g", lw=1.2, zorder=4))
    px = pixel_size(ax)
    apart = [k for k, t in zip(spheres, true_spheres or []) if abs(k[0] - t[0]) / L > px or abs(k[1] - t[1]) / L > px]
    for zc, d in apart:
        ax.add_patch(plt.Circle((zc / L, 0), 0.5 * d / L, fill=False, edgecolor="k", lw=1.1, ls=(0, (4, 2)), zorder=5))
    if wall is not None:
        ax.axvspan(min(wall, z_far) / L, max(wall, z_far) / L, facecolor="0.85", edgecolor="0.55", hatch="///", lw=0, zorder=3)
        ax.axvline(wall / L, color="m", lw=1.5, zorder=4)
    return bool(apart)


# ω is drawn on a signed log scale, linear within ±limit / OMEGA_LINEAR (the boundary layers are 10-100 times the
# wake's vorticity); p on a linear one.
OMEGA_LINEAR = 30.0


def colour_norm(key: str, lim: float):
    if key == "omega":
        return SymLogNorm(linthresh=lim / OMEGA_LINEAR, linscale=1.0, vmin=-lim, vmax=lim, base=10)
    return Normalize(vmin=-lim, vmax=lim)


def label_colour_bar(cb, key: str, lim: float, text: str) -> None:
    """Signed tick labels (+100, 0, −100) at the limits, the linear range's ends and the powers of ten between."""
    if key == "omega":
        lin = lim / OMEGA_LINEAR
        mags = [lin] + [10.0**k for k in range(int(np.ceil(np.log10(lin * 1.5))), int(np.floor(np.log10(lim / 2))) + 1)] + [lim]
        cb.set_ticks(sorted([-m for m in mags] + [0.0] + mags))
        text += f"; signed log scale, linear within ±{lin:.3g}"
    cb.ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: "0" if v == 0 else f"{v:+.3g}".replace("-", "−")))
    cb.ax.tick_params(labelsize=8)
    cb.set_label(text + f"; limits ±{lim:.3g}", fontsize=8)


def draw_panel(ax, levels, key, window, lim, bodies, units, n_lines):
    """One window of the composed field `key` in colour within ±lim, masked outside the fluid, with n_lines
    streamlines on the larger side of ψ; bodies: (spheres, true spheres, wall). The axes must be laid out (their size
    decides whether the kernel's outline is a pixel from the trajectory's). Returns (mesh, any ψ < 0 line, kernel
    outline drawn)."""
    spheres, true_spheres, wall = bodies
    solids = spheres + (true_spheres or [])
    z, R, F, P = window_field(levels, key, window, units)
    Z, RR = np.meshgrid(z, R)
    fluid = ~outside_fluid(np.abs(RR), Z, solids, wall) & np.isfinite(F)
    margin = P_MARGIN_CELLS * (levels[0][1][1] - levels[0][1][0]) if key == "p" else 0.0
    if margin:  # not in the kernel's smeared surface layer, where p is not resolved
        fluid &= ~outside_fluid(np.abs(RR), Z, solids, None, margin)
    L = units.length
    cmap = "RdBu_r" if key == "omega" else "PuOr_r"
    hz, hr = z[1] - z[0], R[1] - R[0]  # a regular grid: an image, pixel centres at the points
    mesh = ax.imshow(np.ma.masked_array(F, ~fluid), cmap=cmap, norm=colour_norm(key, lim), origin="lower", aspect="auto",
                     interpolation="nearest", extent=((z[0] - hz / 2) / L, (z[-1] + hz / 2) / L, (R[0] - hr / 2) / L,
                                                      (R[-1] + hr / 2) / L))
    grown = [(zc, d + 2 * margin) for zc, d in solids]  # with p: streamlines stop at the layer p is not drawn in
    lines = streamlines(z, R, P, streamline_levels(P[fluid] if fluid.any() else P.ravel(), n_lines), grown, wall)
    solid = [seg / L for level, seg in lines if level >= 0]
    dashed = [seg / L for level, seg in lines if level < 0]
    ax.add_collection(LineCollection(solid, colors="k", linewidths=0.6, alpha=0.75, zorder=2))
    if dashed:
        ax.add_collection(LineCollection(dashed, colors="k", linewidths=0.7, alpha=0.75, linestyles=(0, (3, 2)), zorder=2))
    far = z[0] if wall is None or not spheres or spheres[0][0] >= wall else z[-1]
    ax.set_xlim(z[0] / L, z[-1] / L)
    ax.set_ylim(R[0] / L, R[-1] / L)
    ax.set_aspect("equal")
    outlined = draw_bodies(ax, spheres, true_spheres, wall, far, L, margin)
    ax.set_facecolor("0.85")
    ax.set_xlabel(units.z)
    ax.set_ylabel(units.r + " (mirrored)")
    return mesh, bool(dashed), outlined


def outline_levels(ax, levels, units) -> None:
    """Each level's rectangle (mirrored) as a thin dashed outline, labelled with its number where it is wider than a
    tenth of the whole domain."""
    L = units.length
    span = levels[-1][2][-1] - levels[-1][2][0]
    for level, r, z, _ in levels[:-1]:
        ax.add_patch(Rectangle((z[0] / L, -r[-1] / L), (z[-1] - z[0]) / L, 2 * r[-1] / L, fill=False, ec="0.25", lw=0.7,
                               ls="--", zorder=5))
        if z[-1] - z[0] > 0.1 * span:
            ax.annotate(f"level {level}", (z[-1] / L, r[-1] / L), fontsize=7, color="0.25", ha="right", va="bottom", zorder=6,
                        bbox=dict(fc="white", ec="none", alpha=0.75, pad=0.4))


QUANTITY = {"omega": ("vorticity ω", "omega_name"), "p": ("pressure p − p∞", "pressure_name")}


def snapshot_bodies(comment, spheres, wall):
    """(kernel spheres, true spheres or None, wall): `spheres` a list of (z, D), a function of the snapshot's time,
    or None for the comment line's; the comment's trajectory positions when it has them."""
    info = parse_comment(comment)
    if callable(spheres):
        spheres = spheres(snapshot_time(comment))
    if spheres is None:
        spheres = info.get("spheres", [])
    return spheres, info.get("true_spheres"), wall


def snapshot_limits(path: Path, spheres=None, wall=None, units=None) -> dict:
    """{quantity: limit} of one snapshot (field_limit per quantity in the file); a run's scale is the largest."""
    comment, levels = read_snapshot(path)
    kernel, true, wall = snapshot_bodies(comment, spheres, wall)
    units = units or si_units(kernel[0][1] if kernel else 1.0)
    return {k: field_limit(levels, k, kernel + (true or []), wall, units) for k in QUANTITY if k in levels[0][3]}


def run_limits(per_snapshot) -> dict:
    """One colour-scale limit per quantity for a run: the largest of its snapshots' (snapshot_limits)."""
    out = {}
    for lims in per_snapshot:
        for k, v in lims.items():
            out[k] = max(out.get(k, 0.0), v)
    return out


def legend_handles(any_dashed, sphere_label, wall, outlined, key):
    """The legend below a snapshot's panels."""
    handles = [plt.Line2D([], [], color="k", lw=0.6, label="streamlines (ψ = const" + (" ≥ 0)" if any_dashed else ")"))]
    if any_dashed:
        handles.append(plt.Line2D([], [], color="k", lw=0.7, ls=(0, (3, 2)), label="ψ < 0 (circulating the other way)"))
    handles.append(plt.Line2D([], [], color="g", lw=1.2, label=sphere_label + (" where the trajectory has it" if outlined else "")))
    if outlined:
        handles.append(plt.Line2D([], [], color="k", lw=1.1, ls=(0, (4, 2)), label="where the flow solver holds it"))
    if wall is not None:
        handles.append(plt.Line2D([], [], color="m", lw=1.5, label="wall (hatched: beyond it)"))
    handles.append(plt.Line2D([], [], color="0.25", lw=0.7, ls="--", label="grid level boundaries (level 0 finest)"))
    if key == "p":
        handles.append(plt.Rectangle((0, 0), 1, 1, fc="0.85", label=f"p not drawn within {P_MARGIN_CELLS:g} cells of a sphere "
                                                                    "(the kernel's smeared surface)"))
    return handles


# A snapshot's figure, in inches: both panels PANEL_WIDTH wide (a panel whose height would pass PANEL_HEIGHT_MAX is
# narrower, centred), the margins around them, the colour bar right of the panels over their full height.
PANEL_WIDTH, PANEL_HEIGHT_MAX = 7.5, 5.6
MARGIN = dict(left=0.85, right=1.45, top=0.85, between=0.85, bottom=1.1)
BAR_GAP, BAR_WIDTH = 0.2, 0.22


def panel_sizes(windows) -> list:
    """(width, height) in inches of each window's panel at equal aspect (the mirrored r over z)."""
    sizes = []
    for r_max, z0, z1 in windows:
        aspect = (z1 - z0) / (2 * r_max)
        h = min(PANEL_WIDTH / aspect, PANEL_HEIGHT_MAX)
        sizes.append((h * aspect, h))
    return sizes


def snapshot_figure(windows):
    """The figure, its two panels (near the spheres above, the whole domain below) and the colour bar's axes."""
    sizes = panel_sizes(windows)
    width = MARGIN["left"] + PANEL_WIDTH + BAR_GAP + BAR_WIDTH + MARGIN["right"]
    height = MARGIN["top"] + sizes[0][1] + MARGIN["between"] + sizes[1][1] + MARGIN["bottom"]
    fig = plt.figure(figsize=(width, height))
    axes, top = [], height - MARGIN["top"]
    for w, h in sizes:
        left = MARGIN["left"] + (PANEL_WIDTH - w) / 2
        axes.append(fig.add_axes((left / width, (top - h) / height, w / width, h / height)))
        top -= h + MARGIN["between"]
    bottom = MARGIN["bottom"] / height
    bar = fig.add_axes(((MARGIN["left"] + PANEL_WIDTH + BAR_GAP) / width, bottom + 0.02,
                        BAR_WIDTH / width, (height - MARGIN["top"]) / height - bottom - 0.04))
    return fig, axes, bar


def plot_snapshot(path: Path, spheres=None, wall=None, title=None, sphere_label="sphere surface", units=None, limits=None) -> None:
    """spheres: a list of (z, D), a function of the snapshot's time giving it (moving spheres), or None (the comment
    line's); wall: the wall's z (or None); title: replaces the CSV's own label; units: Units (default SI); limits:
    {quantity: colour-scale limit} shared by a run's snapshots (default this snapshot's). Writes PATH.png (vorticity)
    and, when the CSV has a pressure column `p`, PATH_pressure.png: near the spheres above, the whole domain below,
    every level composed; the spheres where the trajectory has them, the kernel's outline dashed where it differs."""
    comment, levels = read_snapshot(path)
    spheres, true, wall = snapshot_bodies(comment, spheres, wall)
    units = units or si_units(spheres[0][1] if spheres else 1.0)
    scope = "every panel and snapshot of this run" if limits else "both panels"
    limits = limits or snapshot_limits(path, spheres, wall, units)
    windows = [near_window(levels, spheres + (true or []), wall), near_window(levels, [], None)]
    for key in (k for k in QUANTITY if k in levels[0][3]):
        name, unit_attr = QUANTITY[key]
        lim = limits.get(key) or 1.0
        fig, axes, bar = snapshot_figure(windows)
        dashed = outlined = False
        for ax, window, n in zip(axes, windows, (10, 8)):
            mesh, d, o = draw_panel(ax, levels, key, window, lim, (spheres, true, wall), units, n)
            dashed, outlined = dashed or d, outlined or o
        outline_levels(axes[1], levels, units)
        axes[0].set_title(f"near the spheres: {name} (colour), streamlines", fontsize=9)
        axes[1].set_title(f"the whole domain: {len(levels)} grid levels composed, the finest wins", fontsize=9)
        cb = fig.colorbar(mesh, cax=bar, extend="both")
        label_colour_bar(cb, key, lim, f"{getattr(units, unit_attr)}: one scale in {scope}")
        fig.legend(handles=legend_handles(dashed, sphere_label, wall, outlined, key), fontsize=8, loc="lower center",
                   ncol=2 if key == "p" else 3, frameon=False)
        fig.suptitle(title or comment.split(";")[0], fontsize=11, y=1 - 0.3 / fig.get_figheight())
        for ax in axes:
            thin_ticks(ax)
        save_png(fig, path.with_suffix(".png") if key == "omega" else path.with_name(path.stem + "_pressure.png"), dpi=110)
