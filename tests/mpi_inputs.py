#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Ranks of an MPI job on different inputs are refused before anything runs: an MPMD job whose two ranks run a sweep
with another --set, with another IMCOL_DATA_DIR (steel's density changed in the second's materials.csv), or with
another --from; a work-precision with another --repeat; a calibration on another measurement. Every such job must
exit 2, rank 0's one error line naming the rank that differs and in what (scene, options); nothing is written. The
same MPMD jobs with equal inputs (an equal copy of the data folder included) run as before, exit 0.

Usage: /usr/bin/python3 tests/mpi_inputs.py --imcol BIN --mpirun MPIRUN --data DATA_DIR (run by ctest as mpi_inputs)
"""
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from mpi_compare import arguments, report  # noqa: E402

SWEEP = ["sweep", "default", "--vary", "velocity", "--from", "0.1", "--to", "1", "--points", "3", "--jobs", "1",
         "--no-plot", "--no-progress"]


def with_option(args, option, value):
    """`args` with `option`'s value replaced."""
    i = args.index(option)
    return [*args[:i + 1], value, *args[i + 2:]]


def mpmd(a, first, second, env1=None, env2=None):
    """`mpirun … -np 1 [-x env1] imcol FIRST : -np 1 [-x env2] imcol SECOND`: rank 0 runs FIRST, rank 1 SECOND."""
    cmd = [a.mpirun, "--allow-run-as-root", "--oversubscribe"]
    for i, (args, env) in enumerate(((first, env1), (second, env2))):
        if i:
            cmd.append(":")
        cmd += ["-np", "1"]
        for k, v in (env or {}).items():
            cmd += ["-x", f"{k}={v}"]
        cmd += [a.imcol, *args]
    return subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=240)


def expect_refused(label, p, out, parts):
    """Exit 2, one error line from rank 0 naming rank 1 and each of `parts` (and no other part), no output folder."""
    failures = []
    errors = [l for l in p.stderr.splitlines() if l.startswith("imcol: error:")]
    if p.returncode != 2:
        failures.append(f"{label}: exit {p.returncode} (expected 2); stderr {p.stderr.strip()[-600:]!r}")
    if len(errors) != 1:
        failures.append(f"{label}: {len(errors)} error lines (expected rank 0's one): {errors}")
        return failures
    line = errors[0]
    expected = "rank 1 differs from rank 0 in " + ", ".join(parts) + " ("
    if not line.startswith("imcol: error: mpirun: ") or expected not in line:
        failures.append(f"{label}: the error line does not say {expected!r}: {line!r}")
    if out.exists():
        failures.append(f"{label}: {out} was written")
    return failures


def expect_ok(label, p):
    if p.returncode != 0:
        return [f"{label}: exit {p.returncode} (expected 0); stderr {p.stderr.strip()[-600:]!r}"]
    if "imcol: error" in p.stderr:
        return [f"{label}: an error on stderr: {p.stderr.strip()[-600:]!r}"]
    return []


def main():
    a = arguments("--data")
    failures = []
    with tempfile.TemporaryDirectory(prefix="imcol_mpi_inputs_") as tmp:
        tmp = Path(tmp)
        # Two copies of the data folder: one equal, one where steel is denser.
        same, denser = tmp / "data_same", tmp / "data_denser"
        shutil.copytree(a.data, same)
        shutil.copytree(a.data, denser)
        m = denser / "materials.csv"
        text = m.read_text()
        if "\nsteel,7780," not in text:
            return report([f"{m}: no steel row with density 7780 to change"])
        m.write_text(text.replace("\nsteel,7780,", "\nsteel,7790,"))

        def out(name):
            return ["--out", str(tmp / name)]

        cases = [
            ("another --set", SWEEP + out("set"), SWEEP + ["--set", "solver.rtol=1e-9"] + out("set"), None, None, ["scene"]),
            ("another IMCOL_DATA_DIR", SWEEP + out("data"), SWEEP + out("data"), {"IMCOL_DATA_DIR": str(same)},
             {"IMCOL_DATA_DIR": str(denser)}, ["scene"]),
            ("another --from", SWEEP + out("from"), with_option(SWEEP, "--from", "0.2") + out("from"), None, None,
             ["scene", "options"]),
        ]
        wp = ["work-precision", "default", "--rtols", "1e-4,1e-5", "--integrators", "cvode-dense", "--no-plot"]
        cases.append(("work-precision, another --repeat", wp + ["--repeat", "1"] + out("wp"), wp + ["--repeat", "2"] + out("wp"),
                      None, None, ["options"]))
        # A calibration on two e tables that differ in one value.
        scene = Path(a.data) / "scenes" / "default.toml"
        e1, e2 = tmp / "e1.csv", tmp / "e2.csv"
        e1.write_text("sphere[0].velocity,e\n0.2,0.5\n0.4,0.7\n")
        e2.write_text("sphere[0].velocity,e\n0.2,0.5\n0.4,0.71\n")
        cal = ["calibrate", str(scene), "--fit", "contact.e_dry=0.8:0.99", "--scan", "2", "--starts", "0", "--profile-points", "0",
               "--jobs", "1", "--no-plot", "--no-progress"]
        cases.append(("calibrate, another --data", cal + ["--data", str(e1)] + out("cal"), cal + ["--data", str(e2)] + out("cal"),
                      None, None, ["options"]))
        for label, first, second, env1, env2, parts in cases:
            failures += expect_refused(label, mpmd(a, first, second, env1, env2), Path(first[first.index("--out") + 1]), parts)
        # Equal inputs still run: the same --set on both ranks, and two equal copies of the data folder.
        failures += expect_ok("equal --set", mpmd(a, SWEEP + ["--set", "solver.rtol=1e-9"] + out("ok1"),
                                                  SWEEP + ["--set", "solver.rtol=1e-9"] + out("ok1")))
        failures += expect_ok("equal data folders", mpmd(a, SWEEP + out("ok2"), SWEEP + out("ok2"), {"IMCOL_DATA_DIR": str(a.data)},
                                                         {"IMCOL_DATA_DIR": str(same)}))
        # --jobs and --out are a rank's own: they may differ.
        failures += expect_ok("another --jobs", mpmd(a, SWEEP + out("ok3"), with_option(SWEEP, "--jobs", "2") + out("ok3")))
    return report(failures)


if __name__ == "__main__":
    sys.exit(main())
