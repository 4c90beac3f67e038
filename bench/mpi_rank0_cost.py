#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""What one sweep point costs rank 0 of an MPI job, beyond running points of its own: a sweep of N cheap points of
the shipped scene `default` (a few ms each) over -np 2 and 3 (--jobs 1), read back from sweep.json: rank 0's time
taking a point in (decoding its bytes, rewriting sweep.csv), the rewrites alone, and loading and checking every
point's scene (each rank does that before the start). Prints one line per run. Not a test: timings vary.

Usage: bench/mpi_rank0_cost.py [--imcol build/bin/imcol] [--mpirun mpirun] [--points 1000,10000] [--ranks 2,3]
"""
import argparse
import json
import subprocess
import tempfile
import time
from pathlib import Path


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--imcol", default="build/bin/imcol")
    ap.add_argument("--mpirun", default="mpirun")
    ap.add_argument("--points", default="1000,10000")
    ap.add_argument("--ranks", default="2,3")
    a = ap.parse_args()
    print(f"{'points':>7} {'ranks':>5} {'wall s':>8} {'rank0 ms/pt':>12} {'rewrites':>9} {'ms/rewrite':>11} "
          f"{'csv MB':>7} {'scenes ms/pt':>13}")
    for n in [int(x) for x in a.points.split(",")]:
        for ranks in [int(x) for x in a.ranks.split(",")]:
            with tempfile.TemporaryDirectory(prefix="imcol_rank0_") as tmp:
                out = Path(tmp) / "sweep"
                cmd = [a.mpirun, "--allow-run-as-root", "--oversubscribe", "-np", str(ranks), a.imcol, "sweep", "default",
                       "--vary", "velocity", "--from", "0.05", "--to", "1", "--points", str(n), "--jobs", "1", "--no-plot",
                       "--no-progress", "--out", str(out)]
                t0 = time.monotonic()
                subprocess.run(cmd, stdout=subprocess.DEVNULL, check=True)
                wall = time.monotonic() - t0
                j = json.loads((out / "sweep.json").read_text())
                mb = (out / "sweep.csv").stat().st_size / 1e6
                print(f"{n:>7} {ranks:>5} {wall:>8.1f} {j['rank0_ms_per_point']:>12.4f} {j['csv_rewrites']:>9} "
                      f"{j['csv_rewrite_ms']:>11.2f} {mb:>7.2f} {1e3 * j['scenes_check_s'] / n:>13.3f}")


if __name__ == "__main__":
    main()
