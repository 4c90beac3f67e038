#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""imcol.run on 1 and 2 threads (concurrent.futures.ThreadPoolExecutor), in one session: the speed-up from releasing
the GIL during runs. A benchmark, not a test: it prints timings.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_threads.py [--runs 40] [--coupled 6] [--rounds 5]

Each batch (the same scenes on 1 worker, then 2) is timed `--rounds` times, alternating, and the fastest of each is
kept, so that a moment of load from another program on the machine counts less. CPU/wall is the process's CPU time
over the wall time: above 1 with 2 workers, the runs did execute at once. "Two runs in progress" is the share of the
batch's time during which two runs had started and not ended: near 100 %, the GIL let them overlap (a run that held it
would exclude the other). A speed-up below CPU/wall's is the machine's other load. The results of the two are
checked to be the same."""
import argparse
import concurrent.futures
import os
import time

import imcol


def timed_run(scene):
    t0 = time.perf_counter()
    r = imcol.run(scene)
    return r.e, (t0, time.perf_counter())


def overlap(spans):
    """The share of the spans' union during which two or more runs were in progress."""
    edges = sorted([(a, 1) for a, _ in spans] + [(b, -1) for _, b in spans])
    both = busy = 0.0
    level, last = 0, edges[0][0]
    for t, step in edges:
        if level >= 1:
            busy += t - last
        if level >= 2:
            both += t - last
        level, last = level + step, t
    return both / busy if busy else 0.0


def batch(scenes, workers):
    """(wall seconds, CPU seconds of the process, the share of time with two runs in progress, the runs' e)"""
    t0, c0 = time.perf_counter(), time.process_time()
    with concurrent.futures.ThreadPoolExecutor(max_workers=workers) as pool:
        out = list(pool.map(timed_run, scenes))
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    return wall, cpu, overlap([span for _, span in out]), [e for e, _ in out]


def compare(label, scenes, rounds):
    best = {1: (float("inf"), 0.0, 0.0), 2: (float("inf"), 0.0, 0.0)}
    results = {}
    for _ in range(rounds):
        for w in (1, 2):
            t, cpu, both, es = batch(scenes, w)
            best[w] = min(best[w], (t, cpu, both))
            results.setdefault(w, es)
            assert es == results[1], "the threaded results differ"
    n = len(scenes)
    (t1, c1, _), (t2, c2, o2) = best[1], best[2]
    print(f"{label}: {n} runs; 1 worker {t1:.3f} s ({1e3 * t1 / n:.2f} ms/run, CPU/wall {c1 / t1:.2f}); "
          f"2 workers {t2:.3f} s ({1e3 * t2 / n:.2f} ms/run, CPU/wall {c2 / t2:.2f}, two runs in progress "
          f"{100 * o2:.0f} % of the time): speed-up {t1 / t2:.2f}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=40, help="runs of the scene `default`")
    ap.add_argument("--coupled", type=int, default=6, help="coarse coupled runs (coupled/gg3462, 12 cells/D)")
    ap.add_argument("--rounds", type=int, default=5)
    a = ap.parse_args()
    print(f"imcol {imcol.__version__}, {os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f} at start")
    compare("default", [imcol.Scene.load("default")] * a.runs, a.rounds)
    coupled = [imcol.Scene.load("coupled/gg3462").set("flow.cells_per_diameter", 12)] * a.coupled
    compare("coupled/gg3462 (12 cells/D)", coupled, a.rounds)
    print(f"load average {os.getloadavg()[0]:.2f} at the end")


if __name__ == "__main__":
    main()
