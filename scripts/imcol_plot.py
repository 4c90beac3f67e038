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


def kernel_colour(kernel: str) -> str:
    if kernel not in KERNEL_COLOURS:
        used = set(KERNEL_COLOURS.values())
        KERNEL_COLOURS[kernel] = next((f"C{i}" for i in range(4, 10) if f"C{i}" not in used), "k")
    return KERNEL_COLOURS[kernel]


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
