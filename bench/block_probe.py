#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Probed preconditioner blocks against blocks built column by column, measured in the same run (docs/flow-kernel.md
"Probed preconditioner blocks").

    python3 bench/block_probe.py [--imcol build/bin/imcol] [--scenes gg3462 ...] [--repeat 3] [--stride 12]

Runs `imcol run coupled/SCENE --quiet --no-plot --set flow.fields=false` with flow.block_probe_stride 0 (every block
column by column) and --stride by turns, `--repeat` times each, and prints per scene the applications of the force
operator Q over the whole run (summary.json flow.q_applications: blocks, probes and GMRES iterations), the coupled
steps' GMRES iterations, the median CPU time of the coupled run (flow.cpu_time_s), the ratios full/probed, and how far e
moved.
"""
import argparse
import json
import pathlib
import statistics
import subprocess
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
SCENES = ["gg3462", "group_b", "gondret_st27", "gondret_st100", "gondret_st742", "bouncing_steel"]


def run_one(imcol, scene, stride, out):
    cmd = [imcol, "run", f"coupled/{scene}", "--out", str(out), "--quiet", "--no-plot", "--set", "flow.fields=false",
           "--set", f"flow.block_probe_stride={stride}"]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return json.loads((out / "summary.json").read_text())


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--imcol", default=str(ROOT / "build" / "bin" / "imcol"))
    ap.add_argument("--scenes", nargs="*", default=SCENES)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--stride", type=int, default=12)
    a = ap.parse_args()
    print(f"{'scene':15s} {'Q full':>8s} {'probed':>8s} {'ratio':>6s} {'GMRES full':>10s} {'probed':>7s} "
          f"{'CPU s full':>10s} {'probed':>7s} {'ratio':>6s} {'Δe':>10s}")
    with tempfile.TemporaryDirectory() as tmp:
        for scene in a.scenes:
            cpu = {0: [], a.stride: []}
            last = {}
            for k in range(a.repeat):
                for stride in (0, a.stride):
                    s = run_one(a.imcol, scene, stride, pathlib.Path(tmp) / f"{scene}_{stride}_{k}")
                    cpu[stride].append(s["flow"]["cpu_time_s"])
                    last[stride] = s
            f, p = last[0]["flow"], last[a.stride]["flow"]
            cf, cp = statistics.median(cpu[0]), statistics.median(cpu[a.stride])
            ef, ep = last[0].get("e"), last[a.stride].get("e")
            de = ep - ef if ef is not None and ep is not None else float("nan")
            print(f"{scene:15s} {f['q_applications']:8d} {p['q_applications']:8d} "
                  f"{f['q_applications'] / p['q_applications']:6.2f} {f['krylov_iterations']:10d} "
                  f"{p['krylov_iterations']:7d} {cf:10.2f} {cp:7.2f} {cf / cp:6.2f} {de:10.2e}", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
