# SPDX-License-Identifier: BSD-3-Clause
"""imcol.history_compare against `imcol history` on the same scene, alone and over a sweep (--vary): history.csv and
history_sweep.csv cell for cell (timings excluded)."""
import numpy as np
import pytest

import imcol
from conftest import imcol_cli
from study_tables import assert_table_equals_csv, read_csv

TIMINGS = {"wall_time_s", "setup_time_s"}


def cli_history(tmp_path, scene, *args):
    out = tmp_path / "history"
    status, _, err = imcol_cli("history", scene, "--out", str(out), "--no-plot", *args)
    assert status == 0, err
    return out


def test_history_of_one_scene_equals_the_command_line_cell_for_cell(tmp_path):
    out = cli_history(tmp_path, "default", "--kernels", "basset,mei-adrian", "--evaluators", "soe,direct")
    header, rows = read_csv(out / "history.csv")
    r = imcol.history_compare("default", kernels=["basset", "mei-adrian"], evaluators=["soe", "direct"])
    assert r.kind == "history" and r.info["collision"]
    assert_table_equals_csv(r, header, rows, TIMINGS)
    assert list(r.kernel) == ["none", "basset", "basset", "mei-adrian", "mei-adrian"]
    assert np.isnan(r.diff_from_reference[0]) and r.diff_from_reference[2] == 0  # direct against itself


def test_history_over_a_sweep_equals_the_command_line_cell_for_cell(tmp_path):
    out = cli_history(tmp_path, "default", "--kernels", "basset", "--vary", "velocity", "--from", "0.1", "--to", "1",
                      "--points", "3", "--jobs", "2", "--no-progress")
    header, rows = read_csv(out / "history_sweep.csv")
    values = [0.1 * 10 ** (i / 2) for i in range(3)]
    r = imcol.history_compare(imcol.Scene.load("default"), kernels=["basset"], vary="velocity", values=values, jobs=2)
    assert r.kind == "history_sweep"
    assert_table_equals_csv(r, header, rows, {"wall_time_s"})
    assert list(r.kernel) == ["none", "basset"] * 3
    assert set(r.status) == {"ok"}


def test_bad_history_input_raises_value_error():
    with pytest.raises(ValueError, match="unknown kernel"):
        imcol.history_compare("default", kernels=["nope"])
    with pytest.raises(ValueError, match="needs vary"):
        imcol.history_compare("default", values=[0.1])
    with pytest.raises(ValueError, match=r"\[fluid\]"):
        imcol.history_compare("dry_steel_steel")
