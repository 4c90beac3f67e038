# SPDX-License-Identifier: BSD-3-Clause
"""imcol.laws against `imcol laws` on the same scene, alone and over a sweep: laws.csv cell for cell (timings
excluded)."""
import numpy as np
import pytest

import imcol
from conftest import imcol_cli
from study_tables import assert_table_equals_csv, read_csv

TIMINGS = {"cpu_time_s", "wall_time_s", "setup_time_s"}


def cli_laws(tmp_path, scene, *args):
    out = tmp_path / "laws"
    status, _, err = imcol_cli("laws", scene, "--out", str(out), "--no-plot", *args)
    assert status == 0, err
    return read_csv(out / "laws.csv")


def test_laws_of_one_scene_equal_the_command_line_cell_for_cell(tmp_path):
    header, rows = cli_laws(tmp_path, "default")
    r = imcol.laws(imcol.Scene.load("default"))
    assert r.kind == "laws"
    assert_table_equals_csv(r, header, rows, TIMINGS)
    assert list(r.law) == imcol.contact_laws()
    assert set(r.status) == {"ran"}
    assert np.all(np.isfinite(r.e)) and np.all(r.e > 0) and np.all(r.e < 1)
    assert r.info["e_is"] in imcol.e_measures()
    assert 0 < r.info["e_dry"] <= 1 and r.info["delta_ss_m"] > 0


def test_laws_over_a_sweep_equal_the_command_line_and_take_the_solver_options(tmp_path):
    values = [0.2, 0.6]
    header, rows = cli_laws(tmp_path, "default", "--laws", "ramp", "--vary", "velocity", "--from", "0.2", "--to", "0.6",
                            "--points", "2", "--spacing", "linear", "--rtol", "1e-7")
    r = imcol.laws("default", laws=["ramp"], vary="velocity", values=values, rtol=1e-7)
    assert_table_equals_csv(r, header, rows, TIMINGS)
    assert header[:3] == ["point", "velocity_m_s", "law"]
    np.testing.assert_array_equal(r.velocity_m_s, values)
    assert r.info["vary"] == "velocity" and r.info["column"] == "velocity_m_s"


def test_bad_laws_and_values_raise_value_error():
    with pytest.raises(ValueError, match="unknown law 'glue'"):
        imcol.laws("default", laws=["glue"])
    with pytest.raises(ValueError, match="needs vary"):
        imcol.laws("default", values=[0.1])
