# SPDX-License-Identifier: BSD-3-Clause
"""The Python module against the command-line program on the same scenes: the same code path gives the same bits."""
import concurrent.futures
import csv
import math

import numpy as np
import pytest

import imcol
from conftest import imcol_cli

# Keys of summary.json that differ between two runs of the same scene (timings) or that only the program writes.
UNSTABLE = {"run", "wall_time_s", "setup_time_s"}


def stable(d):
    return {k: v for k, v in d.items() if k not in UNSTABLE}


def test_version_is_the_programs():
    status, out, _ = imcol_cli("--version")
    assert status == 0
    assert out.strip() == "imcol " + imcol.__version__


def test_run_default_matches_the_cli(cli_run):
    summary, trajectory_csv = cli_run("default")
    r = imcol.run(imcol.Scene.load("default"))
    assert r.e is not None and r.St is not None
    assert r.e == summary["e"]
    assert r.St == summary["St"]
    assert stable(r.to_dict()) == stable(summary)
    assert r.warnings == summary["warnings"]
    assert r.Re == summary["Re"]  # summary keys are attributes
    assert r.stats["steps"] == summary["solver"]["steps"]
    assert r.e_is == "joseph_2001"  # the default for a sphere and a wall
    assert r.measures["joseph_2001"] == r.e
    budget = r.energy_budget
    assert [p["phase"] for p in budget["phases"]] == ["approach", "contact", "rebound", "collision"]
    assert all(abs(p["closure_per_impact_energy"]) < 1e-4 for p in budget["phases"])
    assert len(r.bounces) == summary["contacts"]
    # the trajectory: the CSV's columns and rows, the values to the CSV's printed digits
    with open(trajectory_csv, newline="") as f:
        rows = list(csv.reader(f))
    assert rows[0] == r.columns == list(r.trajectory)
    assert len(rows) - 1 == len(r.trajectory["t"])
    for i, name in enumerate(rows[0]):
        col = np.array([float(row[i]) for row in rows[1:]])
        assert isinstance(r.trajectory[name], np.ndarray) and r.trajectory[name].dtype == np.float64
        np.testing.assert_allclose(r.trajectory[name], col, rtol=1e-9, atol=1e-300, err_msg=name)


def test_set_and_solver_options_match_the_cli(cli_run):
    summary, _ = cli_run("default", "--set", "fluid.viscosity=0.05", "--rtol", "1e-6", "--integrator", "ida")
    scene = imcol.Scene.load("default").set("fluid.viscosity", 0.05)
    assert scene.overrides == ["fluid.viscosity=0.05"]
    r = imcol.run(scene, rtol=1e-6, integrator="ida")
    assert r.e == summary["e"] and r.St == summary["St"]
    assert r.to_dict()["solver"]["integrator"] == "ida" and r.to_dict()["solver"]["rtol"] == 1e-6
    assert r.e != imcol.run(imcol.Scene.load("default")).e  # the key took effect


def test_repeated_solver_options_give_the_fresh_scenes_bits():
    # run(scene, rtol=…) keeps the scene it parsed for those options: the next call with the same options, with
    # others, and after set() must each give what a freshly read scene gives.
    scene = imcol.Scene.load("default")
    fresh = lambda *keys: imcol.Scene.load("default") if not keys else imcol.Scene.load("default").set(*keys)
    a = imcol.run(scene, rtol=1e-6)
    assert imcol.run(scene, rtol=1e-6).e == a.e == imcol.run(fresh("solver.rtol", 1e-6)).e
    b = imcol.run(scene, rtol=1e-7)
    assert b.e == imcol.run(fresh("solver.rtol", 1e-7)).e and b.e != a.e
    assert imcol.run(scene, rtol=1e-6).e == a.e
    scene.set("fluid.viscosity", 0.05)
    c = imcol.run(scene, rtol=1e-6)
    assert c.e == imcol.run(fresh("fluid.viscosity", 0.05), rtol=1e-6).e and c.e != a.e
    assert c.to_dict()["fluid"]["viscosity_Pa_s"] == 0.05


def test_timings_read_without_the_summary_view():
    r = imcol.run(imcol.Scene.load("default"))
    assert r.wall_time_s == r.summary.wall_time_s == r.to_dict()["wall_time_s"] > 0
    assert r.setup_time_s == r.summary.setup_time_s == r.to_dict()["setup_time_s"] >= 0


def test_from_toml_is_the_file(cli_run):
    scene = imcol.Scene.load("default")
    r_text = imcol.run(imcol.Scene.from_toml(scene.toml))
    summary, _ = cli_run("default")
    assert r_text.e == summary["e"] and r_text.St == summary["St"]


def test_kinematics_recording():
    full = imcol.run(imcol.Scene.load("default"))
    kin = imcol.run(imcol.Scene.load("default"), record="kinematics")
    assert kin.to_dict()["max_contact_force_N"] is None
    assert full.to_dict()["max_contact_force_N"] > 0
    assert kin.e == full.e


CLI_PLACE = "command line (--set/--rtol/--atol/--integrator)"


@pytest.mark.parametrize("key,value,cli", [
    ("fluid.viscosity", -1.0, "fluid.viscosity=-1"),
    ("solver.rtol", "abc", "solver.rtol=abc"),
    ("no_such_key", 1, "no_such_key=1"),
    ("sphere[0].diameter", "[1, 2]", "sphere[0].diameter=[1, 2]"),
])
def test_bad_set_has_the_clis_message(key, value, cli):
    status, _, err = imcol_cli("run", "default", "--quiet", "--no-plot", "--set", cli)
    assert status == 2
    scene = imcol.Scene.load("default")
    with pytest.raises(ValueError) as e:
        scene.set(key, value)
    # The same problem, in Python's words: the call and its key instead of the command line's options.
    assert "command line" not in str(e.value) and "--set" not in str(e.value)
    cli_prefix = f"imcol: error: {CLI_PLACE}: key '{key}': "
    assert err.strip().startswith(cli_prefix), err
    assert str(e.value) == f"Scene.set('{key}'): " + err.strip()[len(cli_prefix):]
    assert scene.overrides == []  # unchanged by a refused key


def test_unknown_scene_names_the_call_and_the_command_line_keeps_its_words():
    status, _, err = imcol_cli("run", "no_such_scene", "--quiet", "--no-plot")
    assert status == 2
    assert err.startswith("imcol: error: command line: key 'scene': no scene 'no_such_scene': no file "), err
    with pytest.raises(ValueError) as e:
        imcol.Scene.load("no_such_scene")
    assert str(e.value) == ("Scene.load: scene 'no_such_scene': no shipped scene or file of that name "
                            "(imcol.scenes() lists the shipped scenes)")


def test_toml_syntax_error_names_the_line():
    with pytest.raises(ValueError, match=r"^Scene.from_toml: <string>:2: TOML syntax error"):
        imcol.Scene.from_toml('name = "x"\n[fluid\n')


def test_bad_run_options():
    scene = imcol.Scene.load("default")
    with pytest.raises(ValueError, match=r"^imcol.run: key 'solver.rtol'"):
        imcol.run(scene, rtol=2.0)
    with pytest.raises(ValueError, match="^imcol.run: key 'solver.integrator'"):
        imcol.run(scene, integrator="euler")
    with pytest.raises(ValueError, match="^imcol.run: key 'record'"):
        imcol.run(scene, record="some")
    with pytest.raises(TypeError):
        scene.set("fluid.viscosity", object())


def test_solver_failure_is_imcol_solver_error():
    sets = ["solver.max_steps=3", 'effects=["drag","lubrication","added_mass","elastic"]']
    status, _, err = imcol_cli("run", "default", "--quiet", "--no-plot", *[a for s in sets for a in ("--set", s)])
    assert status == 3
    scene = imcol.Scene.load("default").set("solver.max_steps", 3)
    scene.set("effects", ["drag", "lubrication", "added_mass", "elastic"])
    with pytest.raises(imcol.SolverError) as e:
        imcol.run(scene)
    assert err.strip() == "imcol: solver failure: " + str(e.value)
    assert "CV_TOO_MUCH_WORK" in str(e.value)
    assert issubclass(imcol.SolverError, RuntimeError)


def test_runs_in_threads_give_the_serial_results():
    scenes = [imcol.Scene.load("default").set("sphere[0].velocity", v) for v in (0.2, 0.3, 0.4, 0.5)]
    serial = [imcol.run(s, record="kinematics").e for s in scenes]
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        threaded = [r.e for r in pool.map(lambda s: imcol.run(s, record="kinematics"), scenes)]
    assert threaded == serial
    assert all(e is not None and 0 < e < 1 and math.isfinite(e) for e in serial)
