#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""The plot scripts on small real outputs of imcol (run, sweep with --export dem, history sweep and single-scene
comparison, a coupled run's flow snapshots): each exits 0 and writes its PNGs at the figure's size; and their
helpers on hand-made inputs: the run's phases, the deviation from a correlation, coinciding measures drawn as one
(in plain words with their settings), the kernels' sources, the composition of grid levels (finest wins), the
snapshot comment line read exactly and the kernel's outline dashed only a pixel or more from the trajectory's sphere.

Usage: /usr/bin/python3 tests/test_plots.py --imcol BUILD/bin/imcol   (run by ctest as plot_scripts)
"""
import json
import math
import shutil
import struct
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

import numpy as np

SCRIPTS = Path(__file__).resolve().parent.parent / "scripts"
sys.path.insert(0, str(SCRIPTS))

from flow_field import compose_levels, draw_bodies, parse_comment  # noqa: E402
from imcol_plot import deviation_at, deviation_text, kernel_label, liquid_text, plt  # noqa: E402
from plot_run import run_phases  # noqa: E402
from plot_sweep import measure_groups, sweep_title  # noqa: E402

IMCOL = None  # set from --imcol


def png_size(path: Path):
    """(width, height) in pixels from a PNG's IHDR chunk."""
    with open(path, "rb") as f:
        head = f.read(24)
    assert head[:8] == b"\x89PNG\r\n\x1a\n", path
    return struct.unpack(">II", head[16:24])


class RealOutputs(unittest.TestCase):
    """Each script as imcol runs it, on an output of the built program."""

    @classmethod
    def setUpClass(cls):
        cls.dir = Path(tempfile.mkdtemp(prefix="imcol_test_plots_"))

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.dir, ignore_errors=True)

    def imcol(self, *args):
        r = subprocess.run([IMCOL, *args, "--no-plot"], capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)

    def script(self, name, folder):
        r = subprocess.run(["/usr/bin/python3", str(SCRIPTS / name), str(folder)], capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)

    def test_run_picture(self):
        out = self.dir / "run"
        self.imcol("run", "default", "--quiet", "--out", str(out))
        self.script("plot_run.py", out)
        # 13.5 in wide at 100 dpi; rows of 3 in: z, u, forces (1.15), energy budget (0.85), and 0.6 in for the title
        self.assertEqual(png_size(out / "trajectory.png"), (1350, 1260))
        summary = json.loads((out / "summary.json").read_text())
        phases = run_phases(summary, 0.0, summary["solver"]["t_final_s"])
        self.assertEqual([p[0] for p in phases], ["approach", "contact", "rebound"])
        self.assertEqual(phases[1][1:], (summary["contact"]["t_contact_s"], summary["contact"]["t_separation_s"]))

    def test_sweep_picture_with_dem_fits_and_a_liggghts_block(self):
        out = self.dir / "sweep"
        self.imcol("sweep", "default", "--vary", "velocity", "--from", "0.1", "--to", "1", "--points", "4", "--jobs", "2",
                   "--no-progress", "--export", "dem", "--out", str(out))
        self.script("plot_sweep.py", out)
        self.assertEqual(png_size(out / "sweep.png"), (1800, 990))  # two panels, 15 x 8.25 in at 120 dpi
        # an optional `liggghts` block (parameters, residuals, replayed points) is drawn, not required
        dem = json.loads((out / "dem.json").read_text())
        dem["liggghts"] = {"CriticalStokes": 14.9, "MaximumRestitution": 0.97, "rms_residual": 0.02, "max_residual": 0.05,
                           "points": [{"St": 30.0, "e_replay": 0.4}, {"St": 300.0, "e_replay": 0.9}]}
        (out / "dem.json").write_text(json.dumps(dem))
        (out / "sweep.png").unlink()
        self.script("plot_sweep.py", out)
        self.assertTrue((out / "sweep.png").exists())
        # a sweep beside another (here itself): one legend of measures, one of solid and dashed
        r = subprocess.run(["/usr/bin/python3", str(SCRIPTS / "plot_sweep.py"), str(out), "--compare", str(out), "--out",
                            str(out / "compare.png")], capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(png_size(out / "compare.png"), (1800, 990))

    def test_history_pictures(self):
        out = self.dir / "history_sweep"
        self.imcol("history", "default", "--kernels", "basset,kim", "--vary", "velocity", "--from", "0.1", "--to", "1",
                   "--points", "3", "--jobs", "2", "--no-progress", "--out", str(out))
        self.script("plot_history.py", out)
        self.assertEqual(png_size(out / "history_sweep.png"), (1380, 1020))
        one = self.dir / "history"
        self.imcol("history", "default", "--kernels", "basset,mei-adrian", "--evaluators", "soe", "--out", str(one))
        self.script("plot_history.py", one)
        self.assertEqual(png_size(one / "history.png"), (1680, 744))

    def test_coupled_flow_pictures(self):
        out = self.dir / "coupled"
        self.imcol("run", "coupled/gg3462", "--quiet", "--out", str(out))
        self.script("plot_coupled_flow.py", out)
        snaps = sorted(out.glob("flow_*.csv"))
        self.assertGreaterEqual(len(snaps), 3)
        for snap in snaps:
            for png in (snap.with_suffix(".png"), snap.with_name(snap.stem + "_pressure.png")):
                # panels 7.5 in wide, 0.85 in left of them, colour bar and its label 1.87 in right: 10.22 in at 110 dpi
                self.assertEqual(png_size(png)[0], 1124, png)
                self.assertGreater(png.stat().st_size, 50000)


class HistoryOverheadPicture(unittest.TestCase):
    """plot_history_overhead.py on a hand-made table of the benchmark's columns: one panel per scene, the ratio range
    at equal error in its title."""

    def test_one_panel_per_scene_with_the_ratio_range(self):
        from plot_history_overhead import by_scene  # noqa: E402
        head = "scene,rtol,err_with,ms_with,steps_with,err_without,ms_without,steps_without,ratio_equal_error\n"
        rows = ["a,1e-6,1e-5,2.0,300,2e-5,1.0,290,1.5", "a,1e-8,1e-7,3.0,500,2e-7,2.0,480,1.25",
                "b,1e-6,1e-6,2.5,300,1e-5,1.5,300,nan"]
        with tempfile.TemporaryDirectory() as d:
            csv_path, png = Path(d) / "h.csv", Path(d) / "h.png"
            csv_path.write_text(head + "\n".join(rows) + "\n")
            r = subprocess.run(["/usr/bin/python3", str(SCRIPTS / "plot_history_overhead.py"), str(csv_path), str(png)],
                               capture_output=True, text=True)
            self.assertEqual(r.returncode, 0, r.stderr)
            w, h = png_size(png)
            self.assertEqual((w, h), (1320, 540))  # two panels of 5.5 x 4.5 in at 120 dpi
        import imcol_plot as ip  # noqa: E402
        scenes = by_scene([dict(zip(head.strip().split(","), r.split(","))) for r in rows])
        self.assertEqual(list(scenes), ["a", "b"])
        fig, ax = ip.plt.subplots()
        from plot_history_overhead import panel  # noqa: E402
        panel(ax, "a", scenes["a"])
        self.assertIn("1.25-1.50x", ax.get_title())
        ip.plt.close(fig)


class Helpers(unittest.TestCase):
    def test_deviation_from_a_correlation(self):
        st = [30.0, 100.0, 750.0]
        model, reference = [0.52, 0.80, 0.96], [0.31, 0.70, 0.94]
        self.assertEqual(deviation_text("Legendre (2006)", st, model, reference),
                         "imcol − Legendre (2006): +0.21 at St 30, +0.02 at St 750")
        # the largest deviation named when it lies inside the range; no negative zero
        self.assertEqual(deviation_text("L", [6.0, 46.0, 1066.0], [0.0, 0.62, 0.97], [0.003, 0.45, 0.968], "St_L"),
                         "imcol − L: +0.00 at St_L 6, +0.17 at St_L 46 (largest), +0.00 at St_L 1066")
        # between points: linear in log St (halfway in log between 30 and 100: the mean of +0.21 and +0.10)
        (x, d), = deviation_at(st, model, reference, [math.sqrt(30.0 * 100.0)])
        self.assertAlmostEqual(d, 0.155)
        self.assertTrue(math.isnan(deviation_at(st, model, reference, [1000.0])[0][1]))
        self.assertEqual(deviation_text("x", st, [float("nan")] * 3, reference), "")

    def test_coinciding_measures_are_one_curve_that_says_so(self):
        rows = [{"status": "ok", "e": str(e), "e_fit_distance": str(e), "e_fit_time": str(e + 0.01), "e_instant": str(e),
                 "e_at_gap": "", "e_peak_rebound": str(e + 0.02)} for e in (0.3, 0.6)]
        groups = measure_groups(rows, {"e_is": "joseph_2001"})
        self.assertEqual([g[0] for g in groups], [["e_fit_distance", "e_instant"], ["e_fit_time"], ["e_peak_rebound"]])
        self.assertTrue(groups[0][1].startswith("imcol's e: "))
        self.assertIn("identical here", groups[0][1])
        self.assertEqual(groups[1][1], "e from lines fitted over 10 ms (Yang & Hunt 2006)")  # the default window
        # a set gap in plain words with the sweep's value, no key name; colours fixed per measure
        at_gap = measure_groups([dict(r, e_at_gap=str(float(r["e"]) - 0.05)) for r in rows], {"e_is": "joseph_2001",
                                                                          "overrides": {"measure.at_gap": 0.25}})
        self.assertIn((["e_at_gap"], "e from the speeds at a set gap (0.25 D)", "v", "-.", "C3"), at_gap)
        self.assertFalse(any("measure." in g[1] for g in at_gap))

    def test_run_without_contact_is_one_phase(self):
        self.assertEqual(run_phases({"contact": None}, 0.0, 1.0), [("the whole run", 0.0, 1.0)])
        cut = run_phases({"contact": {"t_contact_s": 0.4, "t_separation_s": None}}, 0.0, 1.0)
        self.assertEqual(cut[-1], ("contact (to the end of the run)", 0.4, 1.0))

    def test_kernels_and_liquids_are_named(self):
        self.assertEqual(kernel_label("kim"), "kim: Kim, Elghobashi & Sirignano (1998)")
        self.assertIn("Basset (1888)", kernel_label("basset"))
        self.assertEqual(liquid_text({"name": "glycerol-water", "mass_fraction": 0.5, "temperature_C": 20.0,
                                      "viscosity_Pa_s": 0.006, "density_kg_m3": 1126.0}),
                         "glycerol-water 50 wt% at 20 °C, μ = 6 mPa s, ρ = 1126 kg/m³")
        self.assertEqual(liquid_text({"viscosity_Pa_s": 0.0, "density_kg_m3": 0.0}), "no liquid")
        self.assertEqual(liquid_text({"viscosity_Pa_s": None, "density_kg_m3": 1200.0}), "a liquid of ρ = 1200 kg/m³")

    def test_compared_sweeps_title_names_bodies_and_liquid(self):
        meta = {"scene": "default", "scene_file": "data/scenes/default.toml", "vary": "viscosity", "from": 0.42, "to": 0.0033,
                "points": 12, "failures": [], "effects": ["drag", "added_mass"]}
        title = sweep_title(meta, [(None, dict(meta, effects=["drag", "added_mass", "flow"]))])
        self.assertEqual(title, "default: 12.7 mm steel sphere onto a zerodur wall in a liquid of ρ = 1200 kg/m³\n"
                                "e against St, viscosity from 0.42 to 0.0033 Pa s, 12 points in each of 2 sweeps; "
                                "effects: drag, added mass; the dashed sweep adds the flow solver (coupled)")

    def test_levels_composed_finest_wins(self):
        # level 0: h = 0.1 over [0, 1] x [0, 2], f = r + z; level 1: h = 0.2 over [0, 2] x [-1, 3], f = r + z + 100
        def level(n, h, r_n, z0, z_n, offset):
            r, z = h * np.arange(r_n + 1), z0 + h * np.arange(z_n + 1)
            return (n, r, z, {"f": r[:, None] + z[None, :] + offset})

        levels = [level(0, 0.1, 10, 0.0, 20, 0.0), level(1, 0.2, 10, -1.0, 20, 100.0)]
        rq = np.array([0.55, 0.05, 1.5, 0.5, 2.5])
        zq = np.array([1.23, 0.0, 1.0, -0.5, 0.0])
        F, L = compose_levels(levels, "f", rq, zq)
        self.assertEqual(L.tolist(), [0, 0, 1, 1, -1])
        np.testing.assert_allclose(F[:4], rq[:4] + zq[:4] + np.array([0, 0, 100, 100]), atol=1e-12)  # bilinear: exact
        self.assertTrue(np.isnan(F[4]))

    def test_snapshot_comment_line_read_exactly(self):
        head = ("contact, t = 0.0243052814 s; level 0 is the finest; psi is the total Stokes streamfunction (m^3/s); "
                "z_shift = 0.00957212327 m; spheres (z, d) = 0.00302368577 0.0127 0.0161205608 0.0127")
        line = head + ("; trajectory spheres (z, d) = 0.00309574946 0.0127 0.0160484995 0.0127; "
                       "gap = 0.000252750079 m = 0.019901581 D")
        info = parse_comment(line)
        self.assertEqual(info["spheres"], [(0.00302368577, 0.0127), (0.0161205608, 0.0127)])
        self.assertEqual(info["true_spheres"], [(0.00309574946, 0.0127), (0.0160484995, 0.0127)])
        self.assertEqual((info["gap_m"], info["gap_D"]), (0.000252750079, 0.019901581))
        self.assertEqual(info["z_shift_m"], 0.00957212327)
        # one sphere, exponents, no gap part (no wall, no pair); a file written before the trajectory part
        one = parse_comment("t = 3.45 s; z_shift = 0 m; spheres (z, d) = -0.003375 0.006; "
                            "trajectory spheres (z, d) = -3.08061785e-03 6e-03")
        self.assertEqual(one["true_spheres"], [(-0.00308061785, 0.006)])
        self.assertNotIn("gap_m", one)
        old = parse_comment(head)
        self.assertNotIn("true_spheres", old)
        self.assertNotIn("gap_m", old)
        # a label naming a gap is not the gap; a garbled part is left out
        self.assertNotIn("gap_m", parse_comment("gap 1 D, t = 0.0121526407 s; spheres (z, d) = -0.0089 0.006"))
        self.assertEqual(parse_comment("t = 1 s; spheres (z, d) = garbled; gap = 2 D"), {})

    def test_kernel_outline_drawn_only_a_pixel_away(self):
        fig, ax = plt.subplots(figsize=(5, 2.5), dpi=100)  # 4 mm over about 400 pixels: a pixel is ~0.01 mm
        ax.set_xlim(-4.0, 0.0)
        ax.set_ylim(-2.0, 2.0)
        kernel, wall = [(-3.375e-3, 6e-3)], 0.0
        self.assertTrue(draw_bodies(ax, kernel, [(-3.08e-3, 6e-3)], wall, -4e-3, 1e-3))
        dashed = [c for c in ax.patches if isinstance(c, plt.Circle) and not c.get_fill()]
        self.assertEqual(len(dashed), 1)
        self.assertAlmostEqual(dashed[0].center[0], -3.375)  # the kernel's, dashed; the trajectory's filled
        filled = [c for c in ax.patches if isinstance(c, plt.Circle) and c.get_fill()]
        self.assertEqual(len(filled), 1)
        self.assertAlmostEqual(filled[0].center[0], -3.08)
        self.assertFalse(draw_bodies(ax, kernel, [(-3.375e-3 + 2e-6, 6e-3)], wall, -4e-3, 1e-3))  # 0.002 mm: under a pixel
        self.assertFalse(draw_bodies(ax, kernel, None, wall, -4e-3, 1e-3))
        plt.close(fig)


if __name__ == "__main__":
    if "--imcol" in sys.argv:
        i = sys.argv.index("--imcol")
        IMCOL = sys.argv[i + 1]
        del sys.argv[i:i + 2]
    if IMCOL is None:
        sys.exit("usage: test_plots.py --imcol BUILD/bin/imcol")
    unittest.main()
