# SPDX-License-Identifier: BSD-3-Clause
"""One API in Python's words: every call takes a Scene, a shipped scene's name or a scene file's path; bad input
names the call and the key, with the close names; the stubs (_imcol.pyi) agree with the functions; every result
column is an attribute listed by dir()."""
import ast
import pathlib
import warnings

import pytest

import imcol
from imcol import _imcol

STUB = pathlib.Path(imcol.__file__).with_name("_imcol.pyi")
DEFAULT = pathlib.Path(imcol.Scene.load("default").path)

# Every call that takes a scene, with arguments that make it cheap or refuse it before anything runs.
SCENE_CALLS = {
    "imcol.run": lambda s: imcol.run(s),
    "imcol.sweep": lambda s: imcol.sweep(s, values=[0.3], jobs=1),
    "imcol.laws": lambda s: imcol.laws(s, laws=["glue"]),
    "imcol.history_compare": lambda s: imcol.history_compare(s, kernels=["nope"]),
    "imcol.work_precision": lambda s: imcol.work_precision(s, rtols=[2.0]),
    "Scene.load": lambda s: imcol.Scene.load(s),
}


@pytest.mark.parametrize("call", SCENE_CALLS)
def test_every_call_names_itself_and_the_close_scenes_for_an_unknown_name(call):
    with pytest.raises(ValueError) as e:
        SCENE_CALLS[call]("defualt")
    assert str(e.value).startswith(f"{call}: scene 'defualt': no shipped scene or file of that name"), e.value
    assert "did you mean 'default'" in str(e.value)
    assert "command line" not in str(e.value) and "--set" not in str(e.value)
    with pytest.raises(TypeError, match=rf"^{call}: scene must be an imcol.Scene, a shipped scene's name or the path"):
        SCENE_CALLS[call](42)


@pytest.mark.parametrize("call", SCENE_CALLS)
def test_every_call_takes_a_scene_a_name_or_a_path(call):
    """The same refusal of the same bad argument, whatever form the scene came in: the scene itself was read."""
    messages = set()
    for scene in (imcol.Scene.load("default"), "default", str(DEFAULT), DEFAULT):
        try:
            SCENE_CALLS[call](scene)
        except ValueError as e:
            messages.add(str(e))
    assert len(messages) <= 1, messages


def test_run_of_a_name_a_path_and_a_scene_agree():
    e = imcol.run(imcol.Scene.load("default"), record="kinematics").e
    assert imcol.run("default", record="kinematics").e == e
    assert imcol.run(DEFAULT, record="kinematics").e == e
    assert imcol.run(str(DEFAULT), record="kinematics").e == e


def test_sweep_of_an_unknown_scene_names_the_call_and_no_command_line():
    with pytest.raises(ValueError) as e:
        imcol.sweep("nosuch", values=[0.1])
    assert str(e.value) == ("imcol.sweep: scene 'nosuch': no shipped scene or file of that name "
                            "(imcol.scenes() lists the shipped scenes)")


def test_set_through_an_array_names_the_element_to_use():
    with pytest.raises(ValueError) as e:
        imcol.Scene.load("default").set("sphere.velocity", 0.05)
    assert str(e.value) == "Scene.set('sphere.velocity'): a scene's spheres are sphere[0]: use 'sphere[0].velocity'"
    with pytest.raises(ValueError) as e:
        imcol.Scene.load("group_a").set("sphere.velocity", 0.05)
    assert str(e.value) == ("Scene.set('sphere.velocity'): a scene's spheres are sphere[0] and sphere[1]: "
                            "use 'sphere[0].velocity'")


def test_set_of_a_misspelt_key_suggests_the_known_one():
    scene = imcol.Scene.load("default")
    with pytest.raises(ValueError) as e:
        scene.set("fluid.viscocity", 0.05)
    assert str(e.value) == "Scene.set('fluid.viscocity'): unknown key; did you mean 'viscosity'?"
    with pytest.raises(ValueError) as e:
        scene.set("solver.integrator", "cvod")
    assert str(e.value).startswith("Scene.set('solver.integrator'): unknown choice 'cvod' (expected ")
    assert str(e.value).endswith("; did you mean 'cvode'?")
    assert scene.overrides == []


def test_a_misspelt_key_in_a_file_is_named_at_its_line(tmp_path):
    text = DEFAULT.read_text().replace("viscosity =", "viscocity =", 1)
    lines = text.splitlines()
    line = next(i for i, s in enumerate(lines, 1) if s.startswith("viscocity"))
    path = tmp_path / "misspelt.toml"
    path.write_text(text)
    where = f"{path}:{line}: key 'fluid.viscocity': unknown key; did you mean 'viscosity'?"
    for call, f in (("Scene.load", imcol.Scene.load), ("imcol.run", imcol.run), ("imcol.sweep", lambda s: imcol.sweep(s, values=[0.3]))):
        with pytest.raises(ValueError) as e:
            f(path)
        assert str(e.value) == f"{call}: {where}"
    with pytest.raises(ValueError) as e:
        imcol.Scene.from_toml(text)
    assert str(e.value) == f"Scene.from_toml: <string>:{line}: key 'fluid.viscocity': unknown key; did you mean 'viscosity'?"


def test_solver_options_name_the_call_and_the_key():
    with pytest.raises(ValueError) as e:
        imcol.run("default", rtol=2.0)
    assert str(e.value).startswith("imcol.run: key 'solver.rtol': must be in ")
    with pytest.raises(ValueError) as e:
        imcol.sweep("default", values=[0.3], integrator="euler")
    assert str(e.value).startswith("imcol.sweep: key 'solver.integrator': unknown choice 'euler'")


def test_sweep_values_are_required_by_keyword():
    with pytest.raises(TypeError):
        imcol.sweep("default")
    with pytest.raises(TypeError):
        imcol.sweep("default", "velocity", [0.3])
    with pytest.raises(ValueError, match=r"^imcol.sweep: key 'values': None"):
        imcol.sweep("default", values=None)


def test_history_is_a_deprecated_alias_of_history_compare():
    with pytest.warns(DeprecationWarning, match="imcol.history_compare"):
        with pytest.raises(ValueError, match=r"^imcol.history_compare: scene 'nosuch'"):
            imcol.history("nosuch")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(ValueError):
            imcol.history_compare("nosuch")
    assert "history_compare" in imcol.__all__ and "history" not in imcol.__all__


# The stubs against the functions: pybind11 writes each function's signature as its docstring's first line.

def signature_of(node):
    """(kind, name, default) per parameter of a parsed function, defaults as Python values."""
    a = node.args
    value = lambda d: None if d is None else ast.literal_eval(d)
    positional = a.posonlyargs + a.args
    defaults = [None] * (len(positional) - len(a.defaults)) + list(a.defaults)
    out = [("positional", p.arg, value(d)) for p, d in zip(positional, defaults)]
    out += [("keyword", p.arg, value(d)) for p, d in zip(a.kwonlyargs, a.kw_defaults)]
    return out


def binding_signature(obj):
    first = obj.__doc__.splitlines()[0]
    return signature_of(ast.parse(f"def {first}: ...").body[0])


def stub_functions():
    tree = ast.parse(STUB.read_text())
    funcs = {n.name: n for n in tree.body if isinstance(n, ast.FunctionDef)}
    methods = {(c.name, n.name): n for c in tree.body if isinstance(c, ast.ClassDef) for n in c.body
               if isinstance(n, ast.FunctionDef) and not n.name.startswith("__")
               and not any(isinstance(d, ast.Name) and d.id == "property" for d in n.decorator_list)}
    return funcs, methods


def test_stub_functions_match_the_bindings():
    funcs, _ = stub_functions()
    public = {n for n in dir(_imcol) if not n.startswith("__") and callable(getattr(_imcol, n))
              and not isinstance(getattr(_imcol, n), type)}
    assert set(funcs) == public
    for name, node in funcs.items():
        assert signature_of(node) == binding_signature(getattr(_imcol, name)), name


def test_stub_methods_match_the_bindings():
    _, methods = stub_functions()
    assert methods
    for (cls, name), node in methods.items():
        assert signature_of(node) == binding_signature(getattr(getattr(_imcol, cls), name)), f"{cls}.{name}"


# Every result column is an attribute, and dir() lists it.

def identifiers(names):
    return {n for n in names if n.isidentifier()}


def test_dir_lists_every_column_of_sweep_and_study_tables():
    r = imcol.sweep("default", values=[0.2, 0.3, 0.4], jobs=2)
    assert {"Re", "St_L", "e_status"} <= set(dir(r))
    assert identifiers(r.columns) <= set(dir(r))
    for c in identifiers(r.columns):
        assert getattr(r, c) is r.table[c]
    t = imcol.dem_fit(r)
    assert identifiers(t.columns) and identifiers(t.columns) <= set(dir(t))
    assert {"columns", "table", "info", "to_dict"} <= set(dir(t))


def test_dir_lists_every_column_of_the_precision_studies():
    wp = imcol.work_precision("default", rtols=[1e-4], integrators=["cvode-dense"], evaluators=["soe"], repeat=1,
                              ref_rtol=1e-6, jobs=1)
    assert identifiers(wp.columns) and identifiers(wp.columns) <= set(dir(wp))
    val = imcol.validate_seed(models=["seed"], jobs=2)
    assert identifiers(val.columns) and identifiers(val.columns) <= set(dir(val))
    assert {"agreement", "flow", "tolerance"} <= set(dir(val))


def test_dir_of_a_result_lists_its_summary():
    r = imcol.run("default", record="kinematics")
    assert identifiers(r.to_dict()) <= set(dir(r))
    assert {"e", "St", "trajectory", "summary", "Re", "St_L", "solver"} <= set(dir(r))
