# SPDX-License-Identifier: BSD-3-Clause
"""`pip install .` into a venv, checked from outside the source tree: the tracked source files copied to a scratch
folder, a venv made there with --system-site-packages, `pip install --no-build-isolation` of the copy with no index
(PIP_NO_INDEX=1), the copy and its build tree deleted; then, from a folder with no imcol in it, the installed package
runs the default scene to the imcol program's e (the same double), lists the shipped scenes, reads its own data
(imcol/data) and its extension (readelf -d, ldd) has no run path and loads nothing from the deleted copy or the source
tree. Prints the pip install's time."""
import argparse
import json
import os
import pathlib
import shutil
import subprocess
import sys
import time

SKIPPED_DIRS = {".git", "out", "third_party_build", "__pycache__"}

CHECK = """
import json, pathlib, imcol
r = imcol.run(imcol.Scene.load("default"))
print(json.dumps({"file": imcol.__file__, "extension": imcol._imcol.__file__, "version": imcol.__version__,
                  "e": r.e, "scenes": imcol.scenes(), "data_dir": imcol.data_dir()}))
"""


def tracked_files(source):
    """The source tree's tracked files (git ls-files), or without git every file outside build and output folders."""
    if (source / ".git").exists() and shutil.which("git"):
        out = subprocess.run(["git", "-C", str(source), "ls-files", "-z"], capture_output=True, check=True).stdout
        return [pathlib.Path(f) for f in out.decode().split("\0") if f and (source / f).is_file()]
    found = []
    for folder, dirs, files in os.walk(source):
        dirs[:] = [d for d in dirs if d not in SKIPPED_DIRS and not d.startswith("build") and not d.endswith(".egg-info")]
        found += [pathlib.Path(folder, f).relative_to(source) for f in files]
    return found


def copy_sources(source, dest):
    files = tracked_files(source)
    for f in files:
        (dest / f).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(source / f, dest / f)
    return len(files)


def clean_env(**extra):
    """The environment without anything that would point Python or imcol at the source tree."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "IMCOL_DATA_DIR", "PYTHONHOME")}
    env.update(PYTHONDONTWRITEBYTECODE="1", **extra)
    return env


def pip_install(args, venv, src):
    """Makes the venv and installs the copy into it: the seconds the install took."""
    subprocess.run([args.python, "-m", "venv", "--system-site-packages", str(venv)], check=True)
    env = clean_env(PIP_NO_INDEX="1", PIP_DISABLE_PIP_VERSION_CHECK="1")
    if args.sundials_dir:
        env["SUNDIALS_DIR"] = args.sundials_dir
    if args.launcher:
        env["CMAKE_CXX_COMPILER_LAUNCHER"] = args.launcher
    t0 = time.monotonic()
    p = subprocess.run([str(venv / "bin" / "python"), "-m", "pip", "install", "--no-build-isolation", str(src)],
                       env=env, capture_output=True, text=True)
    seconds = time.monotonic() - t0
    if p.returncode != 0:
        sys.exit(f"pip install failed ({p.returncode}):\n{p.stdout[-6000:]}\n{p.stderr[-6000:]}")
    return seconds


def program_e(args, out):
    """e of `imcol run default`, read from its summary.json."""
    subprocess.run([args.imcol, "run", "default", "--out", str(out), "--quiet", "--no-plot"], check=True)
    return json.loads((out / "summary.json").read_text())["e"]


def shipped_scenes(source):
    scenes = source / "data" / "scenes"
    return sorted(str(p.relative_to(scenes).with_suffix("")) for p in scenes.rglob("*.toml"))


def check_package(found, args, work, venv):
    """The installed package's answers: a list of failures."""
    failures = []
    package = pathlib.Path(found["file"]).resolve().parent
    if not package.is_relative_to(venv.resolve()):
        failures.append(f"imported {found['file']}, not the venv's package")
    if found["version"] != args.version:
        failures.append(f"imcol.__version__ {found['version']}, the project's {args.version}")
    if pathlib.Path(found["data_dir"]).resolve() != package / "data":
        failures.append(f"imcol.data_dir() is {found['data_dir']}, not the package's {package / 'data'}")
    for f in ("materials.csv", "fluids.csv", "reference/li_2010_table_6_1.csv", "measurements/gg3462_e_table.csv"):
        if not (package / "data" / f).is_file():
            failures.append(f"the package has no data/{f}")
    expected_e = program_e(args, work / "program")
    if found["e"] != expected_e:
        failures.append(f"e of the default scene: installed package {found['e']!r}, imcol program {expected_e!r}")
    if sorted(found["scenes"]) != shipped_scenes(pathlib.Path(args.source)):
        failures.append(f"imcol.scenes() {sorted(found['scenes'])}, shipped {shipped_scenes(pathlib.Path(args.source))}")
    return failures


def check_extension(extension, forbidden):
    """readelf -d and ldd of the extension: no run path, every library found, none under a forbidden folder."""
    dynamic = subprocess.run(["readelf", "-d", extension], capture_output=True, text=True, check=True).stdout
    libs = subprocess.run(["ldd", extension], capture_output=True, text=True, check=True).stdout
    print(f"readelf -d {extension}:\n{dynamic}\nldd:\n{libs}")
    failures = [f"run path: {line.strip()}" for line in dynamic.splitlines() if "RPATH" in line or "RUNPATH" in line]
    failures += [f"ldd: {line.strip()}" for line in libs.splitlines() if "not found" in line]
    for folder in forbidden:
        failures += [f"ldd: {line.strip()} is under {folder}" for line in libs.splitlines() if str(folder) in line]
    return failures


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--source", required=True)
    ap.add_argument("--work", required=True, help="scratch folder (emptied first)")
    ap.add_argument("--python", required=True, help="the interpreter the venv is made from")
    ap.add_argument("--imcol", required=True, help="the imcol program")
    ap.add_argument("--version", required=True)
    ap.add_argument("--sundials-dir", default="")
    ap.add_argument("--launcher", default="", help="compiler launcher for the package's build (ccache)")
    args = ap.parse_args()
    work = pathlib.Path(args.work).resolve()
    shutil.rmtree(work, ignore_errors=True)
    src, venv, elsewhere = work / "src", work / "venv", work / "elsewhere"
    elsewhere.mkdir(parents=True)
    print(f"copied {copy_sources(pathlib.Path(args.source), src)} tracked files to {src}")
    seconds = pip_install(args, venv, src)
    shutil.rmtree(src)
    p = subprocess.run([str(venv / "bin" / "python"), "-c", CHECK], cwd=elsewhere, env=clean_env(),
                       capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"the installed package did not import and run ({p.returncode}):\n{p.stderr[-4000:]}")
    found = json.loads(p.stdout.strip().splitlines()[-1])
    failures = check_package(found, args, work, venv)
    failures += check_extension(found["extension"], [src, pathlib.Path(args.source).resolve()])
    print(f"pip install --no-build-isolation: {seconds:.0f} s; e = {found['e']!r}; {len(found['scenes'])} scenes")
    if failures:
        sys.exit("python_install:\n  " + "\n  ".join(failures))  # the scratch folder kept, to look into
    shutil.rmtree(work)  # the venv holds a copy of pip and setuptools: not left in the build tree
    print("python_install: 0 failed")


if __name__ == "__main__":
    main()
