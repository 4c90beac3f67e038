# SPDX-License-Identifier: BSD-3-Clause
"""A coupled sphere-wall run (Gondret et al.'s St = 27 case with the flow kernel, on a coarse grid): the kernel's
force f_SIM against the analytic forces f_THR, and the blend H that weighs them, f = H f_THR + (1 - H) f_SIM
(docs/coupling.md).
Within a cell or two of the wall f_SIM departs from f_THR: the grid does not resolve the gap; H hands the force to
f_THR from a gap of 2 delta_SL in.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/coupled_forces.py --out out/examples
"""
import argparse
import json
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

import imcol

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--out", default="out/examples", help="folder for the picture and its data")
parser.add_argument("--cells", type=int, default=8, help="flow cells per diameter (the scene has 16)")
args = parser.parse_args()
out = pathlib.Path(args.out)
out.mkdir(parents=True, exist_ok=True)

scene = imcol.Scene.load("coupled/gondret_st27")
scene.set("flow.cells_per_diameter", args.cells).set("measure.bounces", "first")
result = imcol.run(scene)
tr = result.trajectory  # with the flow effect: f_sim1, f_thr1 and H
# H = 1/2 at gap delta_sl, 0 beyond 2 delta_sl (the model block holds text)
delta_sl = float(result.model["blend.delta_sl_m"])

fig, (ax_t, ax_g) = plt.subplots(1, 2, figsize=(11, 4.5), constrained_layout=True)
approach = tr["t"] <= result.contact.t_contact_s
for ax, x, label, keep in ((ax_t, tr["t"] * 1e3, "t (ms)", slice(None)),
                          (ax_g, tr["gap"] * 1e3, "gap (mm), approaching the wall", approach)):
    ax.plot(x[keep], tr["f_sim1"][keep], label="f_SIM (flow kernel)")
    ax.plot(x[keep], tr["f_thr1"][keep], "--", label="f_THR (analytic)")
    ax.set_xlabel(label)
    ax.set_ylabel("force on the sphere (N)")
    h = ax.twinx()
    h.plot(x[keep], tr["H"][keep], color="0.5", lw=1)
    h.set_ylim(-0.02, 1.02)
    h.set_ylabel("H (grey)")
ax_g.set_xscale("log")
ax_g.invert_xaxis()
for g in (delta_sl, 2 * delta_sl):
    ax_g.axvline(g * 1e3, color="0.8", lw=0.8)
ax_t.legend(fontsize=8)
fig.suptitle(f"{result.scene}, {result.flow.grid.cells_per_diameter} cells/D: e = {result.e:.3f}, St = {result.St:.1f}, "
             f"{result.flow.steps} flow steps")
fig.savefig(out / "coupled_forces.png", dpi=120)

(out / "coupled_forces.json").write_text(json.dumps(
    {"scene": "coupled/gondret_st27", "set": {"flow.cells_per_diameter": args.cells, "measure.bounces": "first"},
     "e": result.e, "St": result.St, "flow_steps": result.flow.steps, "rows": len(tr["t"]),
     "max_abs_f_sim1_N": float(abs(tr["f_sim1"]).max()), "max_abs_f_thr1_N": float(abs(tr["f_thr1"]).max())},
    indent=1))
print(f"{out / 'coupled_forces.png'}: e = {result.e:.4f}, St = {result.St:.2f}, {result.flow.steps} flow steps")
