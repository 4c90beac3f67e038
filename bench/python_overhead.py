#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""The cost of a call of imcol.run against the program, measured in the same run.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_overhead.py [--imcol build/bin/imcol] [--scene default]
        [--repeat 50] [--rounds 3]

Each round (the order alternating between rounds) runs `imcol bench SCENE --rtols R --repeat N` as a program and a
Python loop of N calls imcol.run(scene) in this process. The program prints two medians: `median ms`, the
integration alone (summary wall_time_s), and `call ms`, the whole simulate() call (model set-up, integration,
measures, summary; also freeing the previous run's result). The loop gives the median time of the Python call (which
also frees the previous result), `py wall ms`, the median wall_time_s of its results, and `py minflt`, the page
faults per call. Printed per round and as the median over rounds:
  python / median ms   the Python call against the program's integration time (the aim: under 1.05)
  python / call ms     the Python call against the program's whole simulate() call (like for like, across processes)
  call ms / median ms  what simulate() does outside wall_time_s, in the program itself
  in-process           (python ms / py wall ms) / (call ms / median ms): each call normalised by the integration
                       timed in its own process, so a machine running faster or slower in one process than in the other
                       cancels; 1 + the module's own cost, as a fraction of the program's whole call
Both must measure the same e.
"""
import argparse
import pathlib
import resource
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
    """(median ms of the call, median ms of its wall_time_s, page faults per call, e) of `repeat` calls of imcol.run."""
    calls, walls = [], []
    r = None
    faults = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    for _ in range(repeat):
        t0 = time.perf_counter()
        r = imcol.run(scene, rtol=rtol)  # rebinding r frees the previous result, as `r = simulate(sc)` in the program
        calls.append(time.perf_counter() - t0)
        walls.append(r.wall_time_s)  # read from the typed summary: builds no Python objects but a float
    faults = (resource.getrusage(resource.RUSAGE_SELF).ru_minflt - faults) / repeat
    return 1e3 * statistics.median(calls), 1e3 * statistics.median(walls), faults, r.e


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
    print(f"{'round':>5} {'median ms':>10} {'call ms':>9} {'python ms':>10} {'py wall ms':>11} {'py minflt':>10}"
          f" {'py/median':>10} {'py/call':>8} {'call/median':>12} {'in-process':>11}")
    ratios = []
    for k in range(a.rounds):
        if k % 2 == 0:
            med, call, e_cli = run_program(a.imcol, a.scene, a.rtol, a.repeat)
            py, py_wall, faults, e_py = run_python(scene, rtol, a.repeat)
        else:
            py, py_wall, faults, e_py = run_python(scene, rtol, a.repeat)
            med, call, e_cli = run_program(a.imcol, a.scene, a.rtol, a.repeat)
        if abs(e_cli - e_py) > 5e-10:  # the program prints e to 9 decimals
            sys.exit(f"e differs: program {e_cli}, Python {e_py}")
        inproc = (py / py_wall) / (call / med)
        ratios.append((py / med, py / call, call / med, inproc))
        print(f"{k + 1:>5} {med:>10.3f} {call:>9.3f} {py:>10.3f} {py_wall:>11.3f} {faults:>10.2f} {py / med:>10.3f}"
              f" {py / call:>8.3f} {call / med:>12.3f} {inproc:>11.3f}")
    m = [statistics.median(x) for x in zip(*ratios)]
    print(f"median over rounds: python / median ms = {m[0]:.3f}, python / call ms = {m[1]:.3f}, "
          f"call ms / median ms = {m[2]:.3f}, in-process (python / py wall) / (call / median) = {m[3]:.3f}")
    print("python / median ms: the Python call against the program's integration alone (includes simulate()'s own "
          "set-up, measures and summary);\n"
          "in-process: the Python call against the program's whole call, each timed against its own integration, "
          "minus 1 = the module's own cost")


if __name__ == "__main__":
    main()
