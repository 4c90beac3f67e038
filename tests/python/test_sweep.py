# SPDX-License-Identifier: BSD-3-Clause
"""imcol.sweep against `imcol sweep` on the same scenes: sweep.csv cell for cell (timings excluded), failed points
reported, bad input refused with the command line's message."""
import csv
import math

import numpy as np
import pytest

import imcol
from conftest import imcol_cli

TIMINGS = {"wall_time_s"}


def cli_sweep(tmp_path, scene, vary, start, stop, points, *extra):
    """`imcol sweep` with a range: (exit status, stderr, header, rows as lists of cells)."""
    out = tmp_path / "cli"
    status, _, err = imcol_cli("sweep", scene, "--vary", vary, "--from", repr(start), "--to", repr(stop), "--points",
                               str(points), "--jobs", "2", "--out", str(out), "--no-plot", "--no-progress", *extra)
    with open(out / "sweep.csv", newline="") as f:
        rows = list(csv.reader(f))
    return status, err, rows[0], rows[1:]


def log_values(start, stop, points):
    """The values `--from --to --points` gives (log spacing), computed as the program does."""
    return [start * (stop / start) ** (0.0 if points == 1 else i / (points - 1)) for i in range(points)]


def cell(value):
    """A number as sweep.csv writes it (12 significant digits; empty for a missing value)."""
    if isinstance(value, str):
        return value.replace(",", ";").replace("\n", ";")
    if isinstance(value, (float, np.floating)) and math.isnan(value):
        return ""
    return format(float(value), ".12g") if isinstance(value, (float, np.floating)) else str(value)


def assert_same_as_csv(result, header, rows):
    assert result.columns == header
    assert len(result) == len(rows)
    for name in header:
        if name in TIMINGS:
            continue
        got = [cell(v) for v in result.table[name]]
        want = [row[header.index(name)] for row in rows]
        assert got == want, name


@pytest.mark.parametrize("scene,extra", [("default", ()), ("seed_run3", ())])
def test_sweep_equals_the_command_line_cell_for_cell(tmp_path, scene, extra):
    start, stop, n = 0.05, 1.0, 6
    status, err, header, rows = cli_sweep(tmp_path, scene, "velocity", start, stop, n, *extra)
    assert status == 0, err
    r = imcol.sweep(imcol.Scene.load(scene), vary="velocity", values=np.array(log_values(start, stop, n)), jobs=2)
    assert_same_as_csv(r, header, rows)
    assert list(r.status) == ["ok"] * n
    assert r.values.dtype == np.float64 and r.St.dtype == np.float64
    assert np.all(np.diff(r.St) > 0)
    assert r.vary == "velocity" and r.column == "velocity_m_s"
    np.testing.assert_array_equal(r.values, log_values(start, stop, n))
    np.testing.assert_array_equal(r.to_dict()["e"], r.e)
    if scene == "seed_run3":  # a pair: its other Stokes numbers too
        assert np.all(np.isfinite(r.St_B_eq_6_2)) and np.all(np.isfinite(r.table["St_B_table_6_1"]))


def test_sweep_takes_keys_set_and_solver_options_as_the_command_line(tmp_path):
    start, stop, n = 0.2, 2.0, 3
    status, err, header, rows = cli_sweep(tmp_path, "default", "viscosity", start, stop, n, "--set", "sphere[0].velocity=0.5",
                                          "--rtol", "1e-7")
    assert status == 0, err
    scene = imcol.Scene.load("default").set("sphere[0].velocity", 0.5)
    r = imcol.sweep(scene, vary="viscosity", values=log_values(start, stop, n), rtol=1e-7, jobs=1)
    assert_same_as_csv(r, header, rows)


def test_a_failed_point_is_reported_not_raised(tmp_path):
    # The very viscous point needs < 50 steps between samples, the least viscous > 80: with 70 allowed, one fails.
    effects = '["drag","lubrication","added_mass","elastic"]'
    args = ("--set", "solver.max_steps=70", "--set", "effects=" + effects)
    status, err, header, rows = cli_sweep(tmp_path, "gg3462", "viscosity", 0.001, 0.1, 2, *args)
    assert status == 3, err
    scene = imcol.Scene.load("gg3462").set("solver.max_steps", 70).set("effects", effects)
    r = imcol.sweep(scene, vary="viscosity", values=log_values(0.001, 0.1, 2))
    assert_same_as_csv(r, header, rows)
    assert list(r.status) == ["failed", "ok"]
    assert "CV_TOO_MUCH_WORK" in r.messages[0]
    assert math.isnan(r.St[0]) and math.isnan(r.e[0]) and math.isfinite(r.e[1])


def cli_error(*args):
    """The command line's one-line message for bad input, without its prefix and place."""
    status, _, err = imcol_cli("sweep", "default", *args, "--no-plot")
    assert status == 2, err
    return err.strip().split("': ", 1)[1]


def test_bad_vary_and_bad_values_raise_value_error_with_the_command_lines_message():
    scene = imcol.Scene.load("default")
    with pytest.raises(ValueError) as bad:
        imcol.sweep(scene, vary="speed", values=[0.1, 0.2])
    assert str(bad.value) == "imcol.sweep: key 'vary': " + cli_error("--vary", "speed", "--from", "0.1", "--to", "1", "--points", "2")
    for bad_value in (-0.5, 0.0, float("nan"), float("inf")):
        with pytest.raises(ValueError, match=r"^imcol.sweep: key 'values': sweep point 1 \(velocity = .*\): must be a positive number$"):
            imcol.sweep(scene, values=[0.3, bad_value, 0.5])
    with pytest.raises(ValueError, match="must hold 1 to 100000 values"):
        imcol.sweep(scene, values=[])
    with pytest.raises(ValueError, match="one-dimensional"):
        imcol.sweep(scene, values=[[0.1, 0.2]])
    # A point whose scene is bad names the point, before anything runs (as imcol sweep does).
    message = cli_error("--vary", "diameter", "--from", "1e-3", "--to", "1e3", "--points", "2")
    with pytest.raises(ValueError) as bad:
        imcol.sweep(scene, vary="diameter", values=[1e-3, 1e3])
    assert str(bad.value).split("': ", 1)[1] == message
    assert message.startswith("sweep point 1 (diameter = 1000): t_end / output.dt = ")  # the place said once, first
    assert str(bad.value).count("default.toml") == 1
    # No [fluid]: no viscosity sweep.
    dry = imcol.Scene.load("dry_steel_steel")
    status, _, err = imcol_cli("sweep", "dry_steel_steel", "--vary", "viscosity", "--from", "0.1", "--to", "1", "--points", "2", "--no-plot")
    assert status == 2
    with pytest.raises(ValueError) as bad:
        imcol.sweep(dry, vary="viscosity", values=[0.1, 1.0])
    assert str(bad.value) == "imcol.sweep: " + err.strip().removeprefix("imcol: error: ")


def ticks_while(work):
    """Runs work() in another thread; returns how often this thread woke (every 1 ms) until it ended. With the GIL
    held by work() this thread would not run at all until the end."""
    import threading
    done, ticks = threading.Event(), [0]

    def run():
        try:
            work()
        finally:
            done.set()

    t = threading.Thread(target=run)
    t.start()
    while not done.is_set():
        ticks[0] += 1
        done.wait(0.001)
    t.join()
    return ticks[0]


def test_the_gil_is_released_while_the_points_run():
    out = {}
    ticks = ticks_while(lambda: out.setdefault("r", imcol.sweep("default", values=log_values(0.05, 1.0, 40), jobs=1)))
    assert list(out["r"].status) == ["ok"] * 40
    assert ticks > 20


def test_the_gil_is_released_while_the_points_scenes_are_read():
    # Reading 2000 points' scenes takes a tenth of a second or more. The last point is bad, so the sweep stops
    # (ValueError) before anything runs: only the reading is timed.
    out = {}

    def read():
        try:
            imcol.sweep("default", vary="diameter", values=[1e-3] * 1999 + [1e3])
        except ValueError as e:
            out["error"] = str(e)

    ticks = ticks_while(read)
    assert "sweep point 1999 (diameter = 1000)" in out["error"]
    assert ticks > 20
