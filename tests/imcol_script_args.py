# SPDX-License-Identifier: BSD-3-Clause
"""Shared by the test scripts that run imcol and check its output files (vtk_readback.py, vtk_fields.py): their
command line (--imcol, --data) and running imcol."""
import argparse
import subprocess
from pathlib import Path


def imcol_and_data(doc: str):
    """The imcol binary and the data folder from the command line."""
    ap = argparse.ArgumentParser(description=doc.splitlines()[0])
    ap.add_argument("--imcol", required=True)
    ap.add_argument("--data", required=True, help="the data folder (data/)")
    a = ap.parse_args()
    return a.imcol, Path(a.data)


def run(cmd, fail) -> None:
    """Runs a command; `fail(message)` with its exit code and standard error when it does not exit 0."""
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        fail(f"{' '.join(cmd)} exited {p.returncode}: {p.stderr.strip()}")
