# SPDX-License-Identifier: BSD-3-Clause
"""imcol.work_precision and imcol.validate_seed against `imcol work-precision` and `imcol validate seed` on the same
cases: their CSV files cell for cell (timings excluded), the reference and the agreement as the command gives them,
bad input refused, the GIL released while the runs go."""
import csv
import json
import math

import numpy as np
import pytest

import imcol
from conftest import imcol_cli

WP_TIMINGS = {"median_wall_ms"}
VALIDATE_TIMINGS = {"wall_time_s", "wall_time_reduced_order_s", "flow_ms_per_step"}


def read_csv_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def csv_text(value):
    """A cell as the commands write it: numbers with 12 significant digits (empty if missing), words as they are."""
    if isinstance(value, (str, np.str_)):
        return str(value)
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if math.isnan(value):
        return ""
    return format(float(value), ".12g")


def assert_table_equals_csv(result, header, rows, timings):
    assert result.columns == header
    assert len(result) == len(rows)
    for name in header:
        if name in timings:
            continue
        got = [csv_text(v) for v in result.table[name]]
        want = [row[header.index(name)] for row in rows]
        assert got == want, name


def cli_work_precision(tmp_path, scene, *args):
    out = tmp_path / "wp"
    status, _, err = imcol_cli("work-precision", scene, "--repeat", "1", "--no-plot", "--out", str(out), *args)
    assert status == 0, err
    header, rows = read_csv_rows(out / "work_precision.csv")
    return header, rows, json.loads((out / "work_precision.json").read_text())


def test_work_precision_equals_the_command_line_cell_for_cell(tmp_path):
    args = ("--rtols", "1e-4,1e-6", "--integrators", "cvode-dense,ida", "--evaluators", "soe-step,soe")
    header, rows, js = cli_work_precision(tmp_path, "default", *args)
    r = imcol.work_precision("default", rtols=[1e-4, 1e-6], integrators=["cvode-dense", "ida"], evaluators=["soe-step", "soe"],
                             repeat=1)
    assert_table_equals_csv(r, header, rows, WP_TIMINGS)
    assert len(r) == 8 and list(r.status) == ["ok"] * 8
    assert r.metric == "e" and r.scene == js["scene"]
    assert r.reference["value"] == js["reference"]["value"]
    assert r.reference["uncertainty"] == js["reference"]["uncertainty"]
    assert r.reference["solver"]["steps"] == js["reference"]["solver"]["steps"]
    assert r.observed_order == {k: {**v} for k, v in js["observed_order"].items()}
    assert r.median_wall_ms.dtype == np.float64 and r.steps.dtype == np.int64
    assert np.all(r.err_e < 1e-2) and np.all(r.err_e[1::2] < r.err_e[0::2])  # a tighter rtol, a smaller error
    assert set(r.cheapest) == {1e-3, 1e-6, 1e-9}


def test_failed_rungs_are_rows_as_in_the_command_line(tmp_path):
    args = ("--rtols", "1e-3,1e-6", "--ref-rtol", "1e-4", "--integrators", "cvode-dense", "--evaluators", "soe-step,soe",
            "--set", "solver.max_steps=100")
    header, rows, _ = cli_work_precision(tmp_path, "gg3462", *args)
    scene = imcol.Scene.load("gg3462").set("solver.max_steps", 100)
    r = imcol.work_precision(scene, rtols=[1e-3, 1e-6], ref_rtol=1e-4, integrators=["cvode-dense"], evaluators=["soe-step", "soe"],
                             repeat=1)
    assert_table_equals_csv(r, header, rows, WP_TIMINGS)
    assert "failed" in list(r.status)
    failed = [m for s, m in zip(r.status, r.message) if s == "failed"]
    assert all(m.startswith("solver failure: ") for m in failed)


def test_validate_seed_equals_the_command_line_cell_for_cell(tmp_path):
    out = tmp_path / "val"
    status, _, err = imcol_cli("validate", "seed", "--models", "seed", "--no-plot", "--out", str(out))
    assert status == 0, err
    header, rows = read_csv_rows(out / "validate_seed.csv")
    r = imcol.validate_seed(models=["seed"], jobs=2)
    assert_table_equals_csv(r, header, rows, VALIDATE_TIMINGS)
    assert set(r.speed_set) == {"V_Io", "St_B"} and set(r.model) == {"seed"}
    assert not r.flow and r.tolerance == 0.05
    within = sum(1 for e, seed in zip(r.e[r.speed_set == "V_Io"], r.e_seed[r.speed_set == "V_Io"]) if abs(e - float(seed)) <= 0.05)
    at_V = next(a for a in r.agreement if a["speed_set"] == "V_Io")
    assert at_V["within"] == within and at_V["runs"] == len(r) // 2


def test_bad_input_raises_value_error_before_anything_runs():
    with pytest.raises(ValueError, match="each tolerance must lie in"):
        imcol.work_precision("default", rtols=[2.0])
    with pytest.raises(ValueError, match="unknown integrator"):
        imcol.work_precision("default", integrators=["lsoda"])
    with pytest.raises(ValueError, match="no history effect"):
        imcol.work_precision("dry_steel_steel", evaluators=["soe"])
    with pytest.raises(ValueError, match="coupled scene"):
        imcol.work_precision("coupled/gg3462")
    with pytest.raises(ValueError, match="unknown model 'wall'"):
        imcol.validate_seed(models=["wall"])
    with pytest.raises(ValueError, match=r"^imcol.validate_seed: key 'tolerance': must be a positive number"):
        imcol.validate_seed(tolerance=-1)


def ticks_while_study_runs(work):
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


def test_the_gil_is_released_while_the_runs_go():
    out = {}
    ticks = ticks_while_study_runs(lambda: out.setdefault("wp", imcol.work_precision(
        "default", rtols=[1e-4, 1e-6, 1e-8], integrators=["cvode-dense", "ida"], evaluators=["soe"], repeat=2)))
    assert len(out["wp"]) == 6
    assert ticks > 20
    ticks = ticks_while_study_runs(lambda: out.setdefault("val", imcol.validate_seed(jobs=1)))
    assert len(out["val"]) == 24
    assert ticks > 20
