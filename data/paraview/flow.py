# SPDX-License-Identifier: BSD-3-Clause
"""ParaView state for imcol's flow fields: opens flow.pvd beside this file, mirrors the half plane about the axis,
colours |velocity| (m/s) over a range fixed for the whole series, draws the spheres and the wall, and looks at the
(x, z) plane (the axis is z).

    pvpython DIR/flow.py                      build the pipeline (and render when a display is available)
    pvpython DIR/flow.py --screenshot F.png   also save a picture of the first snapshot (no display: xvfb-run -a)
    pvpython DIR/flow.py --no-render          the pipeline only, no view (IMCOL_PV_NO_RENDER=1 does the same)
    ParaView: File > Load State > DIR/flow.py (Python state)

Hidden cells (vtkGhostType = 32: covered by a finer level, inside a sphere, beyond the wall) are not drawn.
"""
import os
import sys

from paraview.simple import (ColorBy, ExtractBlock, GetActiveViewOrCreate, GetAnimationScene, GetColorTransferFunction,
                             GetOpacityTransferFunction, GroupDatasets, PVDReader, Reflect, Render, SaveScreenshot,
                             SetActiveSource, Show, Transform)


def folder():
    """This file's folder (pvpython and ParaView's Load State both set __file__), else the working folder."""
    try:
        return os.path.dirname(os.path.abspath(__file__))
    except NameError:
        return os.getcwd()


def velocity_range(source, times):
    """The largest |velocity| (m/s) over every snapshot, so that the colours compare across the series."""
    top = 0.0
    for t in times or [0.0]:
        source.UpdatePipeline(t)
        info = source.PointData.GetArray("velocity_m_s")
        if info is not None:
            top = max(top, info.GetRange(-1)[1])
    return top if top > 0 else 1.0


def pipeline(pvd):
    """The series split into levels and bodies, each joined to its mirror image about the axis (r = 0: the plane
    x = 0). The levels by Reflect; the bodies by a transform x → −x, since Reflect reorders a polyline's points (the
    mirrored half circle would gain a chord along the axis)."""
    reader = PVDReader(registrationName="flow.pvd", FileName=pvd)
    half = ExtractBlock(registrationName="levels half", Input=reader, Selectors=["/Root/levels"])
    levels = Reflect(registrationName="levels", Input=half)
    levels.Plane = "X"
    levels.CopyInput = 1
    outlines = ExtractBlock(registrationName="bodies half", Input=reader, Selectors=["/Root/bodies"])
    mirror = Transform(registrationName="bodies mirrored", Input=outlines)
    mirror.Transform = "Transform"
    mirror.Transform.Scale = [-1.0, 1.0, 1.0]
    bodies = GroupDatasets(registrationName="bodies", Input=[outlines, mirror])
    return reader, levels, bodies


def show(reader, levels, bodies):
    """The levels coloured by |velocity| over one range for the series, the bodies as black lines."""
    view = GetActiveViewOrCreate("RenderView")
    top = velocity_range(reader, list(reader.TimestepValues or []))
    GetAnimationScene().UpdateAnimationUsingDataTimeSteps()
    shown = Show(levels, view)
    ColorBy(shown, ("POINTS", "velocity_m_s", "Magnitude"))
    lut = GetColorTransferFunction("velocity_m_s")
    lut.AutomaticRescaleRangeMode = "Never"
    lut.RescaleTransferFunction(0.0, top)
    GetOpacityTransferFunction("velocity_m_s").RescaleTransferFunction(0.0, top)
    shown.SetScalarBarVisibility(view, True)
    lines = Show(bodies, view)
    lines.ColorArrayName = ["POINTS", ""]
    lines.AmbientColor = lines.DiffuseColor = [0.0, 0.0, 0.0]
    lines.LineWidth = 2.0
    return view


def look_at_xz(view):
    """The camera on −y looking at the (x, z) plane, z up."""
    view.InteractionMode = "2D"
    view.CameraPosition = [0.0, -1.0, 0.0]
    view.CameraFocalPoint = [0.0, 0.0, 0.0]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.ResetCamera(False)


def main(argv):
    pvd = os.path.join(folder(), "flow.pvd")
    if not os.path.isfile(pvd):
        raise SystemExit(f"flow.py: no flow.pvd beside this file ({pvd})")
    reader, levels, bodies = pipeline(pvd)
    if "--no-render" in argv or os.environ.get("IMCOL_PV_NO_RENDER"):  # the pipeline only: no view, no display
        times = list(reader.TimestepValues or [])
        for part in (levels, bodies):
            part.UpdatePipeline(times[0] if times else 0.0)
        print(f"flow.py: {pvd}: {len(times)} snapshots, |velocity| up to {velocity_range(reader, times):.6g} m/s")
        return
    view = show(reader, levels, bodies)
    SetActiveSource(reader)
    look_at_xz(view)
    Render(view)
    if "--screenshot" in argv:
        SaveScreenshot(argv[argv.index("--screenshot") + 1], view, ImageResolution=[1200, 900])


main(list(getattr(sys, "argv", [])))
