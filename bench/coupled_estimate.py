#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""A coupled run's cost estimate against its measured CPU time (docs/performance.md §7).

    python3 bench/coupled_estimate.py [--imcol build/bin/imcol] [--scenes gg3462 gondret_st27 ...]
        [--cells 16 24 32] [--check 2 [--relative]] [--check-q 1.5]

Runs `imcol run coupled/SCENE --set flow.cells_per_diameter=N --quiet --no-plot` for every shipped coupled scene
(data/scenes/coupled/) or the ones named, at each resolution, one run at a time, and prints summary.json's
flow.estimate.total_s, the run's own CPU time flow.cpu_time_s (start-up, steps and flow fields) and their ratio, and
the applications of the force operator Q the estimate counted against those the run made (flow.estimate.q_applications,
flow.q_applications; a ratio that does not depend on the machine).
With --check R the exit status is 1 when a ratio lies outside [1/R, R]. With --relative the ratios are first divided
by their median, the machine's speed against the one the estimate's unit costs were measured on (flow/cost.hpp),
taken in the same run: the check is then on what the estimate counts, on any machine or build. With --check-q R the
exit status is 1 when the estimated applications of Q over the run's own lie outside [1/R, R], or when the estimated
flow-field snapshots are not those the run took.
"""
import argparse
import json
import pathlib
import statistics
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent


def run_one(imcol, scene, cells, out):
    cmd = [imcol, "run", f"coupled/{scene}", "--out", str(out), "--quiet", "--no-plot",
           "--set", f"flow.cells_per_diameter={cells}"]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    flow = json.loads((out / "summary.json").read_text())["flow"]
    q = flow["estimate"]["q_applications"] / flow["q_applications"] if flow["q_applications"] else 1.0
    snaps = (round(flow["estimate"]["field_snapshots"]), flow["field_snapshots"])
    return flow["estimate"]["total_s"], flow["cpu_time_s"], flow["steps"], q, snaps


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--imcol", default=str(ROOT / "build" / "bin" / "imcol"))
    ap.add_argument("--scenes", nargs="*", default=None, help="names in data/scenes/coupled (default: all)")
    ap.add_argument("--cells", nargs="*", type=int, default=[16, 24, 32])
    ap.add_argument("--check", type=float, default=0, help="fail when estimate/measured is outside [1/R, R]")
    ap.add_argument("--relative", action="store_true", help="check the ratios divided by their median")
    ap.add_argument("--check-q", type=float, default=0, help="fail when the estimated applications of Q over the run's "
                    "are outside [1/R, R]")
    a = ap.parse_args()
    scenes = a.scenes or sorted(p.stem for p in (ROOT / "data" / "scenes" / "coupled").glob("*.toml"))
    rows, qs, bad_q = [], [], []
    print(f"{'scene':22s} {'cells/D':>7s} {'steps':>6s} {'estimate s':>11s} {'measured s':>11s} {'est/meas':>9s} {'Q est/meas':>10s} "
          f"{'snapshots':>9s}")
    with tempfile.TemporaryDirectory() as tmp:
        for scene in scenes:
            for cells in a.cells:
                est, cpu, steps, q, snaps = run_one(a.imcol, scene, cells, pathlib.Path(tmp) / f"{scene}_{cells}")
                ratio = est / cpu if cpu > 0 else float("inf")
                rows.append((scene, cells, est, cpu, ratio))
                qs.append(q)
                if a.check_q and not (1 / a.check_q <= q <= a.check_q):
                    bad_q.append(f"{scene} at {cells} cells/D: applications of Q estimated over made {q:.2f}")
                if a.check_q and snaps[0] != snaps[1]:
                    bad_q.append(f"{scene} at {cells} cells/D: {snaps[0]} flow-field snapshots estimated, {snaps[1]} taken")
                print(f"{scene:22s} {cells:7d} {steps:6d} {est:11.3f} {cpu:11.3f} {ratio:9.2f} {q:10.2f} {snaps[0]:4d}/{snaps[1]:<4d}",
                      flush=True)
    print(f"est/meas {min(r[4] for r in rows):.2f}–{max(r[4] for r in rows):.2f} (median "
          f"{statistics.median(r[4] for r in rows):.2f}); Q est/meas {min(qs):.2f}–{max(qs):.2f}")
    scale = statistics.median(r[4] for r in rows) if a.relative else 1.0
    if a.relative:
        print(f"median est/meas {scale:.2f}: the ratios below are divided by it")
    bad = [f"{scene} at {cells} cells/D: estimate {est:.3f} s, measured {cpu:.3f} s, ratio {ratio / scale:.2f}"
           for scene, cells, est, cpu, ratio in rows if a.check and not (1 / a.check <= ratio / scale <= a.check)]
    for b in bad:
        print(f"coupled_estimate: outside {a.check}x: {b}", file=sys.stderr)
    for b in bad_q:
        print(f"coupled_estimate: outside {a.check_q}x: {b}", file=sys.stderr)
    return 1 if bad or bad_q else 0


if __name__ == "__main__":
    sys.exit(main())
