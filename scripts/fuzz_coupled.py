#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Fuzzed coupled runs (docs/coupling.md "Divergence"): random sphere-wall and sphere-sphere scenes, coarse grids, the
default flow step, in three kinds (a third each): "moving" (the impact sphere at U, Re 5-1000), "low-Re" (the same at
Re 0.05-5) and "from rest" (released from rest under gravity toward the target, terminal Re 0.05-1000 on the standard
drag curve). Each run must end sane (finite e in [0, e_dry], or e = null with a warning saying why; no sphere faster
than the available energy allows) or with exit 3 naming its cause. Prints one line a run and the counts by outcome,
also by kind; one run at a time.

    /usr/bin/python3 scripts/fuzz_coupled.py [--runs 300] [--seed 1] [--imcol build/bin/imcol] [--out DIR]
"""
import argparse, collections, json, math, os, random, shutil, subprocess, sys, tempfile

MATERIALS = {"steel": 7800.0, "glass": 2500.0, "nylon": 1140.0}

def cd_standard(re):
    """Standard drag curve (Clift, Grace & Weber 1978), as flow::standard_drag_coefficient."""
    w = math.log10(re)
    if re < 20:
        return 24 / re * (1 + 0.1315 * re ** (0.82 - 0.05 * w))
    if re <= 260:
        return 24 / re * (1 + 0.1935 * re ** 0.6305)
    return 10 ** (1.6435 - 1.1242 * w + 0.1558 * w * w)

def scene(rng):
    kind = rng.choice(["moving", "low-Re", "from rest"])
    pair = rng.random() < 0.5
    mat1 = rng.choice(list(MATERIALS))
    d1 = rng.uniform(0.003, 0.015)
    rho_f = rng.uniform(800.0, 1300.0)
    rho_p = MATERIALS[mat1]
    effects = ["drag", "lubrication", "added_mass", "history", "elastic", "flow"]
    head = []
    if kind == "from rest":
        while abs(rho_p - rho_f) < 100:
            rho_f = rng.uniform(800.0, 1300.0)
        re = math.exp(rng.uniform(math.log(0.05), math.log(1000.0)))  # terminal Re: mu from C_D Re^2 = 4/3 Ar
        mu = math.sqrt(abs(rho_p - rho_f) * rho_f * 9.81 * d1 ** 3 / (0.75 * cd_standard(re) * re * re))
        u_t = re * mu / (rho_f * d1)
        u = 0.0
        g_eff = abs(rho_p - rho_f) * 9.81 / (rho_p + 0.5 * rho_f)
        effects.append("gravity")
        head = [f"gravity = {9.81 if rho_p > rho_f else -9.81}"]  # + is toward the target
    else:
        u = rng.uniform(0.05, 1.0)
        lo, hi = (5.0, 1000.0) if kind == "moving" else (0.05, 5.0)
        re = math.exp(rng.uniform(math.log(lo), math.log(hi)))
        mu = rho_f * u * d1 / re
    gap = rng.uniform(0.3, 2.0) * d1
    cells = rng.choice([12, 16])
    lines = ['name = "fuzz"', f"effects = {json.dumps(effects)}"] + head + [
             "[fluid]", f"density = {rho_f:.6g}", f"viscosity = {mu:.6g}",
             "[[sphere]]", f'material = "{mat1}"', f"diameter = {d1:.6g}", "position = 0.0", f"velocity = {u:.6g}"]
    if pair:
        mat2 = rng.choice(list(MATERIALS))
        d2 = d1 * rng.uniform(0.6, 1.6)
        u2 = 0.0 if kind == "from rest" else rng.choice([0.0, 0.0, -rng.uniform(0.0, 0.5) * u])
        lines += ["[[sphere]]", f'material = "{mat2}"', f"diameter = {d2:.6g}", f"position = {0.5 * d1 + gap + 0.5 * d2:.6g}",
                  f"velocity = {u2:.6g}"]
    else:
        lines += ["[wall]", 'material = "glass"', f"position = {0.5 * d1 + gap:.6g}"]
    if kind == "from rest":  # time to reach U_t, then the gap and the rebound at U_t
        t_end = 2 * u_t / g_eff + 2 * gap / u_t + 0.02 + 4 * d1 / u_t
    else:
        t_end = gap / u + 0.02 + 4 * d1 / u
    lines += ["[flow]", f"cells_per_diameter = {cells}", "levels = 3", "fields = false",
              "[solver]", f"t_end = {t_end:.6g}",
              "[measure]", 'bounces = "first"']
    what = f"U_t={u_t:.3g}" if kind == "from rest" else f"u={u:.3f}"
    desc = f"{kind} {'pair' if pair else 'wall'} {mat1} d={d1*1e3:.1f}mm {what} Re={re:.3g} rho_f={rho_f:.0f} cells={cells}"
    return "\n".join(lines) + "\n", desc, kind

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=300)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--imcol", default="build/bin/imcol")
    ap.add_argument("--out", default=None, help="keep the scenes and summaries here")
    a = ap.parse_args()
    rng = random.Random(a.seed)
    work = a.out or tempfile.mkdtemp(prefix="imcol_fuzz_")
    os.makedirs(work, exist_ok=True)
    counts, by_kind = collections.Counter(), collections.Counter()
    for k in range(a.runs):
        text, desc, skind = scene(rng)
        path = os.path.join(work, f"s{k:03d}.toml")
        with open(path, "w") as f:
            f.write(text)
        out = os.path.join(work, f"o{k:03d}")
        p = subprocess.run([a.imcol, "run", path, "--no-plot", "--quiet", "--out", out], capture_output=True, text=True)
        if p.returncode == 0:
            s = json.load(open(os.path.join(out, "summary.json")))
            e, e_dry = s.get("e"), s.get("contact", {}).get("e_dry", 1.0)
            ratio = s["flow"].get("max_energy_ratio", 0.0)
            if e is None:
                outcome = "e null: " + ("; ".join(s.get("warnings", []))[:60] or "no reason given")
                kind = "e null, reason stated" if s.get("warnings") else "e null, NO REASON"
            elif 0 <= e <= e_dry * (1 + 1e-9) and ratio <= 1.0 + 1e-9:
                outcome, kind = f"e = {e:.4f}", "sane e"
            else:
                outcome, kind = f"e = {e:.4f} (e_dry {e_dry}), energy ratio {ratio:.3g}", "NOT SANE"
        elif p.returncode == 3:
            msg = p.stderr.strip().splitlines()[-1] if p.stderr.strip() else ""
            kind = "exit 3, flow coupling" if "flow coupling" in msg else "exit 3, other"
            outcome = msg[:160]
        else:
            msg = p.stderr.strip().splitlines()[-1] if p.stderr.strip() else ""
            kind, outcome = f"exit {p.returncode}", msg[:160]
        counts[kind] += 1
        by_kind[(skind, kind)] += 1
        print(f"{k:3d} {desc}: {kind}: {outcome}", flush=True)
        if not a.out:
            shutil.rmtree(out, ignore_errors=True)
    print("counts:", dict(counts))
    for k in sorted(by_kind):
        print(f"  {k[0]}: {k[1]}: {by_kind[k]}")
    if not a.out:
        shutil.rmtree(work, ignore_errors=True)

if __name__ == "__main__":
    sys.exit(main())
