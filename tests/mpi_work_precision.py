#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""`imcol work-precision` over an MPI job against the same command in one process: `mpirun -np 3` on a small ladder
of the shipped scene gg3462 (two tolerances, three history evaluators, --repeat 2) writes a work_precision.csv equal
to the one-process run's cell for cell (the timing column aside), and its work_precision.json names the ranks and the
runs each ran (the reference and every setting's runs). With solver.max_steps so small that some settings fail,
those stay failed rows (same messages) and both exit 0; with the reference itself failing, both exit 3 with the
same error line. An --out folder rank 0 refuses ends every rank with exit 2.

Usage: /usr/bin/python3 tests/mpi_work_precision.py --imcol BIN --mpirun MPIRUN (run by ctest as mpi_work_precision)
"""
import json
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from mpi_compare import arguments, csv_differences, mpi_command, read, refused_out, report  # noqa: E402

TIMING = {"median_wall_ms"}  # differs from run to run
WP = ["work-precision", "gg3462", "--no-plot"]
LADDER = ["--rtols", "1e-4,1e-6", "--evaluators", "soe-step,soe,direct", "--direct-steps", "4"]
RANKS = 3


def compare(a, extra, rc, runs):
    """The one-process and the MPI command with the extra options; both must exit rc. With rc 0 the CSVs must agree
    and the MPI JSON must count `runs` runs; otherwise the last line on stderr must agree. Returns the differences."""
    failures = []
    with tempfile.TemporaryDirectory(prefix="imcol_mpi_wp_") as tmp:
        tmp = Path(tmp)
        cmds = {"one": [a.imcol], "mpi": mpi_command(a, RANKS)}
        err = {}
        for name, cmd in cmds.items():
            p = subprocess.run([*cmd, *WP, *extra, "--out", str(tmp / name)], stdout=subprocess.DEVNULL,
                               stderr=subprocess.PIPE, text=True, timeout=240)
            if p.returncode != rc:
                return [f"{name} exited {p.returncode} (expected {rc}): {p.stderr[-400:]}"]
            lines = [x for x in p.stderr.splitlines() if x.startswith("imcol:")]
            err[name] = lines[-1] if lines else ""
        if rc != 0:
            if not err["one"] or err["one"] != err["mpi"]:
                failures.append(f"error lines differ: '{err['one']}' vs '{err['mpi']}'")
            return failures
        one, mpi = read(tmp / "one" / "work_precision.csv"), read(tmp / "mpi" / "work_precision.csv")
        if len(one) < 3:
            failures.append(f"rows: one process {len(one) - 1} (expected 2 or more)")
        failures += csv_differences(one, mpi, TIMING)
        j = json.loads((tmp / "mpi" / "work_precision.json").read_text())
        o = json.loads((tmp / "one" / "work_precision.json").read_text())
        by_rank = j.get("runs_by_rank", [])
        if j.get("ranks") != RANKS or len(by_rank) != RANKS or sum(by_rank) != runs:
            failures.append(f"work_precision.json: ranks {j.get('ranks')}, runs_by_rank {by_rank} (expected {RANKS} ranks, {runs} runs)")
        if "ranks" in o:
            failures.append("the one-process work_precision.json names ranks")
        for key in ("reference", "observed_order", "skipped", "effects", "trajectory_velocity_scale_m_s"):
            x, y = o.get(key), j.get(key)
            if key == "reference":
                x, y = {k: v for k, v in x.items() if k != "wall_time_s"}, {k: v for k, v in y.items() if k != "wall_time_s"}
            if x != y:
                failures.append(f"work_precision.json '{key}' differs")
        statuses = [row[one[0].index("status")] for row in one[1:]]
        if ("failed" in statuses) != any("max_steps" in e for e in extra):
            failures.append(f"statuses {statuses}")
    return failures


def main():
    a = arguments()
    # Settings: soe-step on 2 integrators, soe on 3, direct on 2 (one step each) = 2*2 + 3*2 + 2 = 12.
    cases = (("", [*LADDER, "--repeat", "2"], 0, 1 + 12 * 2),
             ("failing settings: ", ["--repeat", "1", "--rtols", "1e-3,1e-6", "--ref-rtol", "1e-4", "--evaluators", "soe-step,soe",
                                     "--set", "solver.max_steps=100"], 0, 1 + 10),
             ("failing reference: ", [*LADDER, "--repeat", "1", "--ref-rtol", "1e-5", "--set", "solver.max_steps=40"], 3, 0))
    failures = []
    for label, extra, rc, runs in cases:
        failures += [label + f for f in compare(a, extra, rc, runs)]
    failures += refused_out(a, [*WP, *LADDER], RANKS)
    return report(failures)


if __name__ == "__main__":
    sys.exit(main())
