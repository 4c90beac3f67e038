# SPDX-License-Identifier: BSD-3-Clause
"""imcol: head-on collisions of spheres immersed in a viscous liquid.

    scene = imcol.Scene.load("default").set("fluid.viscosity", 0.05)
    result = imcol.run(scene)
    result.e, result.St, result.trajectory["u1"], result.solver.steps
"""
import pathlib as _pathlib
import sys as _sys
import warnings as _warnings

try:
    import numpy as _numpy  # noqa: F401  (the trajectories and study tables are NumPy arrays)
except ImportError as _e:
    raise ImportError(
        f"imcol needs NumPy, which {_sys.executable} cannot import ({_e}). Install it for this interpreter "
        "(Debian: apt-get install python3-numpy), or, in a venv, make the venv with --system-site-packages so that it "
        "sees Debian's NumPy (python3 -m venv --system-site-packages DIR), or pip install numpy there.") from _e

from ._imcol import (Result, Scene, SolverError, StudyTable, SweepResult, __version__, choices, contact_laws, dem_fit,
                     drag_laws, e_measures, effects, history_compare, history_kernels, integrators, laws,
                     lubrication_models, run, scenes, sweep, sweep_quantities)
from ._imcol import ValidateResult, WorkPrecisionResult, validate_seed, work_precision
from ._imcol import CalibrationResult, calibrate
from ._summary import Bounce, Contact, Event, Flow, Fluid, Solver, Summary, Velocities
from ._imcol import _set_data_dir, data_dir

# The installed package carries its data (imcol/data); the module built in a source tree reads the tree's data/.
if (_pathlib.Path(__file__).parent / "data" / "scenes").is_dir():
    _set_data_dir(str(_pathlib.Path(__file__).parent / "data"))

__all__ = ["Result", "Scene", "SolverError", "StudyTable", "SweepResult", "run", "sweep", "laws", "history_compare", "dem_fit",
           "__version__", "choices", "contact_laws",
           "drag_laws", "e_measures", "effects", "history_kernels", "integrators", "lubrication_models", "scenes",
           "sweep_quantities", "WorkPrecisionResult", "work_precision", "ValidateResult", "validate_seed", "CalibrationResult",
           "calibrate", "Summary", "Bounce",
           "Contact", "Event", "Flow", "Fluid", "Solver", "Velocities", "data_dir"]


def history(*args, **kwargs):
    """Deprecated name of imcol.history_compare (the command is `imcol history`); emits a DeprecationWarning."""
    _warnings.warn("imcol.history is deprecated: use imcol.history_compare", DeprecationWarning, stacklevel=2)
    return history_compare(*args, **kwargs)
