#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""`imcol calibrate` over an MPI job against the same calibration on threads: `mpirun -np 3` on a short search of
the shipped scene gg3462 writes a calibration.csv equal to the threaded one cell for cell (the timing and rank
columns aside; the refined interval ends among them), and a calibration.json with the same best, the same profiles
and 3 ranks whose evaluations add up.
Once for a trajectory (data/measurements/gg3462_trajectory.csv, one thread a rank), once for an e table (two
threads a rank). An --out folder rank 0 refuses ends every rank with exit 2. A --cache file that an MPI job wrote
serves a threaded run every evaluation (none added, the same calibration.csv), and the MPI job run again too.

Usage: /usr/bin/python3 tests/mpi_calibrate.py --imcol BIN --mpirun MPIRUN --data DATA_DIR (run by ctest as mpi_calibrate)
"""
import json
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from mpi_compare import arguments, csv_differences, mpi_command, read, refused_out, report  # noqa: E402

IGNORED = {"wall_ms", "rank"}  # where and how long an evaluation ran
SEARCH = ["--fit", "contact.delta_ss=0.005:0.05", "--set", "contact.delta_ss=0.006", "--scan", "6", "--starts", "2",
          "--max-evals", "12", "--profile-points", "5", "--no-plot", "--no-progress"]
TABLE = "sphere[0].velocity,e\n0.08,0.8450\n0.11,0.8723\n0.16,0.8964\n"


def compare(a, data, jobs):
    failures = []
    with tempfile.TemporaryDirectory(prefix="imcol_mpi_calibrate_") as tmp:
        tmp = Path(tmp)
        if data is None:
            data = tmp / "e.csv"
            data.write_text(TABLE)
        runs = {"threads": [a.imcol], "mpi": mpi_command(a, 3)}
        for name, cmd in runs.items():
            p = subprocess.run([*cmd, "calibrate", "gg3462", "--data", str(data), *SEARCH, "--jobs", str(jobs),
                                "--out", str(tmp / name)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=240)
            if p.returncode != 0:
                return [f"{name} exited {p.returncode}: {p.stderr.strip()}"]
        threads, mpi = read(tmp / "threads" / "calibration.csv"), read(tmp / "mpi" / "calibration.csv")
        if len(threads) < 10:
            failures.append(f"rows: threads {len(threads) - 1} (expected 9 or more)")
        failures += csv_differences(threads, mpi, IGNORED, ("threads", "mpi"))
        jt = json.loads((tmp / "threads" / "calibration.json").read_text())
        jm = json.loads((tmp / "mpi" / "calibration.json").read_text())
        for key in ("best", "profiles", "parameters", "measurement"):
            if jt[key] != jm[key]:
                failures.append(f"calibration.json {key}: threads {jt[key]} vs mpi {jm[key]}")
        ev = jm["evaluations"]
        if jm["ranks"] != 3 or len(ev["by_rank"]) != 3 or sum(ev["by_rank"]) != ev["count"] or ev["count"] != len(mpi) - 1:
            failures.append(f"mpi calibration.json: ranks {jm['ranks']}, by_rank {ev['by_rank']}, count {ev['count']}")
        if jt["ranks"] != 1 or jt["evaluations"]["by_rank"] != [jt["evaluations"]["count"]]:
            failures.append(f"threaded calibration.json: ranks {jt['ranks']}, by_rank {jt['evaluations']['by_rank']}")
        if not any(r[1] == "edge" for r in mpi[1:]):
            failures.append("no evaluation refined an interval end (stage edge)")
        if not any(r[-1] != "0" for r in mpi[1:]):
            failures.append("no evaluation ran on a rank other than 0")
    return failures


def cache_check(a, data):
    failures = []
    with tempfile.TemporaryDirectory(prefix="imcol_mpi_calibrate_cache_") as tmp:
        tmp = Path(tmp)
        cache = tmp / "evaluations.cache"
        for name, cmd in (("mpi", mpi_command(a, 3)), ("threads", [a.imcol]), ("mpi_again", mpi_command(a, 3))):
            p = subprocess.run([*cmd, "calibrate", "gg3462", "--data", str(data), *SEARCH, "--jobs", "1", "--cache", str(cache),
                                "--out", str(tmp / name)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=240)
            if p.returncode != 0:
                return [f"{name} with --cache exited {p.returncode}: {p.stderr.strip()}"]
            j = json.loads((tmp / name / "calibration.json").read_text())
            count, c = j["evaluations"]["count"], j["cache"]
            if name == "mpi":  # a new file: every distinct point added
                ok = c["reused"] == 0 and 0 < c["added"] <= count
            else:  # the whole search from the file
                ok = c["reused"] == count and c["added"] == 0
            if not ok:
                failures.append(f"{name}: cache {c} for {count} evaluations")
        failures += csv_differences(read(tmp / "mpi" / "calibration.csv"), read(tmp / "threads" / "calibration.csv"), IGNORED,
                                    ("mpi", "threads from its cache"))
    return failures


def main():
    a = arguments("--data")
    failures = []
    trajectory = Path(a.data) / "measurements" / "gg3462_trajectory.csv"
    for label, data, jobs in (("trajectory: ", trajectory, 1),
                              ("e table, two threads a rank: ", None, 2)):
        failures += [label + f for f in compare(a, data, jobs)]
    failures += ["cache: " + f for f in cache_check(a, trajectory)]
    failures += refused_out(a, ["calibrate", "gg3462", "--data", str(trajectory), *SEARCH, "--jobs", "1"], 3)
    return report(failures)


if __name__ == "__main__":
    sys.exit(main())
