# SPDX-License-Identifier: BSD-3-Clause
"""No Python call can crash the interpreter: hostile calls (wrong types, None, NaN and inf, huge values, empty TOML,
bad solver options, solver failures, a Result outliving its Scene, runs from 16 threads) in a subprocess, each
raising the Python exception it should, and the subprocess exiting 0."""
import json
import os
import pathlib
import subprocess
import sys

import imcol

HERE = pathlib.Path(__file__).resolve().parent


def test_hostile_calls_raise_and_the_interpreter_lives():
    package_dir = str(pathlib.Path(imcol.__file__).resolve().parents[1])  # the imcol this test imported
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([package_dir, os.environ.get("PYTHONPATH", "")]))
    p = subprocess.run([sys.executable, str(HERE / "hostile_calls.py")], capture_output=True, text=True, timeout=240,
                       env=env, cwd=HERE)
    assert p.returncode == 0, f"exit status {p.returncode}\n{p.stderr[-3000:]}"
    out = json.loads(p.stdout.strip().splitlines()[-1])
    found, expected = out["found"], out["expected"]
    assert len(found) == len(expected) > 50
    wrong = {k: (found[k], expected[k]) for k in expected if found.get(k) != expected[k]}
    assert not wrong, wrong
