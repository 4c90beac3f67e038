# SPDX-License-Identifier: BSD-3-Clause
"""The examples in examples/python: each runs as a script (`--out DIR`), exits 0, draws its picture, and a value it
plotted (written beside the picture as JSON) equals what the command line gives on the same scene."""
import json
import os
import pathlib
import subprocess
import sys

import pytest

import imcol
from conftest import ROOT, imcol_cli

EXAMPLES = ROOT / "examples" / "python"
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def example(tmp_path_factory):
    """Runs examples/python/NAME.py once into its own folder: the JSON it wrote beside NAME.png, as a dict."""
    done = {}

    def run(name):
        if name not in done:
            out = tmp_path_factory.mktemp(name)
            env = dict(os.environ)  # the module this test imports, for the script too
            env["PYTHONPATH"] = os.pathsep.join(
                [str(pathlib.Path(imcol.__file__).resolve().parents[1]), env.get("PYTHONPATH", "")])
            p = subprocess.run([sys.executable, str(EXAMPLES / f"{name}.py"), "--out", str(out)], env=env,
                               capture_output=True, text=True, timeout=300)
            assert p.returncode == 0, p.stderr
            png = (out / f"{name}.png").read_bytes()
            assert png.startswith(PNG_MAGIC) and len(png) > 20000, f"{name}.png: {len(png)} bytes"
            done[name] = json.loads((out / f"{name}.json").read_text())
        return done[name]

    return run


def set_options(settings):
    """{key: value} as the command line's --set options (values as TOML: strings quoted)."""
    return [a for k, v in settings.items() for a in ("--set", f"{k}={json.dumps(v)}")]


def csv_table(path):
    """A CSV file without its '#' lines: (header, rows of cells)."""
    lines = [l for l in path.read_text().splitlines() if l and not l.startswith("#")]
    return lines[0].split(","), [l.split(",") for l in lines[1:]]


def csv_column(path, name):
    header, rows = csv_table(path)
    return [float(r[header.index(name)]) for r in rows]


def cell(x):
    """A number as the CSV files write it (12 significant digits); '' for none."""
    return "" if x is None else format(x, ".12g")


def cli_sweep_point(tmp_path, scene, velocity, settings):
    """One point of `imcol sweep SCENE --vary velocity` at exactly `velocity`: its sweep.csv row by column name."""
    out = tmp_path / "sweep"
    status, _, err = imcol_cli("sweep", scene, "--vary", "velocity", "--from", repr(velocity), "--to", repr(velocity),
                               "--points", "1", "--jobs", "1", "--out", str(out), "--no-plot", "--no-progress",
                               *set_options(settings))
    assert status == 0, err
    header, rows = csv_table(out / "sweep.csv")
    assert len(rows) == 1
    return dict(zip(header, rows[0]))


def test_every_example_is_checked_below():
    assert sorted(p.stem for p in EXAMPLES.glob("*.py")) == ["coupled_forces", "history_kernels",
                                                            "restitution_vs_stokes", "trajectory_forces"]


def test_trajectory_forces_equal_imcol_run(example, cli_run):
    got = example("trajectory_forces")
    summary, trajectory = cli_run(got["scene"], *set_options(got["set"]))
    assert (got["e"], got["St"], got["min_gap_m"]) == (summary["e"], summary["St"], summary["min_gap_m"])
    assert got["rows"] == len(csv_column(trajectory, "t"))
    assert sorted(got["max_abs_force_N"]) == sorted(c for c in csv_table(trajectory)[0] if c.startswith("f_"))
    for column, peak in got["max_abs_force_N"].items():
        assert cell(peak) == cell(max(abs(x) for x in csv_column(trajectory, column))), column
    assert got["max_abs_force_N"]["f_contact1"] > 10  # N: the contact was in the window the example drew


def test_coupled_forces_equal_imcol_run(example, cli_run):
    got = example("coupled_forces")
    summary, trajectory = cli_run(got["scene"], *set_options(got["set"]))
    assert summary["flow"]["grid"]["cells_per_diameter"] == got["set"]["flow.cells_per_diameter"]
    assert (got["e"], got["St"], got["flow_steps"]) == (summary["e"], summary["St"], summary["flow"]["steps"])
    assert got["rows"] == len(csv_column(trajectory, "t"))
    for column in ("f_sim1", "f_thr1"):
        assert cell(got[f"max_abs_{column}_N"]) == cell(max(abs(x) for x in csv_column(trajectory, column)))
    assert max(csv_column(trajectory, "H")) > 0.99  # the blend reached the analytic forces at contact


def test_history_kernels_list_and_values_equal_the_cli(example, cli_run):
    got = example("history_kernels")
    status, _, err = imcol_cli("run", "default", "--set", "history.kernel=\"?\"", "--quiet", "--no-plot")
    assert status == 2
    assert list(got["kernels"]) == err.strip().rsplit("(expected ", 1)[1].rstrip(")").split(" | ")
    speeds = got["velocity_m_s"]
    for kernel, point in (("basset", 0), (list(got["kernels"])[-1], len(speeds) - 1)):
        summary, _ = cli_run(got["scene"], *set_options({"history.kernel": kernel,
                                                        "sphere[0].velocity": speeds[point]}))
        assert (got["kernels"][kernel]["e"][point], got["kernels"][kernel]["St"][point]) == (summary["e"],
                                                                                            summary["St"]), kernel


def test_restitution_vs_stokes_equals_imcol_sweep(example, tmp_path):
    got = example("restitution_vs_stokes")
    wall, pair = got["wall"], got["pair"]
    assert set(wall["status"]) == {"ok"} and set(pair["status"]) == {"ok"}
    assert max(pair["e"]) > 0.8 and min(pair["e"]) == 0  # the curve spans e = 0 to the elastic end
    # The pair's two conventions: eq. (6.2) is twice Table 6.1's, which is imcol's St.
    for st, t61, e62 in zip(pair["St"], pair["St_B_table_6_1"], pair["St_B_eq_6_2"]):
        assert t61 == st and e62 == pytest.approx(2 * st, rel=1e-12)
    for curve, columns in ((wall, ("St", "e")), (pair, ("St", "St_B_table_6_1", "St_B_eq_6_2", "e"))):
        i = len(curve["velocity_m_s"]) // 2
        row = cli_sweep_point(tmp_path / curve["scene"], curve["scene"], curve["velocity_m_s"][i], curve["set"])
        assert row["status"] == curve["status"][i]
        for c in columns:
            assert cell(curve[c][i]) == row[c], (curve["scene"], c)
