# SPDX-License-Identifier: BSD-3-Clause
"""Scene.set: a later set of a key replaces the earlier one (the scene keeps each key once, so set's cost does not
grow with the calls), with the result of the same --set options on the command line; and the values it takes from
NumPy, converted by their kind (bool as bool, integers as int, floats as float, arrays as lists)."""
import time

import numpy as np
import pytest

import imcol

FLUID_TABLE = "{ density = 1200.0, viscosity = 0.03 }"


def test_a_thousand_sets_of_one_key_keep_one_override():
    scene = imcol.Scene.load("default")
    values = [0.1 + k * 1e-4 for k in range(1000)]
    for v in values:
        scene.set("sphere[0].velocity", v)
    assert scene.overrides == ["sphere[0].velocity=" + repr(values[-1])]
    assert repr(scene) == "imcol.Scene('default', path='" + scene.path + "', 1 keys set)"
    assert imcol.run(scene).e == imcol.run(imcol.Scene.load("default").set("sphere[0].velocity", values[-1])).e


def test_the_later_value_wins_and_moves_to_the_end():
    scene = imcol.Scene.load("default").set("fluid.viscosity", 0.05).set("sphere[0].velocity", 0.2)
    scene.set("fluid.viscosity", 0.04)
    assert scene.overrides == ["sphere[0].velocity=0.2", "fluid.viscosity=0.04"]
    # the same key in its other spelling is the same key
    scene.set("sphere.0.velocity", 0.25)
    assert scene.overrides == ["fluid.viscosity=0.04", "sphere.0.velocity=0.25"]
    assert imcol.run(scene).e == imcol.run(
        imcol.Scene.load("default").set("fluid.viscosity", 0.04).set("sphere[0].velocity", 0.25)).e


def test_a_table_set_replaces_the_keys_inside_it_and_keeps_the_clis_order(cli_run):
    # As on the command line, a key set after its table wins over the table's value, and one set before it does not.
    sets = ["fluid.viscosity=0.05", "fluid=" + FLUID_TABLE, "fluid.viscosity=0.04"]
    summary, _ = cli_run("default", *[a for s in sets for a in ("--set", s)])
    scene = imcol.Scene.load("default").set("fluid.viscosity", 0.05).set("fluid", FLUID_TABLE)
    assert scene.overrides == ["fluid=" + FLUID_TABLE]  # fluid.viscosity=0.05 lies inside it: dropped
    assert imcol.run(scene).fluid.viscosity_Pa_s == 0.03
    scene.set("fluid.viscosity", 0.04)
    assert scene.overrides == ["fluid=" + FLUID_TABLE, "fluid.viscosity=0.04"]
    r = imcol.run(scene)
    assert r.fluid.viscosity_Pa_s == summary["fluid"]["viscosity_Pa_s"] == 0.04
    assert r.e == summary["e"]


def test_set_costs_the_same_after_many_calls():
    # Printed, not asserted (the machine is shared): the time per call early and after 10,000 calls of one key.
    scene = imcol.Scene.load("default")
    per_call = {}
    for start, stop in [(0, 200), (200, 10_000), (10_000, 10_200)]:
        t = time.perf_counter()
        for k in range(start, stop):
            scene.set("sphere[0].velocity", 0.1 + (k % 100) * 1e-3)
        per_call[f"calls {start}-{stop}"] = (time.perf_counter() - t) / (stop - start) * 1e3
    print("Scene.set ms per call:", {k: round(v, 4) for k, v in per_call.items()})
    assert len(scene.overrides) == 1


# NumPy values: by their kind, as the Python value of that kind is taken.
@pytest.mark.parametrize("key,value,text", [
    ("solver.max_steps", np.int64(1000), "1000"),
    ("solver.max_steps", np.int32(1000), "1000"),
    ("solver.max_steps", np.uint16(1000), "1000"),
    ("fluid.viscosity", np.float64(0.05), "0.05"),
    ("fluid.viscosity", np.float32(0.05), repr(float(np.float32(0.05)))),  # the float32's value, exactly
    ("fluid.viscosity", np.array(0.05), "0.05"),  # a 0-d array is its element
    ("effects", np.array(["drag", "lubrication", "added_mass", "elastic"]), '["drag", "lubrication", "added_mass", "elastic"]'),
    ("sphere[0].velocity", np.int8(1), "1"),
])
def test_numpy_values_by_kind(key, value, text):
    scene = imcol.Scene.load("default").set(key, value)
    assert scene.overrides == [key + "=" + text]
    as_python = value.tolist()
    assert imcol.run(scene, record="kinematics").e == imcol.run(imcol.Scene.load("default").set(key, as_python),
                                                                  record="kinematics").e


def test_numpy_bools_are_bools():
    scene = imcol.Scene.load("coupled/gg3462").set("flow.added_mass_estimate", np.bool_(True))
    scene.set("flow.fields", np.bool_(False))
    assert scene.overrides == ["flow.added_mass_estimate=true", "flow.fields=false"]
    # a bool where a number belongs: refused with the message a Python bool gets
    messages = []
    for v in (True, np.bool_(True), np.array(True)):
        with pytest.raises(ValueError) as e:
            imcol.Scene.load("default").set("fluid.viscosity", v)
        messages.append(str(e.value))
    assert messages[0].startswith("Scene.set('fluid.viscosity'): must be a number")
    assert messages[1] == messages[2] == messages[0]


def test_numpy_integers_and_floats_as_solver_options():
    r = imcol.run(imcol.Scene.load("default"), rtol=np.float64(1e-6), atol=np.float32(1e-9))
    assert r.solver.rtol == 1e-6 and r.solver.atol == float(np.float32(1e-9))
    with pytest.raises(ValueError) as e:
        imcol.run(imcol.Scene.load("default"), rtol=np.bool_(True))
    with pytest.raises(ValueError) as e_bool:
        imcol.run(imcol.Scene.load("default"), rtol=True)
    assert str(e.value) == str(e_bool.value)


def test_numpy_ints_keep_their_digits():
    # 2**62 + 1 is no double: as an int it keeps every digit
    assert imcol.Scene.load("default").set("solver.max_steps", np.int64(2**62 + 1)).overrides == [
        "solver.max_steps=4611686018427387905"]
    # beyond TOML's integers: refused as the Python int is
    big = np.uint64(2**64 - 1)
    with pytest.raises(ValueError) as e:
        imcol.Scene.load("default").set("solver.max_steps", big)
    with pytest.raises(ValueError) as e_int:
        imcol.Scene.load("default").set("solver.max_steps", int(big))
    assert str(e.value) == str(e_int.value)
