#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""The cost of a call of imcol.run against the program, measured in the same run.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_overhead.py [--imcol build/bin/imcol] [--scene default]
        [--repeat 50] [--rounds 3]

Each round (the order alternating between rounds) runs `imcol bench SCENE --rtols R --repeat N` as a program and a
Python loop of N calls imcol.run(scene) in this process. The program prints two medians: `median ms`, the
integration alone (summary wall_time_s), and `call ms`, the whole simulate() call (model set-up, integration,
measures, summary). The loop gives the median time of the Python call, and the median wall_time_s of its results.
Printed per round and as the median over rounds:
  python / median ms   the Python call against the program's integration time (the aim: under 1.05)
  python / call ms     the Python call against the program's whole simulate() call (like for like)
  call ms / median ms  what simulate() does outside wall_time_s, in the program itself
Both must measure the same e.
"""
import argparse
import pathlib
import re
import statistics
import subprocess
import sys
import time

import imcol

ROOT = pathlib.Path(__file__).resolve().parents[1]


def run_program(imcol_bin, scene, rtol, repeat):
    """(median ms, call ms, e) from `imcol bench`."""
    p = subprocess.run([imcol_bin, "bench", scene, "--rtols", rtol, "--repeat", str(repeat)],
                       capture_output=True, text=True, check=True)
    lines = p.stdout.splitlines()
    header = next(i for i, line in enumerate(lines) if line.split()[:1] == ["rtol"])
    cols = lines[header + 1].split()
    # rtol, e, |e - e_ref|, steps, rhs, median ms, ratio, call ms
    return float(cols[5]), float(cols[7]), float(cols[1])


def run_python(scene, rtol, repeat):
    """(median ms of the call, median ms of its wall_time_s, e) of `repeat` calls of imcol.run."""
    calls, walls = [], []
    for _ in range(repeat):
        t0 = time.perf_counter()
        r = imcol.run(scene, rtol=rtol)
        calls.append(time.perf_counter() - t0)
        walls.append(r.wall_time_s)
    return 1e3 * statistics.median(calls), 1e3 * statistics.median(walls), r.e


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--imcol", default=str(ROOT / "build" / "bin" / "imcol"))
    ap.add_argument("--scene", default="default")
    ap.add_argument("--rtol", default="1e-6", help="as imcol bench's first (default) tolerance")
    ap.add_argument("--repeat", type=int, default=50)
    ap.add_argument("--rounds", type=int, default=3)
    a = ap.parse_args()
    scene = imcol.Scene.load(a.scene)
    rtol = float(a.rtol)
    imcol.run(scene, rtol=rtol)  # warm: the module's first call loads what every later call reuses
    print(f"scene {a.scene}, rtol {a.rtol}: median of {a.repeat} runs per round, {a.rounds} rounds")
    print(f"{'round':>5} {'median ms':>10} {'call ms':>9} {'python ms':>10} {'py wall ms':>11}"
          f" {'py/median':>10} {'py/call':>8} {'call/median':>12}")
    ratios = []
    for k in range(a.rounds):
        if k % 2 == 0:
            med, call, e_cli = run_program(a.imcol, a.scene, a.rtol, a.repeat)
            py, py_wall, e_py = run_python(scene, rtol, a.repeat)
        else:
            py, py_wall, e_py = run_python(scene, rtol, a.repeat)
            med, call, e_cli = run_program(a.imcol, a.scene, a.rtol, a.repeat)
        if abs(e_cli - e_py) > 5e-10:  # the program prints e to 9 decimals
            sys.exit(f"e differs: program {e_cli}, Python {e_py}")
        ratios.append((py / med, py / call, call / med))
        print(f"{k + 1:>5} {med:>10.3f} {call:>9.3f} {py:>10.3f} {py_wall:>11.3f} {py / med:>10.3f} {py / call:>8.3f}"
              f" {call / med:>12.3f}")
    m = [statistics.median(x) for x in zip(*ratios)]
    print(f"median over rounds: python / median ms = {m[0]:.3f}, python / call ms = {m[1]:.3f}, "
          f"call ms / median ms = {m[2]:.3f}")


if __name__ == "__main__":
    main()
