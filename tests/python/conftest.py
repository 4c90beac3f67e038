# SPDX-License-Identifier: BSD-3-Clause
"""Shared helpers of the Python module's tests: the imcol program built beside the module (IMCOL_BINARY, else
build/bin/imcol) and runs of it for comparison."""
import json
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
IMCOL = os.environ.get("IMCOL_BINARY", str(ROOT / "build" / "bin" / "imcol"))


def imcol_cli(*args):
    """Runs the command-line program: (exit status, stdout, stderr)."""
    p = subprocess.run([IMCOL, *args], capture_output=True, text=True, timeout=300)
    return p.returncode, p.stdout, p.stderr


@pytest.fixture
def cli_run(tmp_path):
    """`imcol run SCENE --out DIR ARGS…`: summary.json as a dict and the trajectory.csv's path."""
    def run(scene, *args):
        out = tmp_path / "out"
        status, _, err = imcol_cli("run", scene, "--out", str(out), "--quiet", "--no-plot", *args)
        assert status == 0, err
        return json.loads((out / "summary.json").read_text()), out / "trajectory.csv"
    return run
