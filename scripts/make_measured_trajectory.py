#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Make a "measured" trajectory from an imcol run: what a camera would record, for trying `imcol calibrate`.

Runs `imcol run SCENE` (every bounce followed up to --t-end), keeps t, z1 and z2 every --dt, adds seeded Gaussian
noise of standard deviation --sigma (m) to each z, and moves the clock by --offset (s): the file's t is the run's
t + offset. The header's comment lines say how the file was made.

Usage: /usr/bin/python3 scripts/make_measured_trajectory.py --imcol BIN --scene gg3462 --set contact.delta_ss=0.024 \\
           --dt 0.0005 --t-end 0.07 --sigma 20e-6 --offset 0.003 --seed 1 --out data/measurements/gg3462_trajectory.csv
"""
import argparse
import csv
import random
import subprocess
import sys
import tempfile
from pathlib import Path


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--imcol", default="imcol", help="the imcol program")
    ap.add_argument("--scene", required=True)
    ap.add_argument("--set", action="append", default=[], help="scene overrides, as imcol run takes them")
    ap.add_argument("--dt", type=float, default=0.0005, help="sampling interval (s)")
    ap.add_argument("--t-end", type=float, default=0.07, help="the run's end (s)")
    ap.add_argument("--sigma", type=float, default=20e-6, help="noise standard deviation of each z (m)")
    ap.add_argument("--offset", type=float, default=0.0, help="the file's clock minus the run's (s)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="imcol_measured_") as tmp:
        cmd = [a.imcol, "run", a.scene, "--out", tmp + "/run", "--no-plot", "--quiet",
               "--set", "measure.bounces=\"all\"", "--set", "solver.t_end=%r" % a.t_end]
        for s in a.set:
            cmd += ["--set", s]
        subprocess.run(cmd, check=True)
        with open(Path(tmp) / "run" / "trajectory.csv", newline="") as f:
            rows = list(csv.DictReader(f))
    rng = random.Random(a.seed)
    out = Path(a.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    lines = ["# made by scripts/make_measured_trajectory.py: imcol run %s %s" % (a.scene, " ".join("--set " + s for s in a.set)),
             "# every %g s up to t_end = %g s; z1, z2 + Gaussian noise sigma = %g m (seed %d); t = run's t + %g s" % (
                 a.dt, a.t_end, a.sigma, a.seed, a.offset),
             "t,z1,z2"]
    next_t = 0.0
    for r in rows:
        t = float(r["t"])
        if t + 1e-12 < next_t:
            continue
        next_t += a.dt
        z1 = float(r["z1"]) + rng.gauss(0.0, a.sigma)
        z2 = float(r["z2"]) + rng.gauss(0.0, a.sigma)
        lines.append("%.6f,%.7e,%.7e" % (t + a.offset, z1, z2))
    out.write_text("\n".join(lines) + "\n")
    print("wrote %s (%d rows)" % (out, len(lines) - 3))
    return 0


if __name__ == "__main__":
    sys.exit(main())
