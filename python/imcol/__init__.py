# SPDX-License-Identifier: BSD-3-Clause
"""imcol: head-on collisions of spheres immersed in a viscous liquid.

    scene = imcol.Scene.load("default").set("fluid.viscosity", 0.05)
    result = imcol.run(scene)
    result.e, result.St, result.trajectory["u1"], result.solver.steps
"""
import warnings as _warnings

from ._imcol import (Result, Scene, SolverError, StudyTable, SweepResult, __version__, choices, contact_laws, dem_fit,
                     drag_laws, e_measures, effects, history_compare, history_kernels, integrators, laws,
                     lubrication_models, run, scenes, sweep, sweep_quantities)
from ._imcol import ValidateResult, WorkPrecisionResult, validate_seed, work_precision
from ._summary import Bounce, Contact, Event, Flow, Fluid, Solver, Summary, Velocities

__all__ = ["Result", "Scene", "SolverError", "StudyTable", "SweepResult", "run", "sweep", "laws", "history_compare", "dem_fit",
           "__version__", "choices", "contact_laws",
           "drag_laws", "e_measures", "effects", "history_kernels", "integrators", "lubrication_models", "scenes",
           "sweep_quantities", "WorkPrecisionResult", "work_precision", "ValidateResult", "validate_seed", "Summary", "Bounce",
           "Contact", "Event", "Flow", "Fluid", "Solver", "Velocities"]


def history(*args, **kwargs):
    """Deprecated name of imcol.history_compare (the command is `imcol history`); emits a DeprecationWarning."""
    _warnings.warn("imcol.history is deprecated: use imcol.history_compare", DeprecationWarning, stacklevel=2)
    return history_compare(*args, **kwargs)
