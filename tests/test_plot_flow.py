#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""The flow pictures' scripts (scripts/plot_flow.py, scripts/plot_coupled_flow.py) on snapshots of Stokes flow past
a sphere (exact ψ, ω and p): the masking keeps every streamline vertex outside the spheres and on the fluid's side of
the wall, the units follow the scene, and both scripts exit 0 and write their PNGs with and without a pressure
column `p` (a pressure PNG only with it).

Usage: /usr/bin/python3 tests/test_plot_flow.py (run by ctest as plot_flow_scripts)
"""
import json
import shutil
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

import numpy as np

SCRIPTS = Path(__file__).resolve().parent.parent / "scripts"
sys.path.insert(0, str(SCRIPTS))

from plot_flow import outside_fluid, plt, read_snapshot, scene_units, si_units, streamline_levels, streamlines, thin_ticks  # noqa: E402

A, U, MU = 1e-3, 0.01, 1e-3  # a 2 mm sphere at the origin in a stream of 1 cm/s along +z, water's viscosity


def stokes(r, z):
    """Stokes flow past the fixed sphere: total ψ (m³/s), ω_θ (1/s) and p − p∞ (Pa) at cylindrical (r, z)."""
    R = np.maximum(np.hypot(r, z), 1e-12)
    psi = 0.5 * U * r**2 * (1 - 1.5 * A / R + 0.5 * A**3 / R**3)
    omega = -1.5 * U * A * r / R**3  # sinθ / R² with sinθ = r / R
    p = -1.5 * MU * U * A * z / R**3  # cosθ / R²
    return psi, omega, p


def snapshot_text(levels, spheres, with_p, label="t = 0.5 s"):
    """A snapshot CSV as imcol writes it: levels [(h, nr, nz, z0)] (level 0 the finest), optionally a column p."""
    head = f"# {label}; level 0 is the finest; psi is the total Stokes streamfunction (m^3/s); z_shift = 0 m; spheres (z, d) ="
    head += "".join(f" {zc!r} {d!r}" for zc, d in spheres)
    lines = [head, "level,r,z,psi,omega,u_r,u_z" + (",p" if with_p else "")]
    for level, (h, nr, nz, z0) in enumerate(levels):
        for i in range(nr + 1):
            for j in range(nz + 1):
                r, z = i * h, z0 + j * h
                psi, om, p = stokes(r, z)
                row = [level, r, z, psi, om, 0.0, U] + ([p] if with_p else [])
                lines.append(",".join(repr(float(v)) if k else str(v) for k, v in enumerate(row)))
    return "\n".join(lines) + "\n"


LEVELS = [(A / 8, 24, 64, -4 * A), (A / 4, 24, 64, -8 * A)]  # 16 cells per diameter, two levels


class Masking(unittest.TestCase):
    def setUp(self):
        h, nr, nz, z0 = LEVELS[0]
        self.r = np.arange(nr + 1) * h
        self.z = z0 + np.arange(nz + 1) * h
        self.R = np.concatenate([-self.r[:0:-1], self.r])
        Z, RR = np.meshgrid(self.z, self.R)
        self.P = stokes(np.abs(RR), Z)[0]

    def test_outside_fluid_marks_spheres_and_the_far_side_of_the_wall(self):
        spheres = [(0.0, 2 * A)]
        self.assertTrue(outside_fluid(0.0, 0.0, spheres))
        self.assertTrue(outside_fluid(0.99 * A, 0.0, spheres))
        self.assertFalse(outside_fluid(1.01 * A, 0.0, spheres))
        # the spheres lie on the wall's +z side: z below the wall is beyond it; on its -z side the other way round
        self.assertTrue(outside_fluid(5 * A, -2.1 * A, spheres, wall=-2 * A))
        self.assertFalse(outside_fluid(5 * A, -1.9 * A, spheres, wall=-2 * A))
        self.assertTrue(outside_fluid(5 * A, 2.1 * A, spheres, wall=2 * A))
        self.assertFalse(outside_fluid(5 * A, 1.9 * A, spheres, wall=2 * A))
        # a margin widens both (the colour scale of p leaves out the smeared surface layer)
        self.assertTrue(outside_fluid(1.2 * A, 0.0, spheres, margin=0.25 * A))
        self.assertTrue(outside_fluid(5 * A, 1.9 * A, spheres, wall=2 * A, margin=0.25 * A))
        self.assertFalse(outside_fluid(5 * A, 1.7 * A, spheres, wall=2 * A, margin=0.25 * A))

    def test_no_streamline_vertex_inside_the_sphere(self):
        spheres = [(0.0, 2 * A)]
        levels = streamline_levels(self.P)
        unmasked = streamlines(self.z, self.R, self.P, levels, [])
        inside = sum(int(np.sum(np.hypot(seg[:, 0], seg[:, 1]) < A)) for _, seg in unmasked)
        self.assertGreater(inside, 100)  # without masking, the closed ψ = const lines inside the sphere are drawn
        lines = streamlines(self.z, self.R, self.P, levels, spheres)
        self.assertGreater(sum(len(seg) for _, seg in lines), 2000)  # the flow outside is still drawn
        for _, seg in lines:
            self.assertTrue(np.all(np.hypot(seg[:, 0], seg[:, 1]) >= A), seg[np.hypot(seg[:, 0], seg[:, 1]) < A][:3])

    def test_no_streamline_vertex_beyond_the_wall(self):
        spheres, wall = [(0.0, 2 * A)], -1.6 * A
        lines = streamlines(self.z, self.R, self.P, streamline_levels(self.P), spheres, wall)
        self.assertGreater(len(lines), 20)
        for _, seg in lines:
            self.assertTrue(np.all(seg[:, 0] >= wall))
            self.assertTrue(np.all(np.hypot(seg[:, 0], seg[:, 1]) >= A))

    def test_streamline_levels_skip_a_negligible_opposite_side(self):
        levels = streamline_levels(np.array([-1e-4, 0.0, 1.0]))
        self.assertTrue(np.all(levels >= 0))  # 0.01 % of the other side: the smeared surface's noise
        self.assertEqual(len(levels), 30)
        levels = streamline_levels(np.array([-0.2, 0.0, 1.0]))
        self.assertEqual(int(np.sum(levels < 0)), 5)
        levels = streamline_levels(np.array([-1.0, 0.0, 0.05]))  # mostly ψ < 0 (a sphere moving along -z)
        self.assertEqual(int(np.sum(levels < 0)), 29)
        self.assertEqual(int(np.sum(levels > 0)), 5)


class Units(unittest.TestCase):
    def test_si_lengths_in_mm_below_5_cm(self):
        self.assertEqual(si_units(0.002).length, 1e-3)
        self.assertEqual(si_units(0.002).z, "z [mm]")
        self.assertEqual(si_units(0.1).z, "z [m]")
        self.assertEqual(si_units(0.002).omega_name, "ω [1/s]")
        self.assertEqual(si_units(0.002).time_text(0.0123), "t = 0.0123 s")

    def test_scene_units(self):
        with tempfile.TemporaryDirectory() as tmp:
            scene = Path(tmp) / "s.toml"
            summary = {"scene": str(scene), "grid": {"h": 1 / 16, "cells_per_diameter": 16}}
            scene.write_text("[fluid]\ndensity = 1.0\nviscosity = 0.1\n[stream]\nvelocity = 2.0\n[[sphere]]\ndiameter = 1.0\n")
            u = scene_units(summary)
            self.assertEqual((u.z, u.t, u.omega_name), ("z / D", "t U / D", "ω D / U"))
            self.assertAlmostEqual(u.time, 0.5)  # D / U
            self.assertAlmostEqual(u.force, 4.0)  # ρ U² D²
            self.assertEqual(u.time_text(1.0), "t U / D = 2")
            scene.write_text("[fluid]\ndensity = 1000.0\nviscosity = 1e-3\n[stream]\nvelocity = 0.01\n[[sphere]]\ndiameter = 0.002\n")
            summary["grid"]["h"] = 0.002 / 16
            u = scene_units(summary)
            self.assertEqual((u.z, u.t, u.force_label, u.pressure_name), ("z [mm]", "t [s]", "force along +z [N]", "p − p∞ [Pa]"))


class Ticks(unittest.TestCase):
    def test_tick_labels_do_not_overlap(self):
        """Level 1 of a 2 mm sphere in metres (the labels that overlapped) and in mm, in a narrow panel."""
        for lo, hi in ((-0.0101, 0.0121), (-10.1, 12.1), (-0.0382, 0.0052)):
            fig, ax = plt.subplots(figsize=(6, 3))
            ax.set_xlim(lo, hi)
            ax.set_ylim(0.4 * lo, -0.4 * lo)
            ax.set_aspect("equal")
            fig.colorbar(ax.pcolormesh([lo, hi], [0.4 * lo, -0.4 * lo], [[0.0]]), ax=ax)
            fig.tight_layout()
            thin_ticks(ax)
            fig.canvas.draw()
            for labels, first, last in ((ax.get_xticklabels(), "x0", "x1"), (ax.get_yticklabels(), "y0", "y1")):
                boxes = sorted((getattr(b, first), getattr(b, last)) for b in
                               (t.get_window_extent() for t in labels if t.get_visible() and t.get_text()))
                self.assertGreaterEqual(len(boxes), 2)
                for (_, end), (start, _) in zip(boxes, boxes[1:]):
                    self.assertLess(end, start, (lo, hi, [t.get_text() for t in labels]))
            plt.close(fig)


class Scripts(unittest.TestCase):
    """Both scripts as imcol runs them: exit 0, the PNGs written (a pressure PNG exactly when there is a column p)."""

    def setUp(self):
        self.dir = Path(tempfile.mkdtemp(prefix="imcol_test_plot_flow_"))

    def tearDown(self):
        shutil.rmtree(self.dir, ignore_errors=True)

    def run_script(self, script):
        r = subprocess.run(["/usr/bin/python3", str(SCRIPTS / script), str(self.dir)], capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)

    def check_pngs(self, stem, with_p):
        png = self.dir / f"{stem}.png"
        self.assertTrue(png.exists())
        self.assertGreater(png.stat().st_size, 20000)
        self.assertEqual((self.dir / f"{stem}_pressure.png").exists(), with_p)

    def test_plot_flow(self):
        for with_p in (False, True):
            for f in self.dir.iterdir():
                f.unlink()
            scene = self.dir / "scene.toml"
            scene.write_text(f"[fluid]\ndensity = 1000.0\nviscosity = {MU}\n[stream]\nvelocity = {U}\n"
                             f"[[sphere]]\ndiameter = {2 * A}\nposition = 0.0\n")
            summary = {"scene": str(scene), "name": "stokes_2mm", "Re": 20.0, "grid": {"h": A / 8, "cells_per_diameter": 16},
                       "drag_coefficient_standard": None}
            (self.dir / "summary.json").write_text(json.dumps(summary))
            f_stokes = 6 * np.pi * MU * A * U
            rows = ["t,z1,F1,C_D"] + [f"{t},0,{f_stokes * (1 + 1 / (1 + t))},{24 / 20}" for t in np.linspace(0.05, 0.5, 10)]
            (self.dir / "forces.csv").write_text("\n".join(rows) + "\n")
            (self.dir / "snapshot_00.csv").write_text(snapshot_text(LEVELS, [(0.0, 2 * A)], with_p))
            self.run_script("plot_flow.py")
            self.check_pngs("snapshot_00", with_p)
            self.assertTrue((self.dir / "forces.png").exists())
            _, levels = read_snapshot(self.dir / "snapshot_00.csv")
            self.assertEqual(len(levels), 2)
            self.assertEqual("p" in levels[0][3], with_p)

    def test_plot_coupled_flow_with_a_wall(self):
        for with_p in (False, True):
            for f in self.dir.iterdir():
                f.unlink()
            (self.dir / "summary.json").write_text(json.dumps({"configuration": "sphere-wall"}))
            # the sphere on the wall's -z side: the wall at z1 + D/2 + gap = 1.5 a
            t = np.linspace(0, 1, 5)
            (self.dir / "trajectory.csv").write_text("t,z1,gap\n" + "".join(f"{x},0,{0.5 * A}\n" for x in t))
            (self.dir / "flow_contact.csv").write_text(snapshot_text(LEVELS, [(0.0, 2 * A)], with_p, "contact, t = 0.5 s"))
            self.run_script("plot_coupled_flow.py")
            self.check_pngs("flow_contact", with_p)


if __name__ == "__main__":
    unittest.main()
