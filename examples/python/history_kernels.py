# SPDX-License-Identifier: BSD-3-Clause
"""e against St with each history kernel (`history.kernel`) on the `default` scene (a steel sphere onto a Zerodur
wall, Re 33-1140), and each kernel's e minus Basset's.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/history_kernels.py --out out/examples
"""
import argparse
import copy
import json
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import imcol

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--out", default="out/examples", help="folder for the picture and its data")
parser.add_argument("--points", type=int, default=8, help="impact speeds per kernel")
args = parser.parse_args()
out = pathlib.Path(args.out)
out.mkdir(parents=True, exist_ok=True)

base = imcol.Scene.load("default")
speeds = np.geomspace(0.05, 1.5, args.points)  # m/s
kernels = imcol.history_kernels()  # the values `history.kernel` takes, from the code; basset first
curves = {}
for kernel in kernels:
    runs = [imcol.run(copy.copy(base).set("history.kernel", kernel).set("sphere[0].velocity", float(u)))
            for u in speeds]
    curves[kernel] = {"St": np.array([r.St for r in runs], dtype=float),
                      "e": np.array([r.e for r in runs], dtype=float)}  # None (no e) -> NaN

fig, (ax_e, ax_d) = plt.subplots(2, 1, figsize=(7, 7), sharex=True, constrained_layout=True)
for kernel, c in curves.items():
    ax_e.plot(c["St"], c["e"], "o-", ms=3, label=kernel)
    ax_d.plot(c["St"], c["e"] - curves["basset"]["e"], "o-", ms=3, label=kernel)
ax_e.set_ylabel("e")
ax_e.legend(title="history.kernel")
ax_d.axhline(0, color="0.7", lw=0.8)
ax_d.set_ylabel("e - e(basset)")
ax_d.set_xlabel("St")
ax_d.set_xscale("log")
fig.suptitle(f"{base.name}: e against St by history kernel")
fig.savefig(out / "history_kernels.png", dpi=120)

(out / "history_kernels.json").write_text(json.dumps(
    {"scene": "default", "velocity_m_s": speeds.tolist(),
     "kernels": {k: {"St": c["St"].tolist(), "e": c["e"].tolist()} for k, c in curves.items()}}, indent=1))
for k, c in curves.items():
    d = c["e"] - curves["basset"]["e"]
    print(f"{k:12s} e {c['e'].min():.3f}-{c['e'].max():.3f}, e - e(basset) {d.min():+.4f} to {d.max():+.4f}")
