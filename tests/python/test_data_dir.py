# SPDX-License-Identifier: BSD-3-Clause
"""The data folder from Python: the build-tree module reads the source tree's data/; the package's setter (used at
import by an installed package, for its imcol/data) moves every lookup there, below IMCOL_DATA_DIR."""
import os
import pathlib
import shutil
import subprocess
import sys

import imcol
from imcol import _imcol

SOURCE_DATA = pathlib.Path(__file__).resolve().parents[2] / "data"


def test_the_build_tree_module_reads_the_source_data():
    assert pathlib.Path(imcol.data_dir()).resolve() == SOURCE_DATA
    assert "default" in imcol.scenes()


def test_the_setter_moves_the_scenes_and_empty_restores_them(tmp_path):
    (tmp_path / "scenes").mkdir()
    shutil.copy(SOURCE_DATA / "scenes" / "default.toml", tmp_path / "scenes" / "only_here.toml")
    for table in ("materials.csv", "fluids.csv"):  # read once per process, from whichever folder is set first
        shutil.copy(SOURCE_DATA / table, tmp_path / table)
    try:
        _imcol._set_data_dir(str(tmp_path))
        assert imcol.data_dir() == str(tmp_path)
        assert imcol.scenes() == ["only_here"]
        default = imcol.Scene.load(str(SOURCE_DATA / "scenes" / "default.toml"))
        assert imcol.run(imcol.Scene.load("only_here")).e == imcol.run(default).e
    finally:
        _imcol._set_data_dir("")
    assert pathlib.Path(imcol.data_dir()).resolve() == SOURCE_DATA
    assert "only_here" not in imcol.scenes()


def test_imcol_data_dir_in_the_environment_wins_over_the_setter(tmp_path):
    code = ("import imcol; from imcol import _imcol; _imcol._set_data_dir('/nowhere'); print(imcol.data_dir())")
    env = dict(os.environ, IMCOL_DATA_DIR=str(tmp_path))
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True).stdout
    assert out.strip() == str(tmp_path)
