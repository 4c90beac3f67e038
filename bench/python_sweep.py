#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Throughput of a sweep from Python against `imcol sweep`, measured in the same run.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_sweep.py [--imcol build/bin/imcol] [--points 1000] [--jobs 2]

Each round runs the same velocity sweep of `default` both ways (the order alternating between rounds):
imcol.sweep(...) in this process, and `imcol sweep default --vary velocity --from A --to B --points N --jobs J
--no-plot` as a program (its wall time from start to exit, and the throughput it prints itself). Prints collisions
per second and the ratio Python / program per round, and the median ratio. Both must give the same e at every point.
"""
import argparse
import csv
import os
import pathlib
import re
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import imcol

ROOT = pathlib.Path(__file__).resolve().parents[1]


def values(start, stop, points):
    """The values `--from --to --points` gives (log spacing), computed as the program does."""
    return [start * (stop / start) ** (0.0 if points == 1 else i / (points - 1)) for i in range(points)]


def run_cli(imcol_bin, args, out):
    cmd = [imcol_bin, "sweep", "default", "--vary", "velocity", "--from", repr(args.start), "--to", repr(args.stop),
           "--points", str(args.points), "--jobs", str(args.jobs), "--no-plot", "--no-progress", "--out", str(out)]
    t = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t
    if p.returncode != 0:
        sys.exit("imcol sweep failed: " + p.stderr)
    # "N of N points ran in T s on J jobs: R collisions per second (…)"
    m = re.search(r"(\d+) of \d+ points ran in ([0-9.]+) s on \d+ jobs?: ([0-9.]+) collisions per second", p.stdout)
    with open(out / "sweep.csv", newline="") as f:
        e = [float(r["e"]) if r["e"] else float("nan") for r in csv.DictReader(f)]
    return wall, float(m.group(2)), np.array(e)


def run_python(args):
    t = time.perf_counter()
    r = imcol.sweep("default", vary="velocity", values=values(args.start, args.stop, args.points), jobs=args.jobs)
    wall = time.perf_counter() - t
    if np.any(r.status != "ok"):
        sys.exit("imcol.sweep: a point failed")
    return wall, r.e


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--imcol", default=os.environ.get("IMCOL_BINARY", str(ROOT / "build" / "bin" / "imcol")))
    ap.add_argument("--points", type=int, default=1000)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--from", dest="start", type=float, default=0.05)
    ap.add_argument("--to", dest="stop", type=float, default=1.0)
    ap.add_argument("--rounds", type=int, default=3)
    args = ap.parse_args()
    n = args.points
    print(f"velocity sweep of default, {n} points from {args.start} to {args.stop} m/s, {args.jobs} jobs; "
          f"load average before: {os.getloadavg()[0]:.2f}")
    print(f"{'round':>5} {'python c/s':>11} {'program c/s':>12} {'(its own)':>10} {'ratio':>7} {'ratio (own)':>12}")
    ratios, ratios_own = [], []
    with tempfile.TemporaryDirectory() as tmp:
        for k in range(args.rounds):
            out = pathlib.Path(tmp) / f"round{k}"
            if k % 2 == 0:
                py_wall, py_e = run_python(args)
                cli_wall, cli_own, cli_e = run_cli(args.imcol, args, out)
            else:
                cli_wall, cli_own, cli_e = run_cli(args.imcol, args, out)
                py_wall, py_e = run_python(args)
            # The same points, the same e (sweep.csv's 12 digits).
            if not np.allclose(py_e, cli_e, rtol=1e-11, atol=0, equal_nan=True):
                sys.exit("the two sweeps differ in e")
            py, cli, own = n / py_wall, n / cli_wall, n / cli_own
            ratios.append(py / cli)
            ratios_own.append(py / own)
            print(f"{k:>5} {py:>11.1f} {cli:>12.1f} {own:>10.1f} {py / cli:>7.3f} {py / own:>12.3f}")
    print(f"median ratio python / program: {statistics.median(ratios):.3f} (program timed from start to exit), "
          f"{statistics.median(ratios_own):.3f} (against the throughput the program prints); "
          f"load average after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
