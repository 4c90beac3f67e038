# SPDX-License-Identifier: BSD-3-Clause
"""imcol: head-on collisions of spheres immersed in a viscous liquid.

    scene = imcol.Scene.load("default").set("fluid.viscosity", 0.05)
    result = imcol.run(scene)
    result.e, result.St, result.trajectory["u1"], result.solver.steps
"""
from ._imcol import (Result, Scene, SolverError, StudyTable, SweepResult, __version__, choices, contact_laws, dem_fit,
                     drag_laws, e_measures, effects, history, history_kernels, integrators, laws, lubrication_models, run,
                     scenes, sweep, sweep_quantities)
from ._imcol import ValidateResult, WorkPrecisionResult, validate_seed, work_precision
from ._imcol import CalibrationResult, calibrate
from ._summary import Bounce, Contact, Event, Flow, Fluid, Solver, Summary, Velocities

__all__ = ["Result", "Scene", "SolverError", "StudyTable", "SweepResult", "run", "sweep", "laws", "history", "dem_fit",
           "__version__", "choices", "contact_laws",
           "drag_laws", "e_measures", "effects", "history_kernels", "integrators", "lubrication_models", "scenes",
           "sweep_quantities", "WorkPrecisionResult", "work_precision", "ValidateResult", "validate_seed", "CalibrationResult",
           "calibrate", "Summary", "Bounce",
           "Contact", "Event", "Flow", "Fluid", "Solver", "Velocities"]
