#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Reads imcol's VTK flow fields with VTK itself (vtkXMLMultiBlockDataReader) and checks what a viewer shows.

Coarse coupled runs (a sphere onto a wall, gondret_st27; a pair, gg3462) and a coarse `imcol flow` scene with a wall
(its sphere above it), every snapshot of flow.pvd:
(a) no visible cell (vtkGhostType without HIDDENCELL) has its centre inside a solid (either sphere set, beyond the
    wall), and the ghost array is exactly "covered by a finer level, or centre inside a solid", computed here from the
    levels' extents and the bodies' blocks; VTK's vtkDataSetSurfaceFilter and RemoveGhostCells drop exactly the
    hidden cells, and vtkGeometryFilter's output keeps them marked (the renderer's mapper skips them);
(b) every place is shown by one level at most, and by exactly one unless its finest cell's centre is in a solid
    (random points), and the visible area plus the solid cells' area is the coarsest rectangle's;
(c) the block "spheres" is the trajectory: centre = trajectory.csv's z at the snapshot's time (1e-9 m) for the
    `contact` snapshots; the field data's gap_m is that trajectory's gap; the kernel holds its sphere short of it;
(d) the axis is z: points (r, 0, z), r ≥ 0; velocity (u_r, 0, u_z); the field data's time_s is the .pvd's time.
The output folder holds flow.py, the same as data/paraview/flow.py, and it byte-compiles.
Needs /usr/bin/python3 with VTK's Python module (python3-vtk9, or ParaView's) and python3-numpy.
"""
import csv
import py_compile
import sys
import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path

from imcol_script_args import imcol_and_data, run as run_checked

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkDataSetAttributes, vtkUnstructuredGrid
from vtkmodules.vtkFiltersGeometry import vtkDataSetSurfaceFilter, vtkGeometryFilter
from vtkmodules.vtkIOXML import vtkXMLMultiBlockDataReader

HIDDEN = vtkDataSetAttributes.HIDDENCELL


def fail(msg):
    print(f"vtk_fields: FAIL: {msg}", file=sys.stderr)
    sys.exit(1)


def field(ds, name):
    a = ds.GetFieldData().GetAbstractArray(name)
    if a is None:
        return None
    return a.GetValue(0)


def blocks(mb):
    """{name: dataset or list of datasets} of a snapshot's multiblock."""
    out = {}
    for k in range(mb.GetNumberOfBlocks()):
        name = mb.GetMetaData(k).Get(mb.NAME())
        sub = mb.GetBlock(k)
        out[name] = {sub.GetMetaData(j).Get(mb.NAME()): sub.GetBlock(j) for j in range(sub.GetNumberOfBlocks())}
    return out


def circles(poly):
    """(z centre, radius) of each semicircle polyline; checks it lies in the plane y = 0 at r >= 0."""
    pts = vtk_to_numpy(poly.GetPoints().GetData())
    if np.any(pts[:, 1] != 0) or np.any(pts[:, 0] < 0):
        fail("a sphere's outline leaves the half plane (r >= 0, y = 0)")
    offs = vtk_to_numpy(poly.GetLines().GetOffsetsArray())
    return [((pts[a:b, 2].min() + pts[a:b, 2].max()) / 2, pts[a:b, 0].max()) for a, b in zip(offs[:-1], offs[1:])]


def level_cells(ds):
    """Cell centres (r, z), sizes h, and the ghost array of one level."""
    pts = vtk_to_numpy(ds.GetPoints().GetData())
    conn = vtk_to_numpy(ds.GetCells().GetConnectivityArray()).reshape(-1, 4)
    corner, opposite = pts[conn[:, 0]], pts[conn[:, 2]]
    ghost = ds.GetCellGhostArray()
    if ghost is None:
        fail("a level without a cell ghost array (vtkGhostType)")
    return (corner + opposite) / 2, opposite[:, 0] - corner[:, 0], vtk_to_numpy(ghost).astype(int)


def solid(c, bodies):
    """Where the cell centres c (rows (x, 0, z)) are inside a sphere (either set) or beyond the wall."""
    inside = np.zeros(len(c), bool)
    for zc, a in bodies["spheres"] + bodies["kernel_spheres"]:
        inside |= c[:, 0] ** 2 + (c[:, 2] - zc) ** 2 < a * a
    if bodies["wall"] is not None:
        side = 1.0 if bodies["spheres"][0][0] >= bodies["wall"] else -1.0
        inside |= (c[:, 2] - bodies["wall"]) * side < 0
    return inside


def check_vtk_hides(ds, visible, what):
    """VTK's surface filter and RemoveGhostCells drop the hidden cells; vtkGeometryFilter keeps them with the ghost
    array, which the renderer's mapper reads."""
    surf = vtkDataSetSurfaceFilter()
    surf.SetInputData(ds)
    surf.Update()
    copy = vtkUnstructuredGrid()
    copy.DeepCopy(ds)
    copy.RemoveGhostCells()
    geo = vtkGeometryFilter()
    geo.SetInputData(ds)
    geo.Update()
    ghost = geo.GetOutput().GetCellGhostArray()
    kept = None if ghost is None else int(np.sum((vtk_to_numpy(ghost) & HIDDEN) == 0))
    if surf.GetOutput().GetNumberOfCells() != visible or copy.GetNumberOfCells() != visible or kept != visible:
        fail(f"{what}: {visible} visible cells; vtkDataSetSurfaceFilter keeps {surf.GetOutput().GetNumberOfCells()}, "
             f"RemoveGhostCells {copy.GetNumberOfCells()}, vtkGeometryFilter's output marks {kept} visible")


def check_levels(levels, bodies, what):
    """(a) and (b) for one snapshot; returns the count of hidden cells."""
    cells = [level_cells(ds) for ds in levels]
    ext = [(c[:, 0].min() - h[0] / 2, c[:, 0].max() + h[0] / 2, c[:, 2].min() - h[0] / 2, c[:, 2].max() + h[0] / 2) for c, h, _ in cells]
    hidden_total, area_visible, area_solid = 0, 0.0, 0.0
    for lv, ((c, h, ghost), ds) in enumerate(zip(cells, levels)):
        if np.any(c[:, 1] != 0):
            fail(f"{what} level {lv}: points off the plane y = 0")
        covered = np.zeros(len(c), bool)
        if lv > 0:
            _, r1, z0, z1 = ext[lv - 1]
            covered = (c[:, 0] < r1) & (c[:, 2] > z0) & (c[:, 2] < z1)
        in_solid = solid(c, bodies)
        hidden = (ghost & HIDDEN) != 0
        if np.any(~hidden & in_solid):
            fail(f"{what} level {lv}: {int(np.sum(~hidden & in_solid))} visible cells with their centre inside a solid")
        if np.any(hidden != (covered | in_solid)):
            fail(f"{what} level {lv}: {int(np.sum(hidden != (covered | in_solid)))} cells hidden other than covered-or-solid")
        check_vtk_hides(ds, int(np.sum(~hidden)), f"{what} level {lv}")
        area_visible += float(np.sum(h[~hidden] ** 2))
        area_solid += float(np.sum(h[in_solid & ~covered] ** 2))
        hidden_total += int(hidden.sum())
    _, r1, z0, z1 = ext[-1]
    if abs(area_visible + area_solid - r1 * (z1 - z0)) > 1e-12 * r1 * (z1 - z0):
        fail(f"{what}: visible area {area_visible} + solid cells {area_solid} != the coarsest level's {r1 * (z1 - z0)}")
    check_points(cells, ext, bodies, what)
    return hidden_total


def check_points(cells, ext, bodies, what):
    """(b) at random points: the visible cells that contain each, over the levels."""
    rng = np.random.default_rng(7)
    _, r1, z0, z1 = ext[-1]
    p = np.column_stack([rng.uniform(0, r1, 4000), np.zeros(4000), rng.uniform(z0, z1, 4000)])
    shown = np.zeros(len(p), int)
    finest_solid = np.full(len(p), None)
    for (c, h, ghost), (ra, rb, za, zb) in zip(cells, ext):
        step = h[0]
        nz = int(round((zb - za) / step))
        inside = (p[:, 0] < rb) & (p[:, 2] > za) & (p[:, 2] < zb)
        k = np.floor(p[:, 0] / step).astype(int) * nz + np.floor((p[:, 2] - za) / step).astype(int)
        k = np.where(inside, k, 0)
        shown += inside & ((ghost[k] & HIDDEN) == 0)
        in_solid = solid(c[k], bodies)
        for n in np.nonzero(inside & (finest_solid == None))[0]:  # noqa: E711 (an object array)
            finest_solid[n] = bool(in_solid[n])
    if np.any(shown > 1):
        fail(f"{what}: {int(np.sum(shown > 1))} of {len(p)} points shown by more than one level")
    if np.any((shown == 0) & (finest_solid == False)):  # noqa: E712
        fail(f"{what}: {int(np.sum((shown == 0) & (finest_solid == False)))} points in fluid shown by no level")  # noqa: E712


def read_trajectory(path):
    with open(path) as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    head = rows[0]
    return {name: np.array([float(r[k]) for r in rows[1:]]) for k, name in enumerate(head)}


def check_trajectory(b, traj, t, what):
    """(c) at contact: the spheres block where trajectory.csv has them at t; gap_m its gap; the kernel's larger."""
    k = int(np.argmin(np.abs(traj["t"] - t)))
    if abs(traj["t"][k] - t) > 1e-12 * max(1.0, t):
        fail(f"{what}: no trajectory row at the snapshot's t = {t} s (nearest {traj['t'][k]})")
    sph = b["spheres"]
    for m, (zc, a) in enumerate(sph):
        z = traj[f"z{m + 1}"][k]
        if abs(zc - z) > 1e-9:
            fail(f"{what}: sphere {m + 1} at z = {zc} m in the VTK file, trajectory.csv {z} m")
    gap = sph[1][0] - sph[0][0] - sph[0][1] - sph[1][1] if len(sph) == 2 else b["wall"] - sph[0][0] - sph[0][1]
    if abs(b["gap_m"] - gap) > 1e-9:
        fail(f"{what}: field data gap_m = {b['gap_m']}, the spheres block's gap {gap}")
    if not b["kernel_gap_m"] > b["gap_m"]:
        fail(f"{what}: at contact the kernel's gap {b['kernel_gap_m']} m should exceed the trajectory's {b['gap_m']} m")
    return b["gap_m"] / (2 * sph[0][1])


def snapshot(vtm):
    r = vtkXMLMultiBlockDataReader()
    r.SetFileName(str(vtm))
    r.Update()
    bl = blocks(r.GetOutput())
    levels = [bl["levels"][f"level {k}"] for k in range(len(bl["levels"]))]
    body = bl["bodies"]
    b = {"spheres": circles(body["spheres"]), "kernel_spheres": circles(body["kernel_spheres"]),
         "wall": vtk_to_numpy(body["wall"].GetPoints().GetData())[0, 2] if "wall" in body else None}
    for key in ("time_s", "gap_m", "kernel_gap_m"):
        b[key] = field(levels[0], key)
    return levels, b


def check_velocity(levels, what):
    for lv, ds in enumerate(levels):
        v = vtk_to_numpy(ds.GetPointData().GetArray("velocity_m_s"))
        if np.any(v[:, 1] != 0) or not np.any(v[:, 2] != 0):
            fail(f"{what} level {lv}: velocity_m_s must be (u_r, 0, u_z) with u_z not all 0")
        for name in ("stream_function_m3_s", "vorticity_1_s", "pressure_Pa"):
            if ds.GetPointData().GetArray(name) is None:
                fail(f"{what} level {lv}: no point array {name}")


def check_folder(out, data, coupled=True):
    """Every snapshot of out/flow.pvd; a coupled run's contact snapshot against trajectory.csv (`imcol flow` has no
    trajectory: its two sphere blocks are the same)."""
    root = ET.parse(out / "flow.pvd").getroot()
    times, files = [float(e.get("timestep")) for e in root.iter("DataSet")], [e.get("file") for e in root.iter("DataSet")]
    traj = read_trajectory(out / "trajectory.csv") if coupled else None
    contact = None
    for t, f in zip(times, files):
        levels, b = snapshot(out / f)
        what = f"{out.name}/{f}"
        if b["time_s"] != t:
            fail(f"{what}: field data time_s {b['time_s']} != the .pvd's {t}")
        check_velocity(levels, what)
        if check_levels(levels, b, what) == 0:
            fail(f"{what}: no hidden cell")
        if coupled and Path(f).stem == "flow_contact":
            contact = check_trajectory(b, traj, t, what)
        if not coupled and b["spheres"] != b["kernel_spheres"]:
            fail(f"{what}: prescribed motion, yet the trajectory's spheres differ from the kernel's")
    if coupled and contact is None:
        fail(f"{out.name}: no contact snapshot")
    state = out / "flow.py"
    if not state.is_file() or state.read_bytes() != (data / "paraview/flow.py").read_bytes():
        fail(f"{out.name}: flow.py missing or not data/paraview/flow.py")
    py_compile.compile(str(state), cfile=str(out / "flow.pyc"), doraise=True)
    print(f"{out.name}: {len(times)} snapshots checked" + (f"; gap at contact {contact:.4g} D" if coupled else ""))


def run(cmd):
    run_checked(cmd, fail)


def main():
    imcol, data = imcol_and_data(__doc__)
    with tempfile.TemporaryDirectory(prefix="imcol_vtkf_") as tmp:
        out = Path(tmp) / "wall"
        run([imcol, "run", str(data / "scenes/coupled/gondret_st27.toml"), "--out", str(out), "--no-plot", "--quiet",
             "--set", "flow.cells_per_diameter=8", "--set", "solver.t_end=0.04", "--set", 'flow.fields_format="vtk"',
             "--set", "flow.dt=2e-4", "--set", "output.dt=2e-4"])  # trajectory.csv has a row at every flow step
        check_folder(out, data)
        out = Path(tmp) / "pair"
        pair = Path(tmp) / "gg3462.toml"  # its flow step fixed instead of its Courant number (dt and cfl exclude each other)
        text = (data / "scenes/coupled/gg3462.toml").read_text()
        pair.write_text("\n".join(ln for ln in text.splitlines() if not ln.startswith("cfl =")) + "\n")
        run([imcol, "run", str(pair), "--out", str(out), "--no-plot", "--quiet", "--set", "flow.cells_per_diameter=8",
             "--set", 'flow.fields_format="vtk"', "--set", "flow.dt=6e-3", "--set", "output.dt=6e-3"])
        check_folder(out, data)
        out = Path(tmp) / "flow"  # prescribed motion, the sphere above its wall
        run([imcol, "flow", str(data / "scenes/flow/sphere_wall_approach_re0.1.toml"), "--out", str(out), "--no-plot",
             "--cells", "8", "--levels", "3", "--t-end", "0.5", "--dt", "0.05"])
        check_folder(out, data, coupled=False)
    print("vtk_fields: OK")


if __name__ == "__main__":
    main()
