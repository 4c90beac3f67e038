# SPDX-License-Identifier: BSD-3-Clause
"""The summary as typed attributes (imcol.Summary and its blocks) against summary.json of the same scenes run by the
command line: every key reachable with its value, every key declared with a type the value has, None where absent,
and the type stub declaring the same names."""
import ast
import pathlib
import typing

import pytest

import imcol
from imcol import _summary

UNSTABLE = {"run", "wall_time_s", "setup_time_s"}
# The flow block's timings, and its field snapshots and their estimated cost: the command line writes flow fields, a
# run from Python makes none (the estimate is compared below without them).
FLOW_UNSTABLE = {"flow_time_s", "ode_time_s", "fields_time_s", "cpu_time_s", "start_up_time_s", "flow_share", "ode_share",
                 "ms_per_step", "field_snapshots", "estimate"}


def stable(key, d):
    return {k: v for k, v in d.items() if k not in (FLOW_UNSTABLE if key == "flow" else UNSTABLE)}


def hints(cls):
    return {k: v for k, v in typing.get_type_hints(cls).items() if not k.startswith("_")}

# One scene of each kind: wall with a fluid, pair, free sphere, dry pair, coupled (coarse grid, so it is quick).
SCENES = [
    ("default", []),
    ("seed_run1", []),
    ("rising_sphere", []),
    ("dry_steel_steel", []),
    ("coupled/free_fall_stokes", ["flow.cells_per_diameter=8"]),
]


def conforms(value, annotation):
    """Whether a JSON value has the declared type (Optional, List, Dict, Block classes, float taking ints)."""
    origin, args = typing.get_origin(annotation), typing.get_args(annotation)
    if annotation is typing.Any:
        return True
    if origin is typing.Union:
        return any(conforms(value, a) for a in args)
    if annotation is type(None):
        return value is None
    if origin in (list, typing.List):
        return isinstance(value, list) and all(conforms(v, args[0]) for v in value)
    if origin in (dict, typing.Dict):
        return isinstance(value, dict) and all(conforms(v, args[1]) for v in value.values())
    if isinstance(annotation, type) and issubclass(annotation, _summary.Block):
        return isinstance(value, dict) and check_block(annotation, value) is None
    if annotation is float:
        return isinstance(value, (int, float)) and not isinstance(value, bool)
    return isinstance(value, annotation) and not (annotation is int and isinstance(value, bool))


def check_block(cls, d):
    """None if every declared key of `d` has its type; else the first mismatch."""
    h = hints(cls)
    for k, v in d.items():
        if k in h and not conforms(v, h[k]):
            return f"{cls.__name__}.{k} = {v!r} is not {h[k]}"
    return None


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """(scene, summary.json of `imcol run`, imcol.run's result) for each scene."""
    from conftest import imcol_cli
    import json
    out = []
    for name, sets in SCENES:
        d = tmp_path_factory.mktemp("run")
        args = [a for s in sets for a in ("--set", s)]
        status, _, err = imcol_cli("run", name, "--out", str(d), "--quiet", "--no-plot", *args)
        assert status == 0, err
        scene = imcol.Scene.load(name)
        for s in sets:
            k, v = s.split("=", 1)
            scene.set(k, v)
        out.append((name, json.loads((d / "summary.json").read_text()), imcol.run(scene)))
    return out


def test_every_key_is_an_attribute_with_its_value(runs):
    for name, summary, r in runs:
        for key, value in summary.items():
            if key in UNSTABLE:
                continue
            got = getattr(r, key)
            if isinstance(got, _summary.Block):
                assert stable(key, got.to_dict()) == stable(key, value), (name, key)
            elif isinstance(got, list) and got and isinstance(got[0], _summary.Block):
                assert [b.to_dict() for b in got] == value, (name, key)
            else:
                assert got == value, (name, key)
        mine, cli = stable("", r.to_dict()), stable("", summary)
        if "flow" in cli:
            mine["flow"], cli["flow"] = stable("flow", mine["flow"]), stable("flow", cli["flow"])
        assert mine == cli, name


def test_every_key_is_declared_with_its_type(runs):
    blocks = {"solver": _summary.Solver, "contact": _summary.Contact, "flow": _summary.Flow, "fluid": _summary.Fluid,
              "velocities_m_s": _summary.Velocities}
    declared = set(hints(_summary.Summary))
    for name, summary, r in runs:
        assert set(summary) - UNSTABLE - {"run"} <= declared, (name, set(summary) - declared)
        assert check_block(_summary.Summary, summary) is None, name
        for key, cls in blocks.items():
            if summary.get(key) is not None:
                # the contact block also carries its law's own numbers (W_o_N, beta, …): not declared
                extra = set(summary[key]) - set(hints(cls))
                assert key == "contact" or not extra, (name, key, extra)
                assert isinstance(getattr(r, key), cls)
        for b in summary.get("bounces", []):
            assert set(b) <= set(hints(_summary.Bounce)), (name, set(b))
        for ev in summary.get("events", []):
            assert set(ev) == set(hints(_summary.Event)), name


def test_absent_blocks_are_none(runs):
    by_name = {name: (summary, r) for name, summary, r in runs}
    summary, r = by_name["default"]
    assert "flow" not in summary and r.flow is None
    assert r.contact.law == summary["contact"]["law"] and r.solver.steps == summary["solver"]["steps"]
    assert r.contact.W_o_N == summary["contact"]["W_o_N"]  # a law's own number
    summary, r = by_name["rising_sphere"]
    assert "contact" not in summary and r.contact is None
    summary, r = by_name["coupled/free_fall_stokes"]
    assert r.flow.steps == summary["flow"]["steps"] and r.flow.grid.cells_per_diameter == 8
    cli_est = summary["flow"]["estimate"]
    assert r.flow.estimate.fields_s == 0 and cli_est["fields_s"] > 0
    assert r.flow.estimate.total_s == pytest.approx(cli_est["total_s"] - cli_est["fields_s"], rel=1e-12)
    for k in ("start_up_s", "force_system_blocks_s", "steps_to_t_end_s", "memory_MB"):
        assert getattr(r.flow.estimate, k) == cli_est[k], k
    with pytest.raises(AttributeError, match="imcol.Result has no attribute 'no_such_name'"):
        r.no_such_name
    with pytest.raises(AttributeError, match="Solver has no attribute 'no_such_name'"):
        r.solver.no_such_name
    with pytest.raises(AttributeError):
        r.solver.steps = 3


def test_dir_lists_the_summarys_names(runs):
    _, summary, r = runs[0]
    names = dir(r)
    assert {"e", "St", "trajectory", "to_dict", "solver", "contact", "flow"} <= set(names)
    assert set(k for k in summary if k.isidentifier()) - UNSTABLE <= set(names)
    assert {"steps", "rhs_evals", "rtol"} <= set(dir(r.solver))


STUB = pathlib.Path(imcol.__file__).with_name("_imcol.pyi")


def test_stub_declares_the_summarys_names():
    tree = ast.parse(STUB.read_text())
    result = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == "Result")
    stub = {n.target.id: ast.unparse(n.annotation) for n in result.body if isinstance(n, ast.AnnAssign)}
    stub.update({n.name: ast.unparse(n.returns) for n in result.body if isinstance(n, ast.FunctionDef)})
    src = ast.parse(pathlib.Path(_summary.__file__).read_text())
    summary_cls = next(n for n in src.body if isinstance(n, ast.ClassDef) and n.name == "Summary")
    declared = {n.target.id: ast.unparse(n.annotation) for n in summary_cls.body
                if isinstance(n, ast.AnnAssign) and not n.target.id.startswith("_")}
    # Result's own properties (e, St, bounces, warnings) are typed in the stub as they are in the summary
    for k, t in declared.items():
        assert stub.get(k) == t, (k, stub.get(k), t)
    # and every public name of the extension's Result is in the stub
    public = {n for n in dir(imcol.Result) if not n.startswith("_")}
    assert public <= set(stub), public - set(stub)


def test_stub_declares_every_name_of_the_extension():
    tree = ast.parse(STUB.read_text())
    top = {n.name for n in tree.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
    top |= {n.target.id for n in tree.body if isinstance(n, ast.AnnAssign)}
    from imcol import _imcol
    public = {n for n in dir(_imcol) if not n.startswith("_")} | {"__version__"}
    assert public <= top, public - top
    for cls in ("SweepResult", "SolverError", "Scene"):
        body = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == cls).body
        stub = {n.name for n in body if isinstance(n, ast.FunctionDef)} | {n.target.id for n in body if isinstance(n, ast.AnnAssign)}
        extension = {n for n in dir(getattr(imcol, cls)) if not n.startswith("_")} - set(dir(RuntimeError))
        assert extension <= stub, (cls, extension - stub)
