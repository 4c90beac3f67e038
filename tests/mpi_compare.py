# SPDX-License-Identifier: BSD-3-Clause
"""What the MPI tests (tests/mpi_*.py) share: the command of an MPI job, the cell-for-cell comparison of a CSV
that one process wrote with the one the MPI job wrote, and an output folder that rank 0 refuses."""
import argparse
import csv
import subprocess
import tempfile
from pathlib import Path


def read(path):
    with open(path, newline="") as f:
        return list(csv.reader(f))


def mpi_command(a, ranks):
    """`mpirun … -np RANKS imcol` (a.mpirun, a.imcol), as the tests run it: as root, more ranks than cores allowed."""
    return [a.mpirun, "--allow-run-as-root", "--oversubscribe", "-np", str(ranks), a.imcol]


def csv_differences(one, mpi, ignored, labels=("one process", "mpi")):
    """The differences between two CSVs read by read(): the header, the row count, then every cell of the columns
    not in `ignored`."""
    failures = []
    if one[0] != mpi[0]:
        failures.append(f"headers differ: {one[0]} vs {mpi[0]}")
    if len(mpi) != len(one):
        failures.append(f"rows: {labels[0]} {len(one) - 1}, {labels[1]} {len(mpi) - 1}")
    for r, (x, y) in enumerate(zip(one[1:], mpi[1:]), start=1):
        for name, u, v in zip(one[0], x, y):
            if name not in ignored and u != v:
                failures.append(f"row {r} column {name}: {labels[0]} '{u}' vs {labels[1]} '{v}'")
    return failures


def refused_out(a, args, ranks):
    """The MPI job of `args` (a command line without --out) writing to a folder that holds a file imcol did not
    write: rank 0 refuses the folder, and the job must end with exit 2 and rank 0's error line (not abort, nor leave
    the other ranks waiting). Returns the differences found."""
    with tempfile.TemporaryDirectory(prefix="imcol_mpi_refused_") as tmp:
        out = Path(tmp) / "taken"
        out.mkdir()
        (out / "notes.txt").write_text("not imcol's\n")
        p = subprocess.run([*mpi_command(a, ranks), *args, "--out", str(out)], stdout=subprocess.DEVNULL,
                           stderr=subprocess.PIPE, text=True, timeout=120)
        if p.returncode != 2 or "imcol: error: command line: key '--out'" not in p.stderr:
            return [f"a refused --out: exit {p.returncode} (expected 2), stderr {p.stderr.strip()[-400:]!r}"]
        if (out / "notes.txt").read_text() != "not imcol's\n":
            return ["a refused --out: the folder's file was changed"]
    return []


def arguments(*required):
    """The command line of an MPI test: --imcol BIN --mpirun MPIRUN and the `required` options."""
    ap = argparse.ArgumentParser()
    for name in ("--imcol", "--mpirun", *required):
        ap.add_argument(name, required=True)
    return ap.parse_args()


def report(failures):
    """Prints the failures (or ok); the test's exit status."""
    for f in failures:
        print("FAIL:", f)
    print("ok" if not failures else f"{len(failures)} failures")
    return 1 if failures else 0
