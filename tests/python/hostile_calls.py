# SPDX-License-Identifier: BSD-3-Clause
"""Calls that must raise a Python exception, not crash the interpreter; run by test_hostile.py in a subprocess.
Prints one JSON object: call -> the name of the exception it raised ("returned" if none)."""
import concurrent.futures
import copy
import gc
import json
import math
import pickle
import sys

import numpy as np

import imcol


def default():
    return imcol.Scene.load("default")


def coupled():
    return imcol.Scene.load("coupled/gg3462").set("flow.cells_per_diameter", 8)


def self_holding_list():
    a = ["drag"]
    a.append(a)
    return default().set("effects", a)


def nested(depth):
    v = []
    for _ in range(depth):
        v = [v]
    return v


class BadFloat:
    def __float__(self):
        raise ValueError("no number here")


# call -> (the exception it must raise, the call)
CALLS = {
    # wrong types and None
    "run(bytes)": (TypeError, lambda: imcol.run(b"default")),
    "run(None)": (TypeError, lambda: imcol.run(None)),
    "run(42)": (TypeError, lambda: imcol.run(42)),
    "Scene.load(None)": (TypeError, lambda: imcol.Scene.load(None)),
    "Scene.from_toml(None)": (TypeError, lambda: imcol.Scene.from_toml(None)),
    "Scene()": (TypeError, lambda: imcol.Scene()),
    "Result()": (TypeError, lambda: imcol.Result()),
    "set(1, 2)": (TypeError, lambda: default().set(1, 2)),
    "set(key, None)": (TypeError, lambda: default().set("fluid.viscosity", None)),
    "set(key, object())": (TypeError, lambda: default().set("fluid.viscosity", object())),
    "set(key, 1j)": (TypeError, lambda: default().set("fluid.viscosity", 1j)),
    "set(key, {})": (TypeError, lambda: default().set("fluid.viscosity", {})),
    "set(key, np.array)": (ValueError, lambda: default().set("fluid.viscosity", np.array([1.0, 2.0]))),  # a list
    "set(key, np.complex128)": (TypeError, lambda: default().set("fluid.viscosity", np.complex128(1j))),
    "set(key, np.datetime64)": (TypeError, lambda: default().set("fluid.viscosity", np.datetime64("2020-01-01"))),
    "set(key, np 32-d array)": (ValueError, lambda: default().set("effects", np.zeros([1] * 32))),
    "set(key, BadFloat())": (ValueError, lambda: default().set("fluid.viscosity", BadFloat())),
    "run(rtol=[])": (TypeError, lambda: imcol.run(default(), rtol=[object()])),
    "run(integrator=1)": (TypeError, lambda: imcol.run(default(), integrator=1)),
    "run(record=None)": (TypeError, lambda: imcol.run(default(), record=None)),
    "pickle(Scene)": (TypeError, lambda: pickle.dumps(default())),
    # NaN, inf and huge values
    "set(viscosity, nan)": (ValueError, lambda: default().set("fluid.viscosity", math.nan)),
    "set(viscosity, np.nan)": (ValueError, lambda: default().set("fluid.viscosity", np.float64("nan"))),
    "set(velocity, inf)": (ValueError, lambda: default().set("sphere[0].velocity", math.inf)),
    "set(position, -inf)": (ValueError, lambda: default().set("sphere[0].position", -math.inf)),
    "set(t_end, nan)": (ValueError, lambda: default().set("solver.t_end", math.nan)),
    "set(velocity, 1e300)": (ValueError, lambda: default().set("sphere[0].velocity", 1e300)),
    "set(diameter, 1e-300)": (ValueError, lambda: default().set("sphere[0].diameter", 1e-300)),
    "set(max_steps, 10**30)": (ValueError, lambda: default().set("solver.max_steps", 10**30)),
    "set(t_end, 1e30)": (ValueError, lambda: imcol.run(default().set("solver.t_end", 1e30))),
    "run(rtol=10**400)": (ValueError, lambda: imcol.run(default(), rtol=10**400)),
    "run(rtol=nan)": (ValueError, lambda: imcol.run(default(), rtol=math.nan)),
    "set(cells_per_diameter, 4096)": (ValueError, lambda: coupled().set("flow.cells_per_diameter", 4096)),
    "set(levels, 10**9)": (ValueError, lambda: coupled().set("flow.levels", 10**9)),
    "set(r_max, 1e6)": (ValueError, lambda: coupled().set("flow.r_max", 1e6)),
    "set(effects, deep list)": (ValueError, lambda: default().set("effects", nested(500))),
    "set(effects, self-holding list)": (ValueError, self_holding_list),
    "set(effects, 10**5 names)": (ValueError, lambda: default().set("effects", ["nope"] * 10**5)),
    "set(10**5-part key)": (ValueError, lambda: default().set("a." * 10**5 + "b", 1)),
    # empty, broken and hostile TOML
    "from_toml('')": (ValueError, lambda: imcol.Scene.from_toml("")),
    "from_toml(NUL)": (ValueError, lambda: imcol.Scene.from_toml("\x00\xff[[[[")),
    "from_toml(nested 10**5)": (ValueError, lambda: imcol.Scene.from_toml("a = " + "[" * 10**5)),
    "from_toml(1 MB name)": (ValueError, lambda: imcol.Scene.from_toml("name = '" + "x" * 10**6 + "'")),
    "Scene.load('')": (ValueError, lambda: imcol.Scene.load("")),
    "Scene.load(NUL)": (ValueError, lambda: imcol.Scene.load("de\x00fault")),
    "Scene.load('/')": (ValueError, lambda: imcol.Scene.load("/")),
    "Scene.load('/dev/zero')": (ValueError, lambda: imcol.Scene.load("/dev/zero")),
    "set(key with line break)": (ValueError, lambda: default().set("fluid.viscosity", "1\nname = 'x'")),
    # bad solver options
    "run(rtol=-1)": (ValueError, lambda: imcol.run(default(), rtol=-1.0)),
    "run(atol=0)": (ValueError, lambda: imcol.run(default(), atol=0)),
    "run(rtol='1e-6\\nname=\"x\"')": (ValueError, lambda: imcol.run(default(), rtol='1e-6\nname="x"')),
    "run(integrator='euler')": (ValueError, lambda: imcol.run(default(), integrator="euler")),
    "run(integrator with quotes)": (ValueError, lambda: imcol.run(default(), integrator='cvode"\nname="x')),
    "run(record='some')": (ValueError, lambda: imcol.run(default(), record="some")),
    "set(max_steps, 0)": (ValueError, lambda: default().set("solver.max_steps", 0)),
    # solver failures
    "run(max_steps=5)": (imcol.SolverError, lambda: imcol.run(default().set("solver.max_steps", 5))),
    "run(ida, rtol=1e-14)": (imcol.SolverError, lambda: imcol.run(default(), rtol=1e-14, atol=1e-20, integrator="ida")),
    "run(coupled, max_steps=3)": (imcol.SolverError, lambda: imcol.run(coupled().set("solver.max_steps", 3))),
    # a Result's attributes it does not have
    "Result.no_such": (AttributeError, lambda: imcol.run(default(), record="kinematics").no_such_attribute),
}


def outcome(f):
    try:
        f()
        return "returned"
    except Exception as e:  # noqa: BLE001: the name is the finding
        return type(e).__name__


def result_after_its_scene_is_gone():
    """A Result, its Scene deleted and collected: its values stay (e, the trajectory, the summary)."""
    scene = default()
    r = imcol.run(scene)
    e, n = r.e, len(r.trajectory["t"])
    del scene
    gc.collect()
    same = r.e == e and len(r.trajectory["t"]) == n and r.to_dict()["e"] == e and copy.deepcopy(r.to_dict())["St"] == r.St
    # a chained set's scene (set returns the scene) used after the name that held it is rebound
    s = default().set("fluid.viscosity", 0.05)
    r2 = imcol.run(s)
    del s
    gc.collect()
    return same and r2.e is not None and r2.e == r2.to_dict()["e"]


def many_threads():
    """16 threads: good runs, bad input and solver failures at once; each outcome as alone."""
    work = [
        lambda: imcol.run(default().set("sphere[0].velocity", 0.25), record="kinematics").e,
        lambda: imcol.run(coupled()).e,
        lambda: imcol.run(default().set("solver.max_steps", 5)),
        lambda: imcol.run(default(), integrator="euler"),
        lambda: default().set("fluid.viscosity", math.nan),
    ]

    def one(f):
        try:
            return f()
        except Exception as e:  # noqa: BLE001
            return type(e).__name__ + ": " + str(e)

    alone = [one(f) for f in work]
    with concurrent.futures.ThreadPoolExecutor(16) as pool:
        together = list(pool.map(one, work * 8))
    return together == alone * 8 and alone[2].startswith("SolverError") and alone[3].startswith("ValueError")


def main():
    found = {name: outcome(f) for name, (_, f) in CALLS.items()}
    expected = {name: exc.__name__ for name, (exc, _) in CALLS.items()}
    found["result after its scene is gone"] = str(result_after_its_scene_is_gone())
    expected["result after its scene is gone"] = "True"
    found["16 threads"] = str(many_threads())
    expected["16 threads"] = "True"
    print(json.dumps({"found": found, "expected": expected}))
    sys.stdout.flush()


if __name__ == "__main__":
    main()
