# SPDX-License-Identifier: BSD-3-Clause
"""imcol.calibrate against `imcol calibrate` with the same inputs (a trajectory, and an e table with its hold-out): the
fitted values, intervals and validation, and calibration.csv cell for cell (timings excluded); progress after every
evaluation; a progress callback that raises stops the search (Ctrl-C: test_interrupt.py)."""
import csv
import json
import math
import pathlib
import time

import numpy as np
import pytest

import imcol
from conftest import ROOT, imcol_cli

DATA = ROOT / "data" / "measurements" / "gg3462_trajectory.csv"
FIT = "contact.delta_ss=0.005:0.05"
SEARCH = {"scan": 4, "starts": 1, "max_evals": 6, "profile_points": 3, "refine": 2}
TIMINGS = {"wall_ms"}
EXACT = {"contact.delta_ss"}  # parameter values: 17 digits, the same double


def cli_calibrate(out, data, search, *extra):
    args = ["calibrate", "gg3462", "--data", str(data), "--fit", FIT, "--jobs", "2", "--out", str(out), "--no-plot",
            "--no-progress"]
    for name, value in search.items():
        args += ["--" + name.replace("_", "-"), str(value)]
    status, stdout, err = imcol_cli(*args, *extra)
    assert status == 0, err
    with open(out / "calibration.csv", newline="") as f:
        rows = list(csv.reader(f))
    return json.loads((out / "calibration.json").read_text()), rows[0], rows[1:], stdout


def cell(value):
    """A value as calibration.csv writes it (12 significant digits; empty for a missing value)."""
    if isinstance(value, (str, np.str_)):
        return str(value)
    if isinstance(value, (float, np.floating)):
        return "" if math.isnan(value) else format(float(value), ".12g")
    return str(value)


def assert_same_as_csv(r, header, rows):
    assert list(r.evaluations) == header
    assert r.count == len(rows)
    for name in header:
        if name in TIMINGS:
            continue
        column = [row[header.index(name)] for row in rows]
        if name in EXACT:
            assert [float(c) for c in column] == list(r.evaluations[name]), name
        else:
            assert [cell(v) for v in r.evaluations[name]] == column, name


def test_trajectory_fit_equals_the_command_line(tmp_path):
    j, header, rows, stdout = cli_calibrate(tmp_path / "cli", DATA, SEARCH)
    r = imcol.calibrate("gg3462", DATA, FIT, jobs=2, **SEARCH)
    assert_same_as_csv(r, header, rows)
    assert r.count == j["evaluations"]["count"]
    assert r.values == j["best"]["values"]
    assert r.objective == j["best"]["objective"] and r.rms == j["best"]["rms"] and r.tau_s == j["best"]["tau_s"]
    interval = j["profiles"][0]["interval"]
    assert r.intervals["contact.delta_ss"] == (interval["lo"], interval["hi"])
    assert list(r.profiles["contact.delta_ss"]["values"]) == j["profiles"][0]["values"]
    assert r.factor_rule["factor"] == j["profiles"][0]["factor"]
    assert r.start == {"contact.delta_ss": j["parameters"][0]["start"]}
    assert not r.cancelled and r.ok and r.kind == "trajectory" and r.failed == j["evaluations"]["failed"]
    assert "contact.delta_ss = %.6g" % r.values["contact.delta_ss"] in stdout


def test_table_fit_and_its_validation_equal_the_command_line(tmp_path):
    table = ROOT / "data" / "measurements" / "gg3462_e_table.csv"
    held = ROOT / "data" / "measurements" / "gg3462_e_table_holdout.csv"
    search = {"scan": 2, "starts": 1, "max_evals": 4, "profile_points": 0}
    j, header, rows, _ = cli_calibrate(tmp_path / "cli", table, search, "--validate", str(held))
    r = imcol.calibrate("gg3462", table, FIT, validate=held, jobs=2, **search)
    assert_same_as_csv(r, header, rows)
    assert r.kind == "table" and r.values == j["best"]["values"] and r.tau_s is None and r.intervals == {}
    assert r.validation["rms"] == j["validation"]["rms"]
    assert r.validation["e_sim"] == [row["e_sim"] for row in j["validation"]["by_row"]]


def test_result_is_typed_and_printable():
    r = imcol.calibrate(imcol.Scene.load("gg3462"), str(DATA), {"contact.delta_ss": (0.005, 0.05)}, scan=2, starts=1,
                        max_evals=3, profile_points=0, jobs=2)
    for name in ("values", "intervals", "evaluations", "rms", "tau_s", "count", "cancelled", "to_dict"):
        assert name in dir(r)
    d = r.to_dict()
    assert d["values"] == r.values and d["count"] == r.count and d["cancelled"] is False
    assert repr(r).startswith("imcol.CalibrationResult(values={'contact.delta_ss': ")
    assert r.intervals == {} and r.validation is None


def test_progress_follows_the_evaluations():
    calls = []
    r = imcol.calibrate("gg3462", DATA, FIT, scan=2, starts=1, max_evals=3, profile_points=0, jobs=2,
                        progress=lambda done, total, eta: calls.append((done, total, eta)))
    done = [c[0] for c in calls]
    assert calls and done == sorted(done)  # sampled while it runs (python/interrupt.hpp), never backwards
    # the budget (3 scan, 3 local) while it runs; the count itself once the search has ended (a poll may see that
    # before the final call does)
    assert all(c[1] in (6, r.count) for c in calls)
    assert calls[-1] == (r.count, r.count, 0)  # the last: everything done
    assert all(c[2] >= 0 for c in calls)


def test_a_raising_progress_callback_stops_the_search():
    seen = []

    def progress(done, total, eta):
        seen.append(done)
        raise RuntimeError("enough")

    search = {"scan": 120, "starts": 1, "max_evals": 10, "profile_points": 0, "jobs": 1}
    t0 = time.monotonic()
    whole = imcol.calibrate("gg3462", DATA, FIT, **search)
    t_whole = time.monotonic() - t0
    t0 = time.monotonic()
    with pytest.raises(RuntimeError, match="enough"):
        imcol.calibrate("gg3462", DATA, FIT, progress=progress, **search)
    assert len(seen) == 1 and seen[0] < whole.count  # stopped at the first call, long before the end
    assert time.monotonic() - t0 < 0.5 * t_whole


def test_bad_input_is_refused_before_anything_runs():
    with pytest.raises(ValueError, match="imcol.calibrate: key 'fit'"):
        imcol.calibrate("gg3462", DATA, "contact.delta_ss=0.05:0.005")
    with pytest.raises(ValueError, match="not both"):
        imcol.calibrate("gg3462", DATA, FIT, factor=2.0, confidence=0.9)
    with pytest.raises(ValueError, match="scene file"):
        imcol.calibrate(imcol.Scene.from_toml(pathlib.Path(ROOT / "data" / "scenes" / "gg3462.toml").read_text()), DATA, FIT)
