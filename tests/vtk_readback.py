#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Reads imcol's VTK flow-field files back with an independent reader and checks them against the CSV snapshots.

Runs imcol into a temporary folder (a coarse coupled run with regular snapshots, a coarse `imcol flow` scene with a
wall), then for every snapshot written in both formats: meshio (Debian's python3-meshio) reads each level's .vtu;
the point count, the coordinates (x, y, z) = (r, 0, z) and every field (velocity_m_s = (u_r, 0, u_z),
stream_function_m3_s = psi, vorticity_1_s = omega, pressure_Pa = p) must equal the CSV's rows of that level. The
.vtu arrays are binary Float64, the CSV prints 9 significant digits: each value must agree to 5e-9 of its size
(half a unit in the 9th digit), zeros exactly.
The .pvd and .vtm files are parsed as XML (stdlib): every file they name exists, the times increase and match the
CSV's; the `finer` cell field marks exactly the cells a finer level covers; the kernel's spheres, the trajectory's
spheres and the wall are where the CSV's comment line and summary.json put them.
Needs /usr/bin/python3 with python3-meshio and python3-numpy.
"""
import json
import re
import sys
import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path

from imcol_script_args import imcol_and_data, run as run_checked

import meshio
import numpy as np

REL = 5e-9 * (1 + 1e-9)  # %.9g: half a unit in the 9th significant digit, relative to the value (and the parse)


def fail(msg):
    print(f"vtk_readback: FAIL: {msg}", file=sys.stderr)
    sys.exit(1)


def close(vtk, csv, what):
    vtk = np.asarray(vtk, dtype=float)
    csv = np.asarray(csv, dtype=float)
    if vtk.shape != csv.shape:
        fail(f"{what}: {vtk.shape} values in the VTK file, {csv.shape} in the CSV")
    err = np.abs(vtk - csv)
    bad = err > REL * np.abs(vtk)
    if bad.any():
        k = int(np.argmax(bad))
        fail(f"{what}: {int(bad.sum())} values differ beyond {REL:g} relative, e.g. VTK {vtk.flat[k]!r} vs CSV {csv.flat[k]!r}")
    return float((err / np.maximum(np.abs(vtk), 1e-300)).max())


def read_csv(path):
    lines = path.read_text().splitlines()
    head = lines[0]
    cols = lines[1].split(",")
    rows = np.array([[float(x) for x in ln.split(",")] for ln in lines[2:]])
    t = float(re.search(r"t = (\S+) s;", head).group(1))
    z_d = [float(x) for x in head.split("; spheres (z, d) =")[1].split(";")[0].split()]
    tz_d = [float(x) for x in head.split("; trajectory spheres (z, d) =")[1].split(";")[0].split()]
    return head, cols, rows, t, {"kernel_spheres": list(zip(z_d[0::2], z_d[1::2])), "spheres": list(zip(tz_d[0::2], tz_d[1::2]))}


def xml_files(path):
    """The .pvd/.vtm's DataSet entries (attributes), checked to exist."""
    root = ET.parse(path).getroot()
    sets = root.findall(".//DataSet")
    for s in sets:
        if not (path.parent / s.get("file")).is_file():
            fail(f"{path.name} names {s.get('file')}, which does not exist")
    return root, sets


def check_bodies(out, vtm_sets, vtm, sets, wall_z):
    files = {s.get("name"): vtm.parent / s.get("file") for s in vtm_sets}
    for block, spheres in sets.items():
        check_spheres(files[block], vtm, spheres)
    check_wall(files, vtm, wall_z)


def check_spheres(path, vtm, spheres):
    root = ET.parse(path).getroot()
    pts = np.array(root.find(".//Points/DataArray").text.split(), dtype=float).reshape(-1, 3)
    offsets = np.array(root.find(".//Lines/DataArray[@Name='offsets']").text.split(), dtype=int)
    if len(offsets) != len(spheres):
        fail(f"{vtm.name}: {len(offsets)} spheres in the .vtp, {len(spheres)} in the CSV")
    start = 0
    for (zc, d), end in zip(spheres, offsets):
        p = pts[start:end]
        start = end
        if abs(p[:, 2].min() - (zc - d / 2)) > 1e-8 * d or abs(p[:, 2].max() - (zc + d / 2)) > 1e-8 * d or abs(p[:, 0].max() - d / 2) > 1e-8 * d:
            fail(f"{path.name}: a sphere's polyline spans z {p[:, 2].min()}..{p[:, 2].max()}, r up to {p[:, 0].max()}; the CSV says z = {zc}, d = {d}")
        if np.any(p[:, 1] != 0):
            fail(f"{path.name}: a sphere's polyline leaves the plane y = 0")


def check_wall(files, vtm, wall_z):
    if wall_z is None:
        if "wall" in files:
            fail(f"{vtm.name}: a wall dataset without a wall")
    else:
        if "wall" not in files:
            fail(f"{vtm.name}: no wall dataset")
        w = np.array(ET.parse(files["wall"]).getroot().find(".//Points/DataArray").text.split(), dtype=float).reshape(-1, 3)
        if not np.allclose(w[:, 2], wall_z, rtol=0, atol=1e-12 * max(1.0, abs(wall_z))):
            fail(f"{vtm.name}: the wall is at z = {w[:, 2]}, expected {wall_z}")


def check_folder(out, wall_z):
    pvd = out / "flow.pvd"
    if not pvd.is_file():
        fail(f"no flow.pvd in {out}")
    _, entries = xml_files(pvd)
    times = [float(e.get("timestep")) for e in entries]
    if len(times) < 2 or any(b <= a for a, b in zip(times, times[1:])):
        fail(f"{pvd}: times must increase over at least two snapshots: {times}")
    compared = 0
    worst = 0.0
    for entry, t in zip(entries, times):
        vtm = out / entry.get("file")
        root, sets = xml_files(vtm)
        levels = [s for s in root.find("./vtkMultiBlockDataSet/Block[@name='levels']").findall("DataSet")]
        bodies = root.find("./vtkMultiBlockDataSet/Block[@name='bodies']").findall("DataSet")
        csv_path = out / (vtm.stem + ".csv")
        if not csv_path.is_file():
            continue
        head, cols, rows, t_csv, sphere_sets = read_csv(csv_path)
        if cols[:3] != ["level", "r", "z"] or not {"psi", "omega", "u_r", "u_z"} <= set(cols):
            fail(f"{csv_path.name}: unexpected columns {cols}")
        if abs(t - t_csv) > REL * max(abs(t), 1e-300) and not (t == 0 and t_csv == 0):
            fail(f"{pvd.name}: time {t} for {vtm.name}, the CSV says {t_csv}")
        n_levels = int(rows[:, 0].max()) + 1
        if len(levels) != n_levels:
            fail(f"{vtm.name}: {len(levels)} level datasets, the CSV has {n_levels} levels")
        for lv, ds in enumerate(levels):
            mesh = meshio.read(vtm.parent / ds.get("file"))
            sel = rows[rows[:, 0] == lv]
            c = {name: sel[:, k] for k, name in enumerate(cols)}
            what = f"{vtm.parent.name}/{ds.get('file')}"
            if len(mesh.points) != len(sel):
                fail(f"{what}: {len(mesh.points)} points, the CSV has {len(sel)} rows for level {lv}")
            worst = max(worst, close(mesh.points[:, 0], c["r"], what + " x = r"))
            worst = max(worst, close(mesh.points[:, 2], c["z"], what + " z = z"))
            if np.any(mesh.points[:, 1] != 0):
                fail(f"{what}: y coordinate not 0")
            pd = mesh.point_data
            worst = max(worst, close(pd["velocity_m_s"][:, 0], c["u_r"], what + " velocity_m_s[0] = u_r"))
            worst = max(worst, close(pd["velocity_m_s"][:, 2], c["u_z"], what + " velocity_m_s[2] = u_z"))
            if np.any(pd["velocity_m_s"][:, 1] != 0):
                fail(f"{what}: velocity's y component not 0")
            worst = max(worst, close(pd["stream_function_m3_s"], c["psi"], what + " stream_function_m3_s = psi"))
            worst = max(worst, close(pd["vorticity_1_s"], c["omega"], what + " vorticity_1_s = omega"))
            if "p" in c:
                worst = max(worst, close(pd["pressure_Pa"], c["p"], what + " pressure_Pa = p"))
            for col in cols[3:]:  # any further field: its VTK array has the same values
                if col in ("psi", "omega", "u_r", "u_z"):
                    continue
                match = [k for k, v in pd.items() if v.ndim == 1 and np.array_equal(v.shape, c[col].shape)
                         and np.all(np.abs(v - c[col]) <= REL * np.abs(v))]
                if not match:
                    fail(f"{what}: no point array matches the CSV column {col}")
            if not np.any(pd["vorticity_1_s"] != 0) or not np.any(pd["velocity_m_s"] != 0):
                fail(f"{what}: the flow is zero everywhere (nothing was compared)")
            # cells: quads; `finer` marks the (nr/2)·(nz/2) cells the next finer level covers
            quads = mesh.cells_dict.get("quad")
            nr, nz = int(round(c["r"].max() / (c["r"][c["r"] > 0].min()))), len(np.unique(c["z"])) - 1
            if quads is None or len(quads) != nr * nz:
                fail(f"{what}: expected {nr * nz} quads")
            finer = mesh.cell_data["finer"][0]
            if lv == 0 and finer.any() or lv > 0 and int(finer.sum()) != (nr // 2) * (nz // 2):
                fail(f"{what}: {int(finer.sum())} cells marked finer, expected {0 if lv == 0 else (nr // 2) * (nz // 2)}")
            if np.any(mesh.cell_data["level"][0] != lv):
                fail(f"{what}: cell field level is not {lv}")
            compared += 1
        check_bodies(out, bodies, vtm, sphere_sets, wall_z)
    if compared == 0:
        fail(f"{out}: no snapshot with both a .vtm and a .csv")
    print(f"{out.name}: {len(entries)} snapshots in flow.pvd, {compared} level files compared with the CSV; "
          f"largest relative difference {worst:.2e} (bound {REL:g})")


def run(cmd):
    run_checked(cmd, fail)


def main():
    imcol, data = imcol_and_data(__doc__)
    with tempfile.TemporaryDirectory(prefix="imcol_vtk_") as tmp:
        tmp = Path(tmp)
        # coupled, two spheres: the named moments and a snapshot every 10 ms from t = 0
        out = tmp / "coupled"
        run([imcol, "run", str(data / "scenes/coupled/gg3462.toml"), "--out", str(out), "--no-plot", "--quiet",
             "--set", "flow.cells_per_diameter=8", "--set", "flow.fields_every=0.01"])
        if len(list((out / "vtk").glob("fields_*.vtm"))) < 3:
            fail("coupled: fewer than 3 regular snapshots with flow.fields_every = 0.01 over 60 ms")
        check_folder(out, None)
        # a flow scene with a wall, coarse, in the kernel's frame
        out = tmp / "flow"
        run([imcol, "flow", str(data / "scenes/flow/sphere_wall_approach_re0.1.toml"), "--out", str(out), "--no-plot",
             "--cells", "8", "--levels", "3", "--t-end", "0.5", "--dt", "0.05"])
        wall = json.loads((out / "summary.json").read_text())["wall"]["position"]
        check_folder(out, wall)
        # CSV only: no VTK files
        out = tmp / "csv_only"
        run([imcol, "run", str(data / "scenes/coupled/gg3462.toml"), "--out", str(out), "--no-plot", "--quiet",
             "--set", "flow.cells_per_diameter=8", "--set", 'flow.fields_format="csv"'])
        if (out / "vtk").exists() or (out / "flow.pvd").exists() or not (out / "flow_end.csv").is_file():
            fail("flow.fields_format = \"csv\" must write the CSV snapshots and no VTK files")
    print("vtk_readback: OK")


if __name__ == "__main__":
    main()
