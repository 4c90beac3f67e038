# SPDX-License-Identifier: BSD-3-Clause
"""The module's first use of NumPy from several threads at once, each case in a fresh interpreter (NumPy not yet
imported by the script), with a timeout: a deadlock fails the test instead of hanging it. And without NumPy: the
package's import fails saying which interpreter lacks it and how to get it; the extension alone imports and runs, and
only what returns arrays raises ImportError saying so."""
import json
import os
import pathlib
import subprocess
import sys
import textwrap

import pytest

import imcol

PACKAGE_DIR = str(pathlib.Path(imcol.__file__).resolve().parents[1])  # the imcol this test imported
ROUNDS = 4  # fresh interpreters per case: the race is lost at random


def run_fresh(code, timeout=60):
    """Runs `code` in a fresh interpreter that imports this imcol: its last stdout line as JSON."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([PACKAGE_DIR, os.environ.get("PYTHONPATH", "")]))
    try:
        p = subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True,
                           timeout=timeout, env=env)
    except subprocess.TimeoutExpired:
        pytest.fail(f"the interpreter hung (no exit in {timeout} s): a deadlock")
    assert p.returncode == 0, p.stderr[-3000:]
    return json.loads(p.stdout.strip().splitlines()[-1])


# Two threads run, meet at a barrier, then read their first trajectory at the same moment.
FIRST_TRAJECTORIES = """
    import concurrent.futures, json, sys, threading
    import imcol
    barrier = threading.Barrier(2)
    def last_u1(v):
        r = imcol.run(imcol.Scene.load("default").set("sphere[0].velocity", v))
        barrier.wait()
        return float(r.trajectory["u1"][-1])
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        print(json.dumps(list(pool.map(last_u1, [0.1, 0.2]))))
"""

# The audit's reproducer: four runs on two workers, each reading its trajectory.
REPRODUCER = """
    import concurrent.futures, json
    import imcol
    p = concurrent.futures.ThreadPoolExecutor(2)
    f = lambda v: float(imcol.run(imcol.Scene.load("default").set("sphere[0].velocity", v)).trajectory["u1"][-1])
    print(json.dumps(list(p.map(f, [0.1, 0.2, 0.3, 0.4]))))
"""

# One thread reads a trajectory while another sweeps (which imports NumPy and makes arrays too).
TRAJECTORY_AND_SWEEP = """
    import concurrent.futures, json, threading
    import imcol
    barrier = threading.Barrier(2)
    def trajectory():
        r = imcol.run(imcol.Scene.load("default"))
        barrier.wait()
        return float(r.trajectory["u1"][0])
    def sweep():
        barrier.wait()
        return float(imcol.sweep("default", values=[0.3], jobs=1).values[0])
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        a, b = pool.submit(trajectory), pool.submit(sweep)
        print(json.dumps([a.result(), b.result()]))
"""


def test_first_trajectories_in_two_threads_at_once():
    for _ in range(ROUNDS):
        u = run_fresh(FIRST_TRAJECTORIES)
        assert u == [float(imcol.run(imcol.Scene.load("default").set("sphere[0].velocity", v)).trajectory["u1"][-1])
                     for v in (0.1, 0.2)]


def test_the_audits_reproducer_ends():
    expected = [float(imcol.run(imcol.Scene.load("default").set("sphere[0].velocity", v)).trajectory["u1"][-1])
                for v in (0.1, 0.2, 0.3, 0.4)]
    for _ in range(ROUNDS):
        assert run_fresh(REPRODUCER) == expected


def test_first_trajectory_beside_a_first_sweep():
    for _ in range(ROUNDS):
        assert run_fresh(TRAJECTORY_AND_SWEEP) == [0.3, 0.3]


def test_without_numpy_the_package_names_the_interpreter_and_the_fix():
    out = run_fresh("""
        import json, sys
        sys.modules["numpy"] = None  # `import numpy` raises ImportError
        try:
            import imcol
            print(json.dumps({"imported": True}))
        except ImportError as e:
            print(json.dumps({"error": str(e), "python": sys.executable}))
    """)
    assert "error" in out, out
    assert out["error"].startswith(f"imcol needs NumPy, which {out['python']} cannot import (")
    assert "apt-get install python3-numpy" in out["error"]
    assert "--system-site-packages" in out["error"]


def test_without_numpy_the_extension_runs_and_arrays_say_what_they_need():
    extension = next(pathlib.Path(imcol.__file__).parent.glob("_imcol*.so"))
    out = run_fresh(f"""
        import importlib.machinery, importlib.util, json, sys
        sys.modules["numpy"] = None  # `import numpy` raises ImportError
        spec = importlib.util.spec_from_file_location("_imcol", {str(extension)!r})
        ext = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(ext)
        r = ext.run(ext.Scene.load("default"))
        found = {{"e": r.e, "columns": r.columns[:2]}}
        for name, call in [("trajectory", lambda: r.trajectory), ("sweep", lambda: ext.sweep("default", values=[0.3]))]:
            try:
                call()
                found[name] = "returned"
            except ImportError as e:
                found[name] = str(e)
        print(json.dumps(found))
    """)
    assert out["e"] == imcol.run(imcol.Scene.load("default")).e
    assert out["columns"] == ["t", "z1"]
    assert out["trajectory"].startswith("imcol.Result.trajectory needs NumPy, which could not be imported (")
    assert out["sweep"].startswith("imcol.sweep needs NumPy, which could not be imported (")
