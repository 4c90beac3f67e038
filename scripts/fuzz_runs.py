#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Seeded mutation fuzzer of whole runs: `imcol run` on mutated copies of the shipped scenes (docs/testing.md).

Each case n takes one scene of data/scenes/ (not data/scenes/flow/, which are `imcol flow` scenes), applies one to
three mutations drawn from a generator seeded by (--seed, n) alone -- numbers scaled, negated, zeroed, made nan, inf,
huge or tiny; effects dropped or added; materials swapped; spheres moved, added or removed; solver, measure, output
and model keys changed -- and runs `imcol run SCENE --out DIR --quiet --no-plot` with a CPU-time limit. Coupled
scenes (the `flow` effect) are kept on coarse grids and short t_end. Some cases write into the folder of a complete
earlier run (the default scene with its picture, or a coupled scene with its flow fields). Some meet a hostile
environment, drawn apart from the scene's mutations (so that case N's scene stays the same): a file of the user's
put into that earlier run's folder (the run must be refused, exit 2 naming --out or a bad scene key, the file and
the earlier run kept), or a standard output whose reader has gone (the run must write its folder as usual, not die of SIGPIPE).
Each case must:

  * end by itself (no signal, no timeout) with exit status 0, 2 or 3; exit 2 and 3 print exactly one line on stderr,
    `imcol: error: ...` (exit 2: `imcol: error: SCENE[:LINE]: key 'K': ...`; exit 3: `imcol: solver failure: ...`
    is also accepted, but not SUNDIALS' ILL_INPUT, which is imcol's own error); with exit 0 nothing is printed;
  * with exit 0: summary.json and trajectory.csv exist and parse, hold no NaN or infinity (null where not measured),
    the rows are in time order and the run ends by t_end, e is null only with `e_missing` and a warning, and
    e <= e_dry unless a warning says so;
  * leave a folder that is not mixed: summary.json names this scene and file, trajectory.csv starts at t = 0 with
    sphere 0 at the scene's position and velocity, no file of an earlier run is left beside them (after a failure:
    nothing, or the earlier run whole), and no `*.tmp.*` file is left in or beside the folder.

Prints one line per failing case (its number, the check, the mutations and the command that reproduces it), then
the count of cases by outcome; the exit status is 1 if any case failed.

    /usr/bin/python3 scripts/fuzz_runs.py [--runs 600] [--seed 1] [--jobs 2] [--imcol build/bin/imcol]
        [--timeout 10] [--only N[,N...]] [--keep DIR] [--verbose]

`--only N --keep DIR` reruns case N alone and keeps its scene (DIR/case_N/scene.toml) and output folder.
"""
import argparse, collections, concurrent.futures, copy, csv, json, math, os, random, shutil, subprocess, sys, tempfile
import re, signal, threading, time, tomllib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

EFFECTS = ["drag", "lubrication", "added_mass", "history", "elastic", "gravity", "flow"]
CHOICES = {  # (table, key): the scene's spellings
    ("solver", "integrator"): ["cvode", "ida"],
    ("solver", "linear_solver"): ["auto", "dense", "schur", "gmres"],
    ("measure", "e"): ["contact_ends", "fit_time", "fit_distance", "at_gap", "peak_rebound", "instant",
                       "yang_hunt_2006", "joseph_2001", "gondret_2002"],
    ("measure", "bounces"): ["first", "all"],
    ("drag", "law"): ["stokes", "schiller-naumann"],
    ("lubrication", "model"): ["brenner", "asymptotic", "seed"],
    ("added_mass", "model"): ["lagrangian", "seed"],
    ("history", "kernel"): ["basset", "mei-adrian", "kim", "dorgan-loth"],
    ("history", "evaluator"): ["soe-step", "soe", "direct"],
    ("history", "start"): ["steady", "impulsive"],
    ("history", "reynolds"): ["instantaneous", "initial"],
    ("history", "wall_correction"): ["none", "added-mass"],
    ("flow", "start"): ["impulsive", "developed"],
    ("flow", "force_in_step"): ["linear", "held"],
    ("fluid", "fluid"): ["water", "glycerol-water", "gondret-oil-20mPas", "li2010-43cP", "honey"],
}
NUMBERS = {  # (table, key): a typical value (docs/scene-reference.md, docs/coupling.md)
    ("contact", "delta_ss"): 0.017, ("contact", "delta_sl"): 0.1, ("contact", "e_dry"): 0.97, ("contact", "beta"): 200.0,
    ("lubrication", "cutoff"): 1e-4, ("lubrication", "h_c"): 1.0, ("added_mass", "dw_floor"): 0.034,
    ("history", "tolerance"): 1e-6, ("history", "modes"): 20, ("history", "min_lag"): 1e-6,
    ("history", "horizon"): 0.1, ("history", "direct_step"): 1e-5,
    ("solver", "krylov_tol"): 0.05, ("solver", "rtol"): 1e-8, ("solver", "atol"): 1e-10, ("solver", "t_end"): 0.1,
    ("solver", "max_step"): 1e-4, ("solver", "max_steps"): 100000, ("solver", "step_budget"): 1e7,
    ("measure", "window"): 0.01, ("measure", "instant_gap"): 0.017, ("measure", "stall_fraction"): 0.01,
    ("measure", "fit_distance"): 0.1, ("measure", "at_gap"): 0.1, ("measure", "ends_distance"): 0.02,
    ("measure", "ends_speed_change"): 0.25, ("measure", "ends_tolerance"): 0.02,
    ("measure", "samples_per_window"): 32, ("measure", "disagreement"): 0.05, ("measure", "max_samples"): 1e7,
    ("output", "dt"): 1e-4,
    ("flow", "cfl"): 0.5, ("flow", "tau_p_fraction"): 0.2, ("flow", "developed_distance"): 1.0,
    ("flow", "developed_time"): 0.005, ("flow", "energy_margin"): 0.25, ("flow", "speed_jump"): 3.0,
    ("flow", "speed_jump_floor"): 0.5, ("flow", "krylov_restart"): 30, ("flow", "krylov_tol"): 1e-4,
    ("flow", "ring_spacing"): 1.0, ("flow", "r_max"): 1.0, ("flow", "theta"): 0.5, ("flow", "min_gap_cells"): 3.0,
    ("flow", "dt"): 1e-3,
    ("fluid", "mass_fraction"): 0.5, ("fluid", "temperature"): 20.0,
}
SPHERE_NUMBERS = {"density": 2500.0, "youngs_modulus": 6e10, "poisson_ratio": 0.23, "e_dry": 0.95}
FACTORS = [1e-6, 1e-3, 0.1, 0.5, 0.9, 1.1, 2.0, 10.0, 1e3, 1e6]
HUGE = [1e29, 1e30, 1.0000001e30, 1e31, 1e100, 1e300, 1.7e308]
TINY = [1e-29, 1e-30, 0.9999999e-30, 1e-31, 1e-100, 1e-300, 5e-324]
NAMES = ["", "a/b", "..", "x" * 250, "tab\there", "caf\u00e9", "-dash", " space"]
COUPLED_T_END = 0.03  # s: the longest coupled run (8-12 cells/D, 2-3 levels: about 2 s at most)


def materials():
    with open(os.path.join(ROOT, "data", "materials.csv")) as f:
        rows = [line for line in f if line.strip() and not line.startswith("#")]
    return [r["material"] for r in csv.DictReader(rows)]


def base_scenes(scenes_dir):
    out = []
    for dirpath, _, files in os.walk(scenes_dir):
        if os.path.relpath(dirpath, scenes_dir).split(os.sep)[0] == "flow":
            continue  # `imcol flow` scenes
        out += [os.path.join(dirpath, f) for f in files if f.endswith(".toml")]
    return sorted(out)


# ---- TOML out ---------------------------------------------------------------------------------------------------

def toml_value(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return "nan" if math.isnan(v) else ("inf" if v == math.inf else "-inf" if v == -math.inf else repr(v))
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    raise TypeError(type(v))


def toml_text(scene):
    lines = [f"{k} = {toml_value(v)}" for k, v in scene.items() if not isinstance(v, (dict, list)) or
             (isinstance(v, list) and not (v and all(isinstance(x, dict) for x in v)))]
    for k, v in scene.items():
        if isinstance(v, dict):
            lines.append(f"\n[{k}]")
            lines += [f"{kk} = {toml_value(vv)}" for kk, vv in v.items()]
        elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            for t in v:
                lines.append(f"\n[[{k}]]")
                lines += [f"{kk} = {toml_value(vv)}" for kk, vv in t.items()]
    return "\n".join(lines) + "\n"


# ---- Mutations --------------------------------------------------------------------------------------------------

def is_number(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def numeric_leaves(scene):
    out = []
    for k, v in scene.items():
        if is_number(v):
            out.append((k,))
        elif isinstance(v, dict):
            out += [(k, kk) for kk, vv in v.items() if is_number(vv)]
        elif isinstance(v, list) and all(isinstance(x, dict) for x in v):
            for i, t in enumerate(v):
                out += [(k, i, kk) for kk, vv in t.items() if is_number(vv)]
    return out


def get(scene, path):
    for p in path:
        scene = scene[p]
    return scene


def put(scene, path, value):
    for p in path[:-1]:
        scene = scene[p]
    scene[path[-1]] = value


def name_of(path):
    """('sphere', 0, 'velocity') -> sphere[0].velocity"""
    out = ""
    for p in path:
        out += f"[{p}]" if isinstance(p, int) else (f".{p}" if out else p)
    return out


def new_number(rng, x):
    """A mutated number and how it was made."""
    kind = rng.choice(["factor", "factor", "factor", "negate", "zero", "nan", "inf", "huge", "tiny", "type"])
    if kind == "factor":
        f = rng.choice(FACTORS)
        return x * f, f"x{f:g}"
    if kind == "negate":
        return -x, "negated"
    if kind == "zero":
        return rng.choice([0, 0.0, -0.0]), "0"
    if kind == "nan":
        return math.nan, "nan"
    if kind == "inf":
        return rng.choice([math.inf, -math.inf]), "inf"
    if kind == "huge":
        return rng.choice([1, -1, 1]) * rng.choice(HUGE), "huge"
    if kind == "tiny":
        return rng.choice([1, -1, 1]) * rng.choice(TINY), "tiny"
    t = rng.choice(["int", "string", "bool", "list"])
    return {"int": int(x) if math.isfinite(x) and abs(x) < 1e18 else 1, "string": str(x), "bool": True,
            "list": [x]}[t], t


def spheres(scene):
    s = scene.get("sphere")
    return s if isinstance(s, list) else []


def m_number(rng, scene):
    leaves = numeric_leaves(scene)
    if not leaves:
        return None
    path = rng.choice(leaves)
    v, how = new_number(rng, get(scene, path))
    put(scene, path, v)
    return f"{name_of(path)} {how} -> {toml_value(v)}"


def set_key(scene, table, key, v):
    """Sets table.key = v (creating the table); False where `table` is not a table in this scene."""
    scene.setdefault(table, {})
    if not isinstance(scene[table], dict):
        return False
    scene[table][key] = v
    return True


def m_add_number(rng, scene):
    (table, key), typical = rng.choice(list(NUMBERS.items()))
    if table == "flow" and "flow" not in toml_effects(scene) and rng.random() < 0.8:
        return None  # a [flow] table without the effect is refused at once
    if rng.random() < 0.5:
        v, how = typical, "typical"
    else:
        v, how = new_number(rng, typical)
    if not set_key(scene, table, key, v):
        return None
    return f"{table}.{key} set ({how}) -> {toml_value(v)}"


def m_choice(rng, scene):
    (table, key), names = rng.choice(list(CHOICES.items()))
    if table == "flow" and "flow" not in toml_effects(scene) and rng.random() < 0.8:
        return None
    v = rng.choice(names + ["bogus", ""]) if rng.random() < 0.2 else rng.choice(names)
    if not set_key(scene, table, key, v):
        return None
    return f"{table}.{key} = {toml_value(v)}"


def m_effects(rng, scene):
    eff = scene.get("effects")
    if not isinstance(eff, list):  # the default list (docs/scene-reference.md)
        eff = ["drag", "lubrication", "added_mass", "history", "elastic"] + (["gravity"] if "gravity" in scene else [])
    eff = list(eff)
    kind = rng.choice(["drop", "drop", "add", "add", "omit", "empty", "bogus", "duplicate"])
    if kind == "drop" and eff:
        e = rng.choice(eff)
        eff.remove(e)
        what = f"effect {e} dropped"
    elif kind == "add":
        e = rng.choice([e for e in EFFECTS if e not in eff] or EFFECTS)
        if e == "flow" and rng.random() < 0.7:
            e = "gravity"  # coupled runs are the slow ones
        eff.append(e)
        if e == "gravity" and "gravity" not in scene:
            scene["gravity"] = rng.choice([-9.81, 9.81])
        what = f"effect {e} added"
    elif kind == "omit":
        scene.pop("effects", None)
        return "effects omitted"
    elif kind == "empty":
        eff = []
        what = "effects = []"
    elif kind == "bogus":
        eff.append("bogus")
        what = "effect bogus added"
    else:
        eff.append(eff[0] if eff else "drag")
        what = "an effect repeated"
    scene["effects"] = eff
    return what


def m_material(rng, scene, mats):
    bodies = [("sphere", i) for i in range(len(spheres(scene)))] + ([("wall",)] if isinstance(scene.get("wall"), dict) else [])
    if not bodies:
        return None
    path = rng.choice(bodies)
    body = get(scene, path)
    kind = rng.choice(["swap", "swap", "swap", "bogus", "inline", "override", "drop"])
    if kind == "swap":
        body["material"] = rng.choice(mats)
        return f"{name_of(path + ('material',))} = {body['material']}"
    if kind == "bogus":
        body["material"] = rng.choice(["unobtainium", "", "Steel"])
        return f"{name_of(path + ('material',))} = {json.dumps(body['material'])}"
    if kind == "drop":
        body.pop("material", None)
        return f"{name_of(path + ('material',))} dropped"
    if kind == "inline":
        body.pop("material", None)
        for k, v in SPHERE_NUMBERS.items():
            if rng.random() < 0.8:
                body[k] = v
        return f"{name_of(path)}: inline properties {sorted(k for k in SPHERE_NUMBERS if k in body)}"
    k = rng.choice(list(SPHERE_NUMBERS))
    body[k], how = (SPHERE_NUMBERS[k], "typical") if rng.random() < 0.5 else new_number(rng, SPHERE_NUMBERS[k])
    return f"{name_of(path + (k,))} ({how}) -> {toml_value(body[k])}"


def m_geometry(rng, scene):
    sph = spheres(scene)
    kind = rng.choice(["move", "move", "move", "swap", "drop_target", "sphere_for_wall", "third", "drop_sphere_key"])
    if not sph:
        return None
    d0 = sph[0].get("diameter", 0.01)
    d0 = d0 if is_number(d0) and math.isfinite(d0) and d0 > 0 else 0.01
    if kind == "move":
        i = rng.randrange(len(sph) + (1 if isinstance(scene.get("wall"), dict) else 0))
        body = sph[i] if i < len(sph) else scene["wall"]
        p = body.get("position", 0.0)
        p = p if is_number(p) and math.isfinite(p) else 0.0
        dz = d0 * rng.choice([-2.0, -0.5, -0.1, -0.01, -1e-4, 1e-4, 0.01, 0.1, 0.5, 2.0, 10.0])
        body["position"] = p + dz
        return f"{'sphere[%d]' % i if i < len(sph) else 'wall'}.position moved by {dz / d0:g} D"
    if kind == "swap" and len(sph) >= 2:
        sph[0]["position"], sph[1]["position"] = sph[1].get("position", 0.0), sph[0].get("position", 0.0)
        return "sphere[0] and sphere[1] positions swapped"
    if kind == "drop_target":
        if len(sph) >= 2 and rng.random() < 0.5:
            del sph[1:]
            return "target sphere removed"
        if "wall" in scene:
            del scene["wall"]
            return "wall removed"
        return None
    if kind == "sphere_for_wall" and isinstance(scene.get("wall"), dict) and len(sph) == 1:
        wall = scene.pop("wall")
        wp = wall.get("position", 0.0)
        wp = wp if is_number(wp) and math.isfinite(wp) else 0.0
        d1 = d0 * rng.choice([0.5, 1.0, 2.0])
        sph.append({"material": wall.get("material", "glass"), "diameter": d1, "position": wp + 0.5 * d1,
                    "velocity": rng.choice([0.0, 0.0, -0.05])})
        return f"wall replaced by a sphere of {d1 / d0:g} D"
    if kind == "third":
        last = sph[-1]
        t = dict(last)
        lp = last.get("position", 0.0)
        t["position"] = (lp if is_number(lp) and math.isfinite(lp) else 0.0) + 3 * d0
        sph.append(t)
        return "a third sphere added"
    i = rng.randrange(len(sph))
    k = rng.choice(["position", "diameter", "velocity", "material"])
    sph[i].pop(k, None)
    return f"sphere[{i}].{k} dropped"


def m_drop(rng, scene):
    tables = [k for k, v in scene.items() if isinstance(v, dict) and v]
    if rng.random() < 0.3 and tables:
        t = rng.choice(tables + ["fluid"])
        scene.pop(t, None)
        return f"[{t}] dropped"
    if not tables:
        return None
    t = rng.choice(tables)
    k = rng.choice(list(scene[t]))
    del scene[t][k]
    return f"{t}.{k} dropped"


def m_unknown(rng, scene):
    tables = [k for k, v in scene.items() if isinstance(v, dict)]
    if tables and rng.random() < 0.7:
        t = rng.choice(tables)
        scene[t]["bogus_key"] = 1.0
        return f"{t}.bogus_key added"
    scene["bogus_key"] = 1.0
    return "bogus_key added"


def m_name(rng, scene):
    scene["name"] = rng.choice(NAMES)
    return f"name = {json.dumps(scene['name'])}"


def m_pointwise(rng, scene):
    """A moderate, mostly valid change of one physical number: the runs that get deep."""
    sph = spheres(scene)
    opts = [("fluid", "viscosity"), ("fluid", "density")] if isinstance(scene.get("fluid"), dict) else []
    opts += [("sphere", i, k) for i in range(len(sph)) for k in ("velocity", "diameter")]
    if rng.random() < 0.3:  # any number of the scene: tolerances, windows, contact and flow settings
        opts = [p for p in numeric_leaves(scene) if p[0] != "sphere" or p[-1] != "position"] or opts
    if not opts:
        return None
    path = rng.choice(opts)
    try:
        x = get(scene, path)
    except (KeyError, IndexError):
        return None
    if not is_number(x):
        return None
    f = rng.choice([0.3, 0.5, 0.7, 1.5, 2.0, 3.0]) * (rng.choice([1, -1]) if path[-1] == "velocity" else 1)
    put(scene, path, x * f)
    return f"{name_of(path)} x{f:g}"


MUTATIONS = [(m_number, 6), (m_pointwise, 5), (m_add_number, 3), (m_choice, 4), (m_effects, 3), (m_material, 3),
             (m_geometry, 3), (m_drop, 1), (m_unknown, 1), (m_name, 1)]


GENTLE = [(m_pointwise, 4), (m_choice, 1), (m_material, 1)]


def coarse_flow(rng, scene):
    """A coupled scene on a coarse grid and a short t_end (about 2 s at most); invalid values are left alone."""
    flow = scene.setdefault("flow", {})
    if not isinstance(flow, dict):
        return
    c = flow.get("cells_per_diameter")
    if c is None or (is_number(c) and isinstance(c, int) and c > 12):
        flow["cells_per_diameter"] = rng.choice([8, 8, 8, 12])
    lv = flow.get("levels")
    if lv is None or (isinstance(lv, int) and not isinstance(lv, bool) and lv > 3):
        flow["levels"] = rng.choice([2, 3])
    flow.setdefault("fields", rng.random() < 0.3)
    # imcol's own guard refuses a run estimated above 3.6 s (exit 2); a run that then exceeds the CPU limit is an
    # estimate that was off by a factor of about 3.
    flow.setdefault("max_wall_hours", 0.001)
    solver = scene.setdefault("solver", {})
    if isinstance(solver, dict):
        t = solver.get("t_end", 1.0)
        if not is_number(t) or not math.isfinite(t) or t > COUPLED_T_END:
            if not is_number(t) or math.isnan(t) or t > 0:
                solver["t_end"] = COUPLED_T_END * rng.choice([0.4, 1.0])
    dt = flow.get("dt")
    if is_number(dt) and math.isfinite(dt) and 0 < dt < COUPLED_T_END / 400:
        flow["dt"] = COUPLED_T_END / 400
    for k in ("developed_time", "developed_distance"):  # the start-up runs the kernel too
        v = flow.get(k)
        if is_number(v) and math.isfinite(v) and v > (0.005 if k == "developed_time" else 1.0):
            flow[k] = 0.005 if k == "developed_time" else 1.0


def make_case(seed, n, bases, mats):
    rng = random.Random(f"imcol-fuzz/{seed}/{n}")
    coupled = [b for b in bases if "flow" in toml_effects(b[1])]
    plain = [b for b in bases if b not in coupled]
    is_coupled = rng.random() < 0.12
    path, base = rng.choice(coupled) if is_coupled else rng.choice(plain)
    scene = copy.deepcopy(base)
    muts = []
    # Half the coupled cases change physics only, so that enough of them run to the end.
    mutations = GENTLE if is_coupled and rng.random() < 0.5 else MUTATIONS
    for _ in range(rng.choice([1, 1, 2, 2, 2, 3])):
        fns, weights = zip(*mutations)
        fn = rng.choices(fns, weights)[0]
        d = fn(rng, scene, mats) if fn is m_material else fn(rng, scene)
        if d:
            muts.append(d)
    if "flow" in toml_effects(scene):
        coarse_flow(rng, scene)
    reuse = rng.choice([0, 1]) if rng.random() < 0.15 else None  # which earlier run's folder, if any
    return os.path.relpath(path, ROOT), scene, muts, reuse


def make_hazard(seed, n, reuse):
    """The case's hostile environment, or None: drawn from a generator of its own, so the scene is the same with or without."""
    rng = random.Random(f"imcol-fuzz-environment/{seed}/{n}")
    x = rng.random()
    if reuse is not None and x < 0.3:
        return "foreign file"
    return "closed stdout" if x > 0.92 else None


def toml_effects(scene):
    e = scene.get("effects")
    return e if isinstance(e, list) else []


# ---- Checks -----------------------------------------------------------------------------------------------------

class Failure(Exception):
    def __init__(self, check, detail):
        super().__init__(f"{check}: {detail}")
        self.check = check


def no_non_finite(x, where):
    if isinstance(x, float) and not math.isfinite(x):
        raise Failure("non-finite number", f"{where} = {x}")
    if isinstance(x, dict):
        for k, v in x.items():
            no_non_finite(v, f"{where}.{k}")
    if isinstance(x, list):
        for i, v in enumerate(x):
            no_non_finite(v, f"{where}[{i}]")


def read_output(out):
    """(summary, header, first row) of a complete output folder; raises Failure if it is not one."""
    sp, tp = os.path.join(out, "summary.json"), os.path.join(out, "trajectory.csv")
    for p in (sp, tp):
        if not os.path.isfile(p):
            raise Failure("missing file", os.path.basename(p))
    try:
        with open(sp) as f:
            summary = json.load(f, parse_constant=lambda c: float(c))
    except (ValueError, UnicodeDecodeError) as e:
        raise Failure("summary.json does not parse", str(e)[:120])
    no_non_finite(summary, "summary")
    with open(tp, newline="") as f:
        rows = list(csv.reader(f))
    if len(rows) < 2 or not rows[0] or rows[0][0] != "t":
        raise Failure("trajectory.csv does not parse", f"{len(rows)} lines, header {rows[0][:3] if rows else None}")
    width = len(rows[0])
    t_prev = -math.inf
    for i, r in enumerate(rows[1:], 2):
        if len(r) != width:
            raise Failure("trajectory.csv does not parse", f"line {i} has {len(r)} fields, the header {width}")
        for h, cell in zip(rows[0], r):
            try:
                v = float(cell)
            except ValueError:
                raise Failure("trajectory.csv does not parse", f"line {i} {h} = {cell!r}")
            if not math.isfinite(v):
                raise Failure("non-finite number", f"trajectory.csv line {i} {h} = {cell}")
        if float(r[0]) < t_prev:
            raise Failure("trajectory.csv goes back in time", f"line {i} t = {r[0]} after {t_prev}")
        t_prev = float(r[0])
    return summary, rows[0], rows[1]


def same(a, b, scale):
    """a and b agree to 1e-9 of the larger of them and the scale (the trajectory is written to 12 digits)."""
    return abs(a - b) <= 1e-9 * max(abs(a), abs(b), scale)


def check_matches(summary, header, row, scene, scene_path, expect_name):
    if summary.get("scene") != expect_name:
        raise Failure("mixed folder", f"summary.json scene {summary.get('scene')!r}, expected {expect_name!r}")
    if os.path.abspath(summary.get("scene_file", "")) != os.path.abspath(scene_path):
        raise Failure("mixed folder", f"summary.json scene_file {summary.get('scene_file')!r}")
    first = dict(zip(header, map(float, row)))
    t_end = scene.get("solver", {}).get("t_end", 1.0) if isinstance(scene.get("solver"), dict) else 1.0
    t_final = (summary.get("solver") or {}).get("t_final_s")
    if is_number(t_end) and is_number(t_final) and t_final > t_end * (1 + 1e-9):
        raise Failure("ran past t_end", f"solver.t_final_s = {t_final}, t_end = {t_end}")
    s0 = spheres(scene)[0]
    want = {"t": 0.0, "z1": float(s0["position"]), "u1": float(s0.get("velocity", 0.0))}
    history = scene.get("history") if isinstance(scene.get("history"), dict) else {}
    if history.get("start") == "impulsive":
        del want["u1"]  # the start-up momentum below the force floor is given at t = 0 (contact/history_force.cpp)
    scale = {"t": 0.0, "z1": float(s0["diameter"]), "u1": 0.0}  # a position of 1e-29 m beside others of 1e-2 m is 0
    for k, v in want.items():
        if k not in first or not same(first[k], v, scale[k]):
            raise Failure("trajectory.csv does not start at the scene", f"first row {k} = {first.get(k)}, scene {v}")


def check_exit0(summary):
    warnings = summary.get("warnings") or []
    e = summary.get("e", "absent")
    if e == "absent":
        raise Failure("summary.json has no e", "")
    if e is None:
        if not summary.get("e_missing") or not warnings:
            raise Failure("e null without a reason", f"e_missing {summary.get('e_missing')!r}, {len(warnings)} warnings")
        return
    e_dry = (summary.get("contact") or {}).get("e_dry")
    if e_dry is not None and e > e_dry * (1 + 1e-9) and not any("e_dry" in w for w in warnings):
        raise Failure("e above e_dry without a warning", f"e = {e}, e_dry = {e_dry}")
    if e < 0:
        raise Failure("negative e", f"e = {e}")


def stray_tmp(dirs):
    out = []
    for d in dirs:
        if os.path.isdir(d):
            for dp, dirs, files in os.walk(d):
                out += [os.path.join(dp, f) for f in files + dirs if ".tmp." in f]
    return sorted(set(out))


def wall_limit(a):
    """s: a backstop for a run that waits without computing (a loaded machine stretches the CPU limit 10-fold)."""
    return max(300.0, 30 * a.timeout)


def run_timed(cmd, prefix, wall_limit, closed_stdout=False):
    """(exit code or None if killed at the wall-clock limit, stderr, stdout, CPU seconds of the run itself).
    closed_stdout: the run's standard output is a pipe whose read end is already closed (stdout is then "")."""
    with open(prefix + ".out", "w+") as fo, open(prefix + ".err", "w+") as fe:
        if closed_stdout:
            r, w = os.pipe()
            os.close(r)
            try:
                p = subprocess.Popen(cmd, stdout=w, stderr=fe)
            finally:
                os.close(w)
        else:
            p = subprocess.Popen(cmd, stdout=fo, stderr=fe)
        timer = threading.Timer(wall_limit, p.kill)
        timer.start()
        _, status, usage = os.wait4(p.pid, 0)  # the rusage of this child alone (sh execs imcol: the same process)
        p.returncode = rc = os.waitstatus_to_exitcode(status)
        killed = not timer.is_alive()
        timer.cancel()
        fo.seek(0)
        fe.seek(0)
        return (None if killed else rc), fe.read(), fo.read(), usage.ru_utime + usage.ru_stime


# One function (91 lines): a case's mutation, run and every check on its outcome read as one story of that case.
def run_case(a, n, bases, mats, work, templates):
    base, scene, muts, reuse = make_case(a.seed, n, bases, mats)
    cdir = os.path.join(work, f"case_{n}")
    shutil.rmtree(cdir, ignore_errors=True)
    os.makedirs(cdir)
    spath = os.path.join(cdir, "scene.toml")
    with open(spath, "w") as f:
        f.write(toml_text(scene))
    out = os.path.join(cdir, "out")
    template = templates[reuse] if reuse is not None else None
    hazard = make_hazard(a.seed, n, reuse)
    if template:
        shutil.copytree(template["dir"], out)  # copy2: the earlier run's files keep their times
    user_file = os.path.join(out, "experiment_2019.csv")
    if hazard == "foreign file":
        with open(user_file, "w") as f:
            f.write("t,z\n0,1\n")
    # The time limit is on CPU time (ulimit -t: SIGXCPU), so that a loaded machine does not fail cases; the wall
    # clock limit is a backstop for a run that waits without computing.
    cmd = ["/bin/sh", "-c", f'ulimit -S -t {max(1, math.ceil(a.timeout))} && exec "$0" "$@"',
           a.imcol, "run", spath, "--out", out, "--no-plot"] + ([] if hazard == "closed stdout" else ["--quiet"])
    t0, started_ns = time.monotonic(), time.time_ns()
    rc, err, sout, cpu = run_timed(cmd, os.path.join(cdir, "std"), wall_limit(a), hazard == "closed stdout")
    wall = time.monotonic() - t0
    desc = f"{base}: " + ("; ".join(muts) or "unchanged") + (f" [into the folder of an earlier run of {template['label']}]" if template else "")
    desc += f" [{hazard}]" if hazard else ""
    try:
        if rc is None:
            raise Failure("timeout", f"more than {wall_limit(a):g} s of wall time")
        if rc == -signal.SIGXCPU:
            raise Failure("timeout", f"more than {math.ceil(a.timeout)} s of CPU time")
        if rc < 0:
            raise Failure("signal", f"killed by signal {-rc}: {err.strip()[-200:]}")
        if rc not in (0, 2, 3):
            raise Failure(f"exit {rc}", err.strip().splitlines()[-1][:200] if err.strip() else "(no message)")
        lines = err.splitlines()
        if hazard == "foreign file":  # refused before anything runs (or the scene first), the user's file and the earlier run kept
            if rc != 2 or len(lines) != 1 or not lines[0].startswith("imcol: error: "):
                raise Failure("a folder holding a user's file was not refused", f"exit {rc}: {err.strip()[:200]!r}")
            with open(user_file) as f:
                if f.read() != "t,z\n0,1\n":
                    raise Failure("the user's file changed", user_file)
            s, h, r = read_output(out)
            check_matches(s, h, r, template["scene"], template["path"], template["name"])
            return n, "refused: a user's file in --out", None, desc, (wall, cpu), err.strip()
        if hazard == "closed stdout":
            lines = [ln for ln in lines if not ln.startswith("imcol: warning: ")]  # without --quiet, warnings are said
        if rc in (2, 3):
            ok = ("imcol: error: ",) + (("imcol: solver failure: ",) if rc == 3 else ())
            if len(lines) != 1 or not lines[0].startswith(ok):
                raise Failure(f"exit {rc} message", f"{len(lines)} stderr lines: {err.strip()[:200]!r}")
            # ILL_INPUT is SUNDIALS refusing what imcol gave it: a defect of the program, not a failure of the solver.
            if rc == 3 and "ILL_INPUT" in lines[0]:
                raise Failure("integrator refused its input", lines[0][:200])
            # Bad input is in the scene (the only input): the message names the file, maybe a line, and a key.
            if rc == 2 and not re.match(r"imcol: error: " + re.escape(spath) + r"(:\d+)?: key '[^']*': \S", lines[0]):
                raise Failure("exit 2 message does not name the scene and a key", lines[0][:200])
        elif hazard != "closed stdout" and err.strip():
            raise Failure("stderr with --quiet", err.strip()[:200])
        if rc == 0 and sout.strip():
            raise Failure("stdout with --quiet", sout.strip()[:200])
        tmp = stray_tmp([out, cdir])
        if tmp:
            raise Failure("stray tmp file", os.path.relpath(tmp[0], cdir))
        if rc == 0:
            summary, header, row = read_output(out)
            name = scene.get("name") if isinstance(scene.get("name"), str) else "scene"
            check_matches(summary, header, row, scene, spath, name)
            check_exit0(summary)
            if template:  # nothing may be left of the earlier run
                stale = sorted(f for f in os.listdir(out) if os.stat(os.path.join(out, f)).st_mtime_ns < started_ns)
                if stale:
                    raise Failure("mixed folder", f"left from the earlier run: {', '.join(stale)}")
            outcome = "exit 0, e null" if summary.get("e") is None else "exit 0"
        else:
            present = [f for f in ("summary.json", "trajectory.csv") if os.path.exists(os.path.join(out, f))]
            if template:  # the earlier run whole, or nothing
                if present:
                    s, h, r = read_output(out)
                    check_matches(s, h, r, template["scene"], template["path"], template["name"])
            elif present:
                raise Failure("output of a failed run", f"{', '.join(present)} written")
            # Not a failure, but worth a look: a scene the reader accepted that the solver cannot even start.
            outcome = f"exit {rc}" + (" at t = 0" if rc == 3 and "at t = 0 s" in err else "")
        return n, outcome, None, desc, (wall, cpu), err.strip()
    except Failure as f:
        return n, "FAIL " + f.check, str(f), desc, (wall, cpu), err.strip()
    except Exception as e:  # a case the checks did not foresee (e.g. exit 0 for a scene without sphere 0)
        return n, "FAIL unforeseen", f"unforeseen: {type(e).__name__}: {e}", desc, (wall, cpu), err.strip()
    finally:
        if not a.keep:
            shutil.rmtree(cdir, ignore_errors=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", type=int, default=600, help="cases 0 .. runs-1")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--only", default=None, help="comma-separated case numbers (reproduce a failure)")
    ap.add_argument("--jobs", type=int, default=1, help="cases run at once")
    ap.add_argument("--imcol", default=os.path.join(ROOT, "build", "bin", "imcol"))
    ap.add_argument("--scenes", default=os.path.join(ROOT, "data", "scenes"))
    ap.add_argument("--timeout", type=float, default=10.0, help="CPU seconds per run")
    ap.add_argument("--keep", default=None, help="keep every case's scene and output folder here")
    ap.add_argument("--verbose", action="store_true", help="one line per case, not only the failures")
    a = ap.parse_args()
    a.imcol = os.path.abspath(a.imcol)
    mats = materials()
    bases = []
    for p in base_scenes(a.scenes):
        with open(p, "rb") as f:
            bases.append((p, tomllib.load(f)))
    work = os.path.abspath(a.keep) if a.keep else tempfile.mkdtemp(prefix="imcol_fuzz_runs_")
    os.makedirs(work, exist_ok=True)
    # The earlier runs that some cases write over: the default scene with its picture, and a coupled scene on a
    # coarse grid with its flow fields.
    templates = []
    for i, (rel, extra) in enumerate([("default.toml", []),
                                      ("coupled/gg3462.toml", ["--no-plot", "--set", "flow.cells_per_diameter=8",
                                                               "--set", "flow.levels=2"])]):
        tpath = os.path.join(a.scenes, rel)
        with open(tpath, "rb") as f:
            tscene = tomllib.load(f)
        t = {"dir": os.path.join(work, f"earlier_run_{i}"), "path": tpath, "scene": tscene, "label": rel,
             "name": tscene.get("name", os.path.splitext(os.path.basename(rel))[0])}
        shutil.rmtree(t["dir"], ignore_errors=True)
        subprocess.run([a.imcol, "run", tpath, "--out", t["dir"], "--quiet"] + extra, check=True)
        templates.append(t)
    cases = [int(x) for x in a.only.split(",")] if a.only else range(a.runs)
    t0 = time.monotonic()
    counts, failures, cpu_total, slowest = collections.Counter(), 0, 0.0, (0.0, None)
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as pool:
        futs = [pool.submit(run_case, a, n, bases, mats, work, templates) for n in cases]
        for fut in futs:
            n, outcome, problem, desc, (wall, cpu), err = fut.result()
            cpu_total += cpu
            slowest = max(slowest, (cpu, n))
            counts[outcome] += 1
            if problem:
                failures += 1
                print(f"FAIL case {n}: {problem} | {desc} | {wall:.2f} s, {cpu:.2f} s CPU | "
                      f"repeat: scripts/fuzz_runs.py --seed {a.seed} --only {n} --keep DIR", flush=True)
            elif a.verbose:
                print(f"case {n}: {outcome} ({wall:.2f} s, {cpu:.2f} s CPU) | {desc}" + (f" | {err[:160]}" if err else ""), flush=True)
    if not a.keep:
        shutil.rmtree(work, ignore_errors=True)
    total = sum(counts.values())
    print(f"{total} cases (seed {a.seed}) in {time.monotonic() - t0:.1f} s ({cpu_total:.1f} s CPU in imcol, the most "
          f"{slowest[0]:.2f} s in case {slowest[1]}): " +
          ", ".join(f"{k}: {v}" for k, v in sorted(counts.items())))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
