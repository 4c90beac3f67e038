# SPDX-License-Identifier: BSD-3-Clause
"""The choice lists against the command line's own error text and `imcol scenes`."""
import pathlib
import re

import pytest

import imcol
from conftest import ROOT, imcol_cli


def expected_list(err, sep):
    """The allowed values a command-line error names: '… (expected a, b, c)'."""
    m = re.search(r"\(expected ([^)]*)\)\s*$", err.strip())
    assert m, err
    return m.group(1).split(sep)


def set_error(scene, key, value):
    status, _, err = imcol_cli("run", scene, "--set", f"{key}={value}", "--no-plot", "--quiet", "--out", "/dev/null/x")
    assert status == 2, err
    return err


@pytest.mark.parametrize("key", sorted(imcol.choices()))
def test_every_choice_key_lists_what_the_scene_reader_accepts(key):
    allowed = imcol.choices()[key]
    assert allowed and len(set(allowed)) == len(allowed)
    if key == "effects":
        err = set_error("default", key, '["bogus"]')
        assert "unknown effect 'bogus'" in err
        assert expected_list(err, ", ") == allowed == imcol.effects()
        return
    # A [flow] key needs a coupled scene; every other key is read in the default scene.
    err = set_error("coupled/gondret_st27" if key.startswith("flow.") else "default", key, "bogus")
    assert f"key '{key}': unknown choice 'bogus'" in err, err
    assert expected_list(err, " | ") == allowed
    # Refused from Python too, with the same message (the same reader).
    scene = imcol.Scene.load("coupled/gondret_st27" if key.startswith("flow.") else "default")
    with pytest.raises(ValueError) as refused:
        scene.set(key, "bogus")
    assert str(refused.value).startswith(f"Scene.set('{key}'): unknown choice 'bogus'")
    assert expected_list(str(refused.value), " | ") == allowed


def test_the_choice_keys_are_every_choice_the_scene_reader_reads():
    # Each TableReader::choice call in the collision-scene reader is one key of choices() (besides `effects`).
    source = (ROOT / "core" / "scene.cpp").read_text() + (ROOT / "core" / "flow_spec.cpp").read_text()
    calls = re.findall(r'\br\.choice\("(\w+)"', source)
    assert len(calls) == len(imcol.choices()) - 1
    assert sorted(calls) == sorted(k.split(".")[1] for k in imcol.choices() if k != "effects")


def test_the_lists_are_the_command_lines():
    assert imcol.history_kernels() == imcol.choices()["history.kernel"]
    status, _, err = imcol_cli("history", "default", "--kernels", "bogus", "--no-plot")
    assert status == 2 and expected_list(err, ", ") == imcol.history_kernels(), err
    status, _, err = imcol_cli("run", "default", "--integrator", "bogus", "--no-plot")
    assert status == 2 and expected_list(err, ", ") == imcol.integrators() == imcol.choices()["solver.integrator"], err
    status, _, err = imcol_cli("laws", "default", "--laws", "bogus", "--no-plot")
    assert status == 2 and expected_list(err, ", ") == imcol.contact_laws() == imcol.choices()["contact.law"], err
    status, _, err = imcol_cli("sweep", "default", "--vary", "bogus", "--from", "1", "--to", "2", "--points", "2")
    assert status == 2 and expected_list(err, ", ") == imcol.sweep_quantities(), err
    assert imcol.lubrication_models() == imcol.choices()["lubrication.model"]
    assert imcol.drag_laws() == imcol.choices()["drag.law"]
    assert imcol.e_measures() == imcol.choices()["measure.e"]


def scenes_listed(*pattern):
    """The names `imcol scenes [PATTERN]` prints, in its order."""
    status, out, err = imcol_cli("scenes", *pattern)
    assert status == 0, err
    return [line.split()[0] for line in out.splitlines() if line.startswith("  ")]


@pytest.mark.parametrize("pattern", ["", "coupled/*", "glycerol", "no such scene"])
def test_scenes_are_the_ones_imcol_scenes_lists(pattern):
    names = imcol.scenes(pattern)
    assert names == (scenes_listed(pattern) if pattern else scenes_listed())
    if pattern == "":
        assert "default" in names and len(names) > 40
        for name in names:  # each loads by its name, or is a flow scene (data/scenes/flow/)
            if not name.startswith("flow/"):
                imcol.Scene.load(name)
    if pattern == "no such scene":
        assert names == []
