# SPDX-License-Identifier: BSD-3-Clause
"""One run of the `default` scene (a steel sphere onto a Zerodur wall): the gap and the velocity against time, and
every force column of the trajectory (drag, lubrication, added mass, contact, history, ...) near the contact.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/trajectory_forces.py --out out/examples
"""
import argparse
import json
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import imcol

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--out", default="out/examples", help="folder for the picture and its data")
args = parser.parse_args()
out = pathlib.Path(args.out)
out.mkdir(parents=True, exist_ok=True)

settings = {"output.dt": 2e-6}  # s between trajectory rows (the scene's 0.1 ms has two rows in the contact)
scene = imcol.Scene.load("default")
for key, value in settings.items():
    scene.set(key, value)
result = imcol.run(scene)  # record="full": the trajectory has the forces
tr = result.trajectory
t_ms = tr["t"] * 1e3

# The force columns are the trajectory's f_* columns: f_drag1, f_lub1, f_am1, f_contact1, f_hist1, ...
forces = [c for c in result.columns if c.startswith("f_")]
# Near contact: from the first to the last sample with the gap below 0.3 mm.
near = tr["gap"] < 3e-4
t0, t1 = tr["t"][near].min(), tr["t"][near].max()
window = (tr["t"] >= t0) & (tr["t"] <= t1)

fig, (ax_gap, ax_u, ax_f) = plt.subplots(3, 1, figsize=(7, 9), constrained_layout=True)
ax_gap.plot(t_ms, tr["gap"] * 1e3)
ax_gap.set_ylabel("gap (mm)")
ax_u.plot(t_ms, tr["u1"])
ax_u.axhline(0, color="0.7", lw=0.8)
ax_u.set_ylabel("u1 (m/s)")
for ax in (ax_gap, ax_u):
    ax.axvspan(t0 * 1e3, t1 * 1e3, color="0.9")
    ax.set_xlabel("t (ms)")
for c in forces:
    ax_f.plot(t_ms[window], tr[c][window], label=c)
ax_f.set_yscale("symlog", linthresh=1e-4)
ax_f.set_xlabel("t (ms), gap below 0.3 mm")
ax_f.set_ylabel("force on sphere 1 (N)")
ax_f.legend(fontsize=8, ncol=2)
fig.suptitle(f"{result.scene}: e = {result.e:.3f}, St = {result.St:.1f}\neffects: {', '.join(result.effects)}")
fig.savefig(out / "trajectory_forces.png", dpi=120)

# What was plotted, to check against `imcol run default`.
peaks = {c: float(np.max(np.abs(tr[c]))) for c in forces}
(out / "trajectory_forces.json").write_text(json.dumps(
    {"scene": "default", "set": settings, "e": result.e, "St": result.St, "min_gap_m": result.min_gap_m,
     "rows": len(tr["t"]), "max_abs_force_N": peaks}, indent=1))
print(f"{out / 'trajectory_forces.png'}: e = {result.e:.4f}, St = {result.St:.2f}, forces {', '.join(forces)}")
