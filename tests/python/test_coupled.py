# SPDX-License-Identifier: BSD-3-Clause
"""Coupled runs (the flow effect) from Python against `imcol run` of the same scene, on a coarse grid."""
import csv

import numpy as np
import pytest

import imcol

COARSE = 8  # flow.cells_per_diameter: a run in a fraction of a second

# Keys that differ between two runs of one scene: timings (and the program's own `run` block).
TIMINGS = {"run", "wall_time_s", "setup_time_s"}
FLOW_TIMINGS = {"ms_per_step", "start_up_time_s", "flow_time_s", "ode_time_s", "flow_share", "ode_share", "fields_time_s", "cpu_time_s"}


def without_timings(summary):
    d = {k: v for k, v in summary.items() if k not in TIMINGS}
    d["flow"] = {k: v for k, v in summary["flow"].items() if k not in FLOW_TIMINGS}
    return d


@pytest.mark.parametrize("name", ["coupled/gg3462", "coupled/gondret_st27"])
def test_coarse_coupled_run_is_the_clis(name, cli_run):
    scene = imcol.Scene.load(name).set("flow.cells_per_diameter", COARSE)
    r = imcol.run(scene)
    summary, trajectory_csv = cli_run(name, "--set", f"flow.cells_per_diameter={COARSE}")
    assert r.e is not None
    assert r.e == summary["e"] and r.St == summary["St"]
    assert r.stats["steps"] == summary["solver"]["steps"]
    d = r.to_dict()
    assert d["flow"]["grid"]["cells_per_diameter"] == COARSE
    assert d["flow"]["steps"] == summary["flow"]["steps"] > 0
    # The program writes the flow fields (flow.fields = true); a Python run keeps none, so computes none.
    assert summary["flow"]["field_snapshots"] > 0
    assert d["flow"]["field_snapshots"] == 0 and d["flow"]["fields_time_s"] == 0
    expected = without_timings(summary)
    expected["flow"]["field_snapshots"] = 0
    # ... and its cost estimate counts none: the program's total less its fields_s
    est = expected["flow"]["estimate"]
    assert est["fields_s"] > 0 and d["flow"]["estimate"]["fields_s"] == 0
    assert d["flow"]["estimate"]["total_s"] == pytest.approx(est["total_s"] - est["fields_s"], rel=1e-12)
    assert est["field_snapshots"] > 0 and d["flow"]["estimate"]["field_snapshots"] == 0
    est["total_s"], est["fields_s"], est["field_snapshots"] = d["flow"]["estimate"]["total_s"], 0, 0
    assert without_timings(d) == expected

    # the trajectory, f_SIM and f_THR included, to the CSV's printed digits
    with open(trajectory_csv, newline="") as f:
        rows = list(csv.reader(f))
    assert rows[0] == r.columns
    assert {"f_sim1", "f_thr1"} <= set(r.columns)
    assert len(rows) - 1 == len(r.trajectory["t"])
    for i, col in enumerate(rows[0]):
        cli = np.array([float(row[i]) for row in rows[1:]])
        np.testing.assert_allclose(r.trajectory[col], cli, rtol=1e-9, atol=1e-300, err_msg=col)
    assert np.any(r.trajectory["f_sim1"] != 0) and np.any(r.trajectory["f_thr1"] != 0)


def test_a_coupled_run_without_fields_is_the_clis(cli_run):
    # With flow.fields = false the program computes none either: the whole summary agrees but for timings.
    scene = imcol.Scene.load("coupled/gg3462").set("flow.cells_per_diameter", COARSE).set("flow.fields", False)
    summary, _ = cli_run("coupled/gg3462", "--set", f"flow.cells_per_diameter={COARSE}", "--set", "flow.fields=false")
    assert without_timings(imcol.run(scene).to_dict()) == without_timings(summary)
