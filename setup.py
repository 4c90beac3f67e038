# SPDX-License-Identifier: BSD-3-Clause
"""The Python package imcol's build (pyproject.toml has its metadata): CMake configures the project and builds the
extension imcol._imcol alone (Release; no tests, benchmarks or MPI; SUNDIALS linked statically, no run path), and the
wheel holds it with python/imcol's files and the shipped data (data/ as imcol/data, which the package reads).

Environment: SUNDIALS_DIR (else the SUNDIALS scripts/setup.sh built into third_party_build/, else the system's),
CMAKE_ARGS (more CMake options), CMAKE_BUILD_PARALLEL_LEVEL (parallel jobs; default: every processor)."""
import os
import pathlib
import re
import shlex
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext
from setuptools.command.build_py import build_py

ROOT = pathlib.Path(__file__).resolve().parent


def project_version():
    """The version of CMakeLists.txt's project(imcol VERSION x.y.z): one source of truth."""
    m = re.search(r"project\(\s*imcol\s+VERSION\s+([0-9][0-9.]*)", (ROOT / "CMakeLists.txt").read_text())
    if not m:
        sys.exit("setup.py: no `project(imcol VERSION …)` in CMakeLists.txt")
    return m.group(1)


def sundials_dir():
    """SUNDIALS_DIR, else the newest SUNDIALS in third_party_build/ (scripts/setup.sh), else None: CMake's search."""
    if os.environ.get("SUNDIALS_DIR"):
        return os.environ["SUNDIALS_DIR"]
    found = sorted(ROOT.glob("third_party_build/sundials-*/install/lib/cmake/sundials/SUNDIALSConfig.cmake"))
    return str(found[-1].parent) if found else None


def configure_args(build_dir):
    """CMake's configure command: the module target for this interpreter, and nothing else turned on."""
    args = ["cmake", "-S", str(ROOT), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
            "-DIMCOL_PYTHON=ON", f"-DPython3_EXECUTABLE={sys.executable}", "-DIMCOL_BUILD_TESTS=OFF",
            "-DIMCOL_BUILD_BENCHMARKS=OFF", "-DIMCOL_MPI=OFF", "-DIMCOL_SUNDIALS_STATIC=ON", "-DCMAKE_SKIP_RPATH=ON"]
    if shutil.which("ninja") and not (build_dir / "CMakeCache.txt").exists():
        args += ["-G", "Ninja"]
    if sundials_dir():
        args.append(f"-DSUNDIALS_DIR={sundials_dir()}")
    return args + shlex.split(os.environ.get("CMAKE_ARGS", ""))


class CMakeBuildExt(build_ext):
    """Builds imcol._imcol with CMake (target imcol_python) and puts it where the wheel takes it."""

    def build_extension(self, ext):
        build_dir = pathlib.Path(self.build_temp).resolve() / "cmake"
        build_dir.mkdir(parents=True, exist_ok=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        subprocess.run(configure_args(build_dir), check=True)
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "imcol_python", "-j", jobs], check=True)
        built = sorted((build_dir / "python" / "imcol").glob("_imcol*.so"))
        if len(built) != 1:
            sys.exit(f"setup.py: expected one extension in {build_dir / 'python' / 'imcol'}, found {built}")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)


class BuildPyWithData(build_py):
    """The package's Python files, and data/ copied to imcol/data (scenes, materials, fluids, reference tables,
    measurements)."""

    def run(self):
        super().run()
        dest = pathlib.Path(self.build_lib) / "imcol" / "data"
        shutil.rmtree(dest, ignore_errors=True)
        shutil.copytree(ROOT / "data", dest, ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))


setup(
    version=project_version(),
    packages=["imcol"],
    package_dir={"imcol": "python/imcol"},
    package_data={"imcol": ["*.pyi", "py.typed"]},
    ext_modules=[Extension("imcol._imcol", sources=[])],
    cmdclass={"build_ext": CMakeBuildExt, "build_py": BuildPyWithData},
    options={"build": {"build_base": "build-python"}},
    zip_safe=False,
)
