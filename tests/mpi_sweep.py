#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""`imcol sweep` over an MPI job against the same sweep on threads: `mpirun -np 3` on six points of the shipped
scene `default` writes a sweep.csv equal to the threaded one cell for cell (the timing column aside), and its
sweep.json names the ranks and the points each ran, which add up to the sweep. The same with solver.max_steps so
small that some points fail: the others still run, both exit 3 and the CSVs (messages included) agree; and with two
threads a rank. An --out folder rank 0 refuses ends every rank with exit 2.

Usage: /usr/bin/python3 tests/mpi_sweep.py --imcol BIN --mpirun MPIRUN (run by ctest as mpi_sweep)
"""
import json
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from mpi_compare import arguments, csv_differences, mpi_command, read, refused_out, report  # noqa: E402

TIMING = {"wall_time_s"}  # differs from run to run
SWEEP = ["sweep", "default", "--vary", "velocity", "--from", "0.05", "--to", "1", "--points", "6", "--no-plot",
         "--no-progress"]


def compare(a, extra, rc):
    """The threaded and the MPI sweep with the extra options; both must exit rc. Returns the differences found."""
    failures = []
    with tempfile.TemporaryDirectory(prefix="imcol_mpi_sweep_") as tmp:
        tmp = Path(tmp)
        runs = {"threads": [a.imcol], "mpi": mpi_command(a, 3)}
        for name, cmd in runs.items():
            got = subprocess.run([*cmd, *SWEEP, *extra, "--out", str(tmp / name)], stdout=subprocess.DEVNULL,
                                 stderr=subprocess.DEVNULL, timeout=120).returncode
            if got != rc:
                return [f"{name} exited {got} (expected {rc})"]
        threads, mpi = read(tmp / "threads" / "sweep.csv"), read(tmp / "mpi" / "sweep.csv")
        if len(threads) != 7:
            failures.append(f"rows: threads {len(threads) - 1} (expected 6)")
        failures += csv_differences(threads, mpi, TIMING, ("threads", "mpi"))
        j = json.loads((tmp / "mpi" / "sweep.json").read_text())
        if j.get("ranks") != 3 or len(j.get("points_by_rank", [])) != 3 or sum(j["points_by_rank"]) != 6:
            failures.append(f"sweep.json: ranks {j.get('ranks')}, points_by_rank {j.get('points_by_rank')} (expected 3 ranks, 6 points)")
        t = json.loads((tmp / "threads" / "sweep.json").read_text())
        if j.get("failures") != t.get("failures") or (j.get("failures") == []) != (rc == 0) or not j.get("complete"):
            failures.append(f"sweep.json: failures {j.get('failures')} (threads: {t.get('failures')}), complete {j.get('complete')}")
        if "ranks" in t:
            failures.append("the threaded sweep.json names ranks")
        if (tmp / "mpi" / "sweep.partial").exists():
            failures.append("sweep.partial left behind")
    return failures


def main():
    a = arguments()
    failures = []
    cases = (("", ["--jobs", "1"], 0), ("two threads a rank: ", ["--jobs", "2"], 0),
             ("failing points: ", ["--jobs", "1", "--set", "solver.max_steps=60"], 3))
    for label, extra, rc in cases:
        failures += [label + f for f in compare(a, extra, rc)]
    failures += refused_out(a, [*SWEEP, "--jobs", "1"], 3)
    return report(failures)


if __name__ == "__main__":
    sys.exit(main())
