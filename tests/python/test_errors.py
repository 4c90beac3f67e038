# SPDX-License-Identifier: BSD-3-Clause
"""imcol.SolverError's facts (integrator, flag, time, state, local errors) against the command line's message for
the same failing scene."""
import math
import re

import pytest

import imcol
from conftest import imcol_cli

# The integrator's message: "<integrator> failed at t = <t> s with <FLAG> [<solver's text>]; largest weighted local
# errors: <name>=<value> …" (integrators/sundials_driver.cpp).
MESSAGE = re.compile(r"^(\w+) failed at t = (\S+) s with (\w+)(?: \[.*\])?; largest weighted local errors:((?: \S+=\S+)+)$")

# SUNDIALS return flags (cvode.h, ida.h)
FLAGS = {"CV_TOO_MUCH_WORK": -1, "IDA_TOO_MUCH_WORK": -1, "IDA_ERR_FAIL": -3}


def g(x):
    """A number as the C++ message writes it (ostream's default: 6 significant digits)."""
    return format(x, "g")


@pytest.mark.parametrize("sets,opts", [
    ({"solver.max_steps": 5}, {}),
    ({"solver.max_steps": 5}, {"integrator": "ida"}),
    ({}, {"integrator": "ida", "rtol": 1e-14, "atol": 1e-20}),  # error test failures at a near-touching gap
])
def test_solver_error_facts_are_the_clis_message(sets, opts, tmp_path):
    args = [a for k, v in sets.items() for a in ("--set", f"{k}={v}")]
    args += [a for k, v in opts.items() for a in (f"--{k}", str(v))]
    status, _, err = imcol_cli("run", "default", "--quiet", "--no-plot", "--out", str(tmp_path / "out"), *args)
    assert status == 3, err
    cli = err.strip().removeprefix("imcol: solver failure: ")

    scene = imcol.Scene.load("default")
    for k, v in sets.items():
        scene.set(k, v)
    with pytest.raises(imcol.SolverError) as info:
        imcol.run(scene, **opts)
    e = info.value
    assert str(e) == cli  # the same message

    integrator, t, flag_name, errors = MESSAGE.match(cli).groups()
    assert e.integrator == integrator == opts.get("integrator", "cvode")
    assert g(e.time) == t and isinstance(e.time, float)
    assert e.flag_name == flag_name
    assert e.flag == FLAGS[flag_name] and isinstance(e.flag, int)
    pairs = [p.split("=") for p in errors.split()]
    assert [(n, g(v)) for n, v in e.local_errors.items()] == [(n, v) for n, v in pairs]

    # the state: the model's components (summary.json solver.state names them) at e.time
    ok = imcol.run(imcol.Scene.load("default"))
    assert list(e.state) == ok.to_dict()["solver"]["state"] == ["gap", "u1"]
    assert all(isinstance(v, float) and math.isfinite(v) for v in e.state.values())
    gap0, u0 = ok.trajectory["gap"][0], ok.trajectory["u1"][0]
    if "solver.max_steps" in sets:  # a few steps after t = 0: the gap closed at the mean speed (to the run's rtol)
        assert e.time < 1e-4
        rtol = ok.to_dict()["solver"]["rtol"]
        assert e.state["gap"] == pytest.approx(gap0 - 0.5 * (u0 + e.state["u1"]) * e.time, rel=rtol)
        assert 0 < u0 - e.state["u1"] < 1e-3 * u0
    else:  # at the touch or in the contact: the gap between the deepest overlap of the run that passes and ~0
        deepest = ok.to_dict()["min_gap_m"]
        assert deepest * (1 + 1e-3) <= e.state["gap"] < 1e-6 * gap0
        assert e.time > 0.01


def test_a_failure_not_the_integrators_has_no_facts(tmp_path):
    # A coupled run whose flow coupling diverges (explicit fluid inertia for a light sphere): the message only.
    sets = {"solver.t_end": 0.2, "flow.added_mass_estimate": "false", "flow.fields": "false"}
    status, _, err = imcol_cli("run", "coupled/free_rise_ratio0.5", "--quiet", "--no-plot", "--out", str(tmp_path / "out"),
                               *[a for k, v in sets.items() for a in ("--set", f"{k}={v}")])
    assert status == 3, err
    scene = imcol.Scene.load("coupled/free_rise_ratio0.5")
    for k, v in sets.items():
        scene.set(k, v)
    with pytest.raises(imcol.SolverError) as info:
        imcol.run(scene)
    assert err.strip() == "imcol: solver failure: " + str(info.value)
    assert "the flow coupling diverged" in str(info.value)
    e = info.value
    assert (e.integrator, e.flag, e.flag_name, e.time, e.state, e.local_errors) == (None,) * 6


def test_solver_error_made_in_python_has_empty_facts():
    e = imcol.SolverError("by hand")
    assert str(e) == "by hand" and e.flag is None and e.state is None
    assert isinstance(e, RuntimeError)


# Bad input names the Python call and the key, never the command line's options (--set, --rtols, command line).
BAD_INPUT = [
    ("Scene.set('fluid.viscosity'): must be > 0", lambda: imcol.Scene.load("default").set("fluid.viscosity", -1.0)),
    ("Scene.set('effects'): a target sphere or wall needs 'elastic'", lambda: imcol.Scene.load("default").set("effects", ["drag"])),
    ("Scene.set('fluid.viscocity'): unknown key; did you mean 'viscosity'?",
     lambda: imcol.Scene.load("default").set("fluid.viscocity", 0.05)),
    ("Scene.set('sphere.velocity'): a scene's spheres are sphere[0]: use 'sphere[0].velocity'",
     lambda: imcol.Scene.load("default").set("sphere.velocity", 0.05)),
    ("Scene.from_toml: <string>:1: key 'x': unknown key", lambda: imcol.Scene.from_toml("x = 1")),
    ("imcol.run: key 'solver.atol': must be in (0, 1)", lambda: imcol.run("default", atol=-1.0)),
    ("imcol.sweep: key 'solver.rtol': must be in [1e-14, 1)", lambda: imcol.sweep("default", values=[0.3], rtol=5.0)),
    ("imcol.laws: key 'solver.integrator': unknown choice 'euler' (expected cvode | ida)",
     lambda: imcol.laws("default", integrator="euler")),
    ("imcol.laws: key 'vary': unknown value 'speed'", lambda: imcol.laws("default", vary="speed", values=[1.0])),
    ("imcol.history_compare: key 'solver.rtol': must be in", lambda: imcol.history_compare("default", rtol=5.0)),
    ("imcol.work_precision: key 'integrators': 'lsoda': unknown integrator",
     lambda: imcol.work_precision("default", integrators=["lsoda"])),
    ("imcol.work_precision: key 'rtols': each tolerance must lie in", lambda: imcol.work_precision("default", rtols=[2.0])),
    ("imcol.validate_seed: key 'models': unknown model 'wall'", lambda: imcol.validate_seed(models=["wall"])),
    ("imcol.validate_seed: key 'solver.rtol': must be in", lambda: imcol.validate_seed(rtol=5.0)),
]


@pytest.mark.parametrize("start,call", BAD_INPUT, ids=[s.split(":")[0] for s, _ in BAD_INPUT])
def test_bad_input_names_the_call_and_the_key_in_pythons_words(start, call):
    with pytest.raises(ValueError) as e:
        call()
    message = str(e.value)
    assert message.startswith(start), message
    assert "command line" not in message and "--" not in message, message
