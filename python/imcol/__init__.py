# SPDX-License-Identifier: BSD-3-Clause
"""imcol: head-on collisions of spheres immersed in a viscous liquid.

    scene = imcol.Scene.load("default").set("fluid.viscosity", 0.05)
    result = imcol.run(scene)
    result.e, result.St, result.trajectory["u1"], result.solver.steps
"""
from ._imcol import Result, Scene, SolverError, __version__, run
from ._summary import Bounce, Contact, Event, Flow, Fluid, Solver, Summary, Velocities

__all__ = ["Result", "Scene", "SolverError", "run", "__version__",
           "Summary", "Bounce", "Contact", "Event", "Flow", "Fluid", "Solver", "Velocities"]
