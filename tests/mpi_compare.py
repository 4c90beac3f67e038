# SPDX-License-Identifier: BSD-3-Clause
"""What the MPI tests (tests/mpi_*.py) share: the command of an MPI job, and the cell-for-cell comparison of a CSV
that one process wrote with the one the MPI job wrote."""
import csv


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
