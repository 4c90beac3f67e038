# SPDX-License-Identifier: BSD-3-Clause
"""Shared set-up of imcol's plot scripts: matplotlib without a display, the DIR argument, atomic PNGs.

Needs Debian's python3-matplotlib (importable from /usr/bin/python3 only).
"""
import csv
import math
import os
import sys
from pathlib import Path
from typing import Optional

import matplotlib
import matplotlib.ticker  # noqa: F401  (re-exported)

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402,F401  (re-exported)


def out_dir(doc: str) -> Optional[Path]:
    """The one command-line argument DIR, or None after printing the usage `doc`."""
    if len(sys.argv) != 2:
        print(doc.strip(), file=sys.stderr)
        return None
    return Path(sys.argv[1])


def save_png(fig, path: Path, dpi: int = 120) -> None:
    """Writes the figure completely or not at all (a temporary file unique to this process, then rename),
    and closes it; concurrent writers into one folder never share a temporary file."""
    tmp = path.with_name(f"{path.name}.tmp.{os.getpid()}.png")
    try:
        fig.savefig(tmp, dpi=dpi)
        os.replace(tmp, path)
    finally:
        plt.close(fig)
        if tmp.exists():
            tmp.unlink()


def write_text(path: Path, text: str) -> None:
    """Writes a text file completely or not at all (a temporary file unique to this process, then rename)."""
    tmp = path.with_name(f"{path.name}.tmp.{os.getpid()}")
    try:
        tmp.write_text(text)
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def read_rows(path: Path) -> list:
    """The rows of a CSV file written by imcol, as dicts by column name (lines starting with '#' are comments)."""
    with open(path, newline="") as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


# One colour per history kernel, the same in every picture (history.png, history_sweep.png); a kernel not listed
# takes the next free colour of matplotlib's cycle.
KERNEL_COLOURS = {"none": "0.45", "basset": "C0", "mei-adrian": "C1", "kim": "C2", "dorgan-loth": "C3"}


# Marker, line style and draw order (larger: on top) per kernel, so that curves lying on each other stay visible:
# Basset last, hollow and larger, around the finite-Re kernels' markers.
KERNEL_MARKS = {"none": ("o", "-", 1), "basset": ("s", "-", 5), "mei-adrian": ("^", "--", 3), "kim": ("v", ":", 4),
                "dorgan-loth": ("D", "-.", 2)}
# Each kernel's source (contact/history_kernel.hpp).
KERNEL_SOURCES = {"none": "no history force", "basset": "Basset (1888), the Re → 0 kernel",
                  "mei-adrian": "Mei & Adrian (1992)", "kim": "Kim, Elghobashi & Sirignano (1998)",
                  "dorgan-loth": "Dorgan & Loth (2007)"}


def kernel_style(kernel: str) -> dict:
    """matplotlib keywords of a kernel's curve: colour, marker (Basset's hollow and larger), line style, z-order."""
    mk, ls, z = KERNEL_MARKS.get(kernel, ("P", "-", 2))
    style = dict(color=kernel_colour(kernel), marker=mk, ls=ls, zorder=2 + z, ms=5, lw=1.3)
    if kernel == "basset":
        style.update(mfc="none", ms=9, mew=1.6, lw=2.2)
    return style


def kernel_label(kernel: str) -> str:
    """'kim (Kim, Elghobashi & Sirignano 1998)'."""
    return f"{kernel}: {KERNEL_SOURCES[kernel]}" if kernel in KERNEL_SOURCES else kernel


def kernel_colour(kernel: str) -> str:
    if kernel not in KERNEL_COLOURS:
        used = set(KERNEL_COLOURS.values())
        KERNEL_COLOURS[kernel] = next((f"C{i}" for i in range(4, 10) if f"C{i}" not in used), "k")
    return KERNEL_COLOURS[kernel]


# The effects (scene key `effects`) in plain words.
EFFECT_WORDS = {"added_mass": "added mass", "elastic": "elastic contact", "history": "history force",
                "flow": "the flow solver (coupled)", "lubrication": "lubrication", "drag": "drag"}


# The force columns of trajectory.csv by what they are (the sphere's number follows the name: f_drag1, f_drag2).
FORCE_NAMES = {"f_drag": "drag", "f_lub": "lubrication", "f_am": "added mass", "f_contact": "contact", "f_hist": "history",
               "f_grav": "gravity", "f_sim": "simulated f_SIM", "f_thr": "theory f_THR"}


def force_label(column: str, pair: bool) -> str:
    """'f_am1' -> 'added mass' (one sphere) or 'sphere 1 added mass' (a pair); other columns unchanged."""
    stem, k = column.rstrip("0123456789"), column[len(column.rstrip("0123456789")):]
    name = FORCE_NAMES.get(stem)
    if name is None:
        return column
    return f"sphere {k} {name}" if pair and k else name


def has_e(r) -> bool:
    """A sweep row (sweep.csv, history_sweep.csv) whose run ended and measured e."""
    return r["status"] == "ok" and bool(r["e"])


def positions(rows, meta, key: str) -> list:
    """Each row's x (its column `key`, e.g. St): a row without it (a failed run) gets the value interpolated in log-log
    from the others' (x against the varied quantity), so that its gap and marker stand where it would have been."""
    col = meta["column"]
    known = sorted((math.log(float(r[col])), math.log(float(r[key]))) for r in rows if r.get(key) and float(r[key]) > 0)
    xs = []
    for r in rows:
        if r.get(key) or len(known) < 2:
            xs.append(float(r[key]) if r.get(key) else float("nan"))
            continue
        v = math.log(float(r[col]))
        i = 1  # the segment of `known` around v; the end segments extrapolate
        while i < len(known) - 1 and known[i][0] < v:
            i += 1
        (a0, b0), (a1, b1) = known[i - 1], known[i]
        xs.append(math.exp(b0 + (b1 - b0) * (v - a0) / (a1 - a0)) if a1 != a0 else math.exp(b0))
    return xs


REPO = Path(__file__).resolve().parent.parent


def read_scene(scene_file) -> Optional[dict]:
    """A scene file (TOML) as a dict, or None when it cannot be read; a relative path not found from the working
    folder is taken from the repository's top (imcol writes the path it was given)."""
    if not scene_file:
        return None
    path = Path(scene_file)
    if not path.is_absolute() and not path.exists():
        path = REPO / path
    try:
        import tomllib

        with open(path, "rb") as f:
            return tomllib.load(f)
    except (ImportError, OSError, TypeError, ValueError):
        return None


def scene_bodies(scene_file) -> Optional[dict]:
    """The spheres (material, D in m) and the wall's material of a scene file (TOML), or None when it cannot be read."""
    scene = read_scene(scene_file)
    if scene is None:
        return None
    spheres = [(s.get("material", ""), float(s["diameter"])) for s in scene.get("sphere", []) if "diameter" in s]
    wall = scene.get("wall")
    return {"spheres": spheres, "wall": wall.get("material", "") if isinstance(wall, dict) else None}


def bodies_text(bodies: Optional[dict]) -> str:
    """'12.7 mm steel sphere onto a zerodur wall', 'two 12.7 mm glass spheres', or '' without the scene."""
    if not bodies or not bodies["spheres"]:
        return ""
    names = [f"{1e3 * d:.3g} mm {m}".strip() for m, d in bodies["spheres"]]
    if len(names) == 1:
        wall = bodies["wall"]
        return names[0] + " sphere" + ("" if wall is None else f" onto a {wall} wall".replace("a  wall", "a wall"))
    return f"two {names[0]} spheres" if names[0] == names[1] else f"{names[0]} sphere onto a {names[1]} sphere"


def liquid_text(fluid: Optional[dict]) -> str:
    """'glycerol-water 50 wt% at 20 °C, μ = 6 mPa s, ρ = 1126 kg/m³' from summary.json's `fluid` (μ and ρ left out
    when None), 'a liquid of μ = 20 mPa s, ρ = 1200 kg/m³' without a name; 'no liquid' when μ = 0."""
    if not fluid:
        return ""
    mu, rho = fluid.get("viscosity_Pa_s"), fluid.get("density_kg_m3")
    if mu is not None and mu <= 0:
        return "no liquid"
    name = fluid.get("name") or ""
    if fluid.get("mass_fraction") is not None:
        name += f" {100 * fluid['mass_fraction']:.3g} wt%"
    if fluid.get("temperature_C") is not None:
        name += f" at {fluid['temperature_C']:.3g} °C"
    values = ([f"μ = {1e3 * mu:.3g} mPa s"] if mu is not None else []) + ([f"ρ = {rho:.4g} kg/m³"] if rho is not None else [])
    if not fluid.get("name"):  # a liquid given by its values alone
        return "a liquid of " + ", ".join(values) if values else "a liquid"
    return ", ".join([name.strip()] + values)


def figure_legend(fig, axes, **kw):
    """One legend for the figure: every labelled artist of `axes` once (the first of each label), right of the panels."""
    seen = {}
    for ax in axes:
        for h, label in zip(*ax.get_legend_handles_labels()):
            if label and not label.startswith("_"):
                seen.setdefault(label, h)
    opts = dict(loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize=8, frameon=False)
    opts.update(kw)
    return fig.legend(list(seen.values()), list(seen), **opts) if seen else None


def deviation_at(xs, model, reference, at) -> list:
    """model − reference (two lists over xs) at the x values `at`, interpolated linearly in log x between the nearest
    finite points (NaN outside the points' range): [(x, deviation)]."""
    pts = sorted((math.log(x), m - r) for x, m, r in zip(xs, model, reference)
                 if x > 0 and math.isfinite(m) and math.isfinite(r))
    out = []
    for x in at:
        v = math.log(x)
        d = float("nan")
        for (a0, d0), (a1, d1) in zip(pts, pts[1:]):
            if a0 <= v <= a1:
                d = d0 + (d1 - d0) * (v - a0) / (a1 - a0) if a1 > a0 else d0
                break
        if len(pts) == 1 and abs(pts[0][0] - v) < 1e-12:
            d = pts[0][1]
        out.append((x, d))
    return out


def deviation_text(name: str, xs, model, reference, xname: str = "St") -> str:
    """'imcol − NAME: +0.21 at St 30, +0.17 at St 46 (largest), +0.02 at St 750': the deviation at the lowest and
    highest x with both values, and the largest one when it lies between them."""
    pts = sorted((x, m - r) for x, m, r in zip(xs, model, reference) if x > 0 and math.isfinite(m) and math.isfinite(r))
    if not pts:
        return ""
    big = max(pts, key=lambda p: abs(p[1]))
    shown = [(pts[0], "")] + ([(big, " (largest)")] if big not in (pts[0], pts[-1]) else []) + ([(pts[-1], "")] if len(pts) > 1 else [])

    def at(x):
        return f"{xname} {x:.3g}" if x < 1000 else f"{xname} {x:.0f}"

    return f"imcol − {name}: " + ", ".join(f"{round(d, 2) + 0.0:+.2f} at {at(x)}{tag}" for (x, d), tag in shown)


def scene_fluid(scene_file) -> Optional[dict]:
    """A scene file's liquid in summary.json's `fluid` form (name, mass fraction, temperature, μ and ρ when given in the
    scene; a named liquid's μ and ρ come from data/fluids.csv and are left out), or None."""
    scene = read_scene(scene_file)
    if scene is None:
        return None
    fl = scene.get("fluid", {})
    return {"name": fl.get("fluid"), "mass_fraction": fl.get("mass_fraction"), "temperature_C": fl.get("temperature"),
            "viscosity_Pa_s": fl.get("viscosity"), "density_kg_m3": fl.get("density")}


def sweep_scene_text(meta) -> str:
    """'default: 12.7 mm steel sphere onto a zerodur wall in …' from a sweep's json (scene, scene_file, vary): the
    swept quantity left out (a diameter sweep names no bodies; a viscosity or density sweep no μ or ρ)."""
    bodies = bodies_text(scene_bodies(meta.get("scene_file"))) if meta["vary"] != "diameter" else ""
    fluid = scene_fluid(meta.get("scene_file"))
    if fluid and meta["vary"] in ("viscosity", "density"):  # swept: the scene's value is not the sweep's
        fluid[{"viscosity": "viscosity_Pa_s", "density": "density_kg_m3"}[meta["vary"]]] = None
    liquid = liquid_text(fluid)
    return meta["scene"] + (": " + bodies if bodies else "") + (" in " + liquid if liquid else "")
