# SPDX-License-Identifier: BSD-3-Clause
"""imcol.dem_fit against `imcol sweep … --export dem` on the same sweep: dem.csv cell for cell and dem.json's fits
number for number."""
import json

import numpy as np

import imcol
from conftest import imcol_cli
from study_tables import assert_table_equals_csv, read_csv


def test_dem_fit_equals_the_exported_files(tmp_path):
    out = tmp_path / "sweep"
    status, out_text, err = imcol_cli("sweep", "default", "--vary", "velocity", "--from", "0.1", "--to", "1", "--points", "4",
                               "--jobs", "2", "--export", "dem", "--out", str(out), "--no-plot", "--no-progress")
    assert status == 0, err
    header, rows = read_csv(out / "dem.csv")
    dem = json.loads((out / "dem.json").read_text())
    values = [0.1 * 10 ** (i / 3) for i in range(4)]
    s = imcol.sweep(imcol.Scene.load("default"), vary="velocity", values=values, jobs=2)
    r = imcol.dem_fit(s)
    assert r.kind == "dem"
    assert_table_equals_csv(r, header, rows)
    np.testing.assert_array_equal(r.e, s.e)
    info = r.info
    assert info["fits"] == dem["fits"]
    assert info["fit_error"] == dem["fit_error"]
    assert info["points"] == dem["points"]
    assert info["e_dry_scene"] == dem["e_dry_scene"]
    assert info["St_column"] == dem["St_column"]
    best = dem["best"]
    assert (info["best"]["form"], info["best"]["e_dry_is"]) == (best["form"], best["e_dry_is"])
    assert len(info["fits"]) == 4 and info["best"]["rms_residual"] >= 0
    # LIGGGHTS's viscous rule fitted through the replay: the same block, and the closing line says its parameters.
    assert info["liggghts"] == dem["liggghts"]
    lg = info["liggghts"]
    assert lg["fit_error"] is None
    assert 0 < lg["MaximumRestitution"] <= 1 and lg["CriticalStokes"] > 0
    assert f"CriticalStokes = {lg['CriticalStokes']:.2f}, MaximumRestitution = {lg['MaximumRestitution']:.3f}" in out_text
