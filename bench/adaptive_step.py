#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""The adaptive flow step against the fixed one, measured in the same run (docs/coupling.md "The adaptive step").

    python3 bench/adaptive_step.py [--imcol build/bin/imcol] [--scenes gondret_st742 ...] [--repeat 3]

Runs `imcol run coupled/SCENE --quiet --no-plot --set flow.fields=false` with flow.adaptive_step true and false by
turns, `--repeat` times each, and prints per scene the flow steps, the median CPU time of the coupled run
(summary.json flow.cpu_time_s) and its ratio fixed/adaptive, the step range, and how far e and the first rebound's apex
moved.
"""
import argparse
import json
import pathlib
import statistics
import subprocess
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
BOUNCING = ["gondret_st27", "gondret_st100", "gondret_st152", "gondret_st192", "gondret_st742"]


def run_one(imcol, scene, adaptive, out):
    cmd = [imcol, "run", f"coupled/{scene}", "--out", str(out), "--quiet", "--no-plot", "--set", "flow.fields=false",
           "--set", f"flow.adaptive_step={'true' if adaptive else 'false'}"]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return json.loads((out / "summary.json").read_text())


def apex_mm(summary):
    bounces = summary.get("bounces") or []
    apex = bounces[0].get("apex_gap_m") if bounces else None
    return 1e3 * apex if apex is not None else float("nan")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--imcol", default=str(ROOT / "build" / "bin" / "imcol"))
    ap.add_argument("--scenes", nargs="*", default=BOUNCING)
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    print(f"{'scene':15s} {'steps fixed':>11s} {'adaptive':>9s} {'CPU s fixed':>11s} {'adaptive':>9s} {'ratio':>6s} "
          f"{'dt ms':>13s} {'Δe':>10s} {'apex mm fixed':>13s} {'adaptive':>9s}")
    with tempfile.TemporaryDirectory() as tmp:
        for scene in a.scenes:
            cpu = {True: [], False: []}
            last = {}
            for k in range(a.repeat):
                for adaptive in (False, True):
                    s = run_one(a.imcol, scene, adaptive, pathlib.Path(tmp) / f"{scene}_{adaptive}_{k}")
                    cpu[adaptive].append(s["flow"]["cpu_time_s"])
                    last[adaptive] = s
            f, d = last[False], last[True]
            cf, cd = statistics.median(cpu[False]), statistics.median(cpu[True])
            de = (d["e"] - f["e"]) if d.get("e") is not None and f.get("e") is not None else float("nan")
            dt = f"{1e3 * d['flow']['dt_min_s']:.3g}-{1e3 * d['flow']['dt_max_s']:.3g}"
            print(f"{scene:15s} {f['flow']['steps']:11d} {d['flow']['steps']:9d} {cf:11.2f} {cd:9.2f} {cf / cd:6.2f} "
                  f"{dt:>13s} {de:10.2e} {apex_mm(f):13.2f} {apex_mm(d):9.2f}", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
