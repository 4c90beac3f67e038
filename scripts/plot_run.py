#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Plot one imcol run: positions and velocities against time, the force terms on linear axes per phase (approach,
contact, rebound), and the first collision's energy budget; one legend; the scene's parameters in the title.

Usage: /usr/bin/python3 scripts/plot_run.py OUT_DIR   (writes OUT_DIR/trajectory.png)
Needs Debian's python3-matplotlib (importable from /usr/bin/python3 only).
"""
import json
import math
import sys

from imcol_plot import (EFFECT_WORDS, FORCE_NAMES, bodies_text, figure_legend, force_label, liquid_text, out_dir, plt, read_rows, save_png,
                        scene_bodies)


def draw_e_fits(ax, ax_u, summary) -> None:
    """The windows and fitted curves behind e (first contact) on the position panel: the lines of joseph_2001 and
    fit_distance, the parabolas of contact_ends; their slopes as crosses on the velocity panel."""
    em = summary.get("e_measures") or {}
    name = summary.get("e_is")
    m = em.get(name) if isinstance(em, dict) else None
    if not m or not (m.get("approach") or m.get("rebound")):
        return
    curve = "parabolas" if name == "contact_ends" else "lines"
    first = True
    for side in ("approach", "rebound"):
        w = m.get(side)
        if not w:
            continue
        t0, t1 = w["t0_s"], w["t1_s"]
        ax.axvspan(1e3 * t0, 1e3 * t1, color="orange", alpha=0.25, lw=0, label=f"{name}: the stretches fitted" if first else None)
        span = t1 - t0
        for k in ("z1", "z2"):
            p = w.get(k)
            if not p:
                continue
            # the parabola over its window and one window beyond on the far side from the contact
            a, b = (t0 - span, t1) if side == "approach" else (t0, t1 + span)
            ts = [a + (b - a) * i / 60 for i in range(61)]
            zs = [p["z_m"] + p["u_m_s"] * (t - p["t_ref_s"]) + 0.5 * p["a_m_s2"] * (t - p["t_ref_s"]) ** 2 for t in ts]
            ax.plot([1e3 * t for t in ts], [1e3 * z for z in zs], color="k", lw=0.9, ls="--",
                    label=f"fitted {curve} (their slopes give e)" if first else None)
            ax_u.plot([1e3 * p["t_ref_s"]], [p["u_m_s"]], "x", color="k", ms=7,
                      label="fitted velocities behind e" if first else None)
            first = False


# The budget's forces (summary.json `energy_budget`) and the trajectory's force columns they are.
BUDGET_FORCES = {"drag": "f_drag", "lubrication": "f_lub", "added_mass": "f_am", "history": "f_hist", "contact": "f_contact",
                 "gravity": "f_grav", "simulated": "f_sim"}


def draw_energy_budget(ax, summary) -> None:
    """The first collision's energy budget (summary `energy_budget`): what each force dissipated in each phase, in
    units of the impact kinetic energy (negative: the force gave energy to the spheres)."""
    budget = summary.get("energy_budget")
    if not budget:
        ax.set_visible(False)
        return
    phases = [p for p in budget["phases"] if p["phase"] != "collision"]
    stems = list(FORCE_NAMES)  # the force panel's colours, by the budget's names of the same forces
    colour = {f: f"C{stems.index(stem)}" for f, stem in BUDGET_FORCES.items()}
    forces = [f for f in BUDGET_FORCES if any(abs(p["dissipated_per_impact_energy"].get(f, 0.0)) > 1e-4 for p in phases)]
    width = 0.8 / max(1, len(forces))
    for i, f in enumerate(forces):
        xs = [k + (i - (len(forces) - 1) / 2) * width for k in range(len(phases))]
        ax.bar(xs, [p["dissipated_per_impact_energy"].get(f, 0.0) for p in phases], width, label=f.replace("_", " "),
               color=colour[f])
    ax.axhline(0, color="k", lw=0.6)
    ax.set_xticks(range(len(phases)), [f"{p['phase']}\n{1e3 * p['t0_s']:.2f}-{1e3 * p['t1_s']:.2f} ms" for p in phases])
    worst = max(abs(p["closure_per_impact_energy"]) for p in budget["phases"])
    ax.set_ylabel("energy dissipated /\nimpact kinetic energy")
    ax.set_title(f"energy budget of the first collision: impact kinetic energy {1e6 * budget['impact_kinetic_energy_J']:.4g} uJ, "
                 f"closes to {worst:.1g} of it", fontsize=9)


def run_phases(summary, t0: float, t1: float) -> list:
    """The run's phases around its first contact (summary `contact`): [(name, start, end)] in s, approach up to the
    contact, the contact up to separation (or the end), the rebound after it; one phase for a run without contact."""
    contact = summary.get("contact") or {}
    tc, ts = contact.get("t_contact_s"), contact.get("t_separation_s")
    if tc is None or not t0 < tc < t1:
        return [("the whole run", t0, t1)]
    phases = [("approach", t0, tc)]
    if ts is None or ts >= t1:
        return phases + [("contact (to the end of the run)", tc, t1)]
    return phases + [("contact", tc, ts), ("rebound" if len(summary.get("bounces") or []) < 2 else "after the first separation", ts, t1)]


def phase_slice(t, t0: float, t1: float) -> slice:
    """The samples of t (sorted) in [t0, t1], with one neighbour on each side so that the phases join."""
    i = next((k for k, x in enumerate(t) if x >= t0), len(t))
    j = next((k for k, x in enumerate(t) if x > t1), len(t))
    return slice(max(i - 1, 0), min(j + 1, len(t)))


def draw_phase_row(fig, cells, t, series, phases, ylabel: str, right=None) -> list:
    """One linear panel per phase in `cells` (GridSpec cells): series [(values, style)], each panel over its own
    phase and y range; `right`: series drawn on a twin axis of their own (the contact force, 100 x larger)."""
    axes = []
    for k, (name, a, b) in enumerate(phases):
        ax = fig.add_subplot(cells[k])
        sl = phase_slice(t, a, b)
        tt = [1e3 * x for x in t[sl]]
        for values, style in series:
            ax.plot(tt, values[sl], **style)
        if right and any(abs(v) > 0.01 * max(map(abs, values)) for values, _ in right for v in values[sl]):  # its own axis
            tw = ax.twinx()
            for values, style in right:
                tw.plot(tt, values[sl], **style)
            tw.set_ylabel("contact force (N), right axis", fontsize=8)
            tw.tick_params(labelsize=8)
        elif right:  # no contact in the phase: the contact force is 0, drawn with the others
            for values, style in right:
                ax.plot(tt, values[sl], **style)
        ax.axhline(0, color="k", lw=0.5)
        ax.set_xlim(tt[0], tt[-1])
        n = max(1, math.ceil(-math.log10(max(1e3 * (b - a), 1e-9))) + 1)  # decimals that tell the ends apart
        ax.set_title(f"{name}: {1e3 * a:.{n}f}–{1e3 * b:.{n}f} ms", fontsize=9)
        ax.set_xlabel("t (ms)")
        ax.tick_params(labelsize=8)
        axes.append(ax)
    axes[0].set_ylabel(ylabel)
    return axes


def force_series(col, pair: bool, coupled: bool):
    """The force columns as (values, style): (fluid terms, the contact force)."""
    term_colour = {stem: f"C{i}" for i, stem in enumerate(FORCE_NAMES)}
    fluid, contact = [], []
    for k in col:
        if k.startswith("f_") and not k.startswith(("f_sim", "f_thr")):
            stem = k.rstrip("0123456789")
            style = dict(color=term_colour.get(stem), ls="--" if k.endswith("2") else "-", lw=1.2, label=force_label(k, pair))
            (contact if stem == "f_contact" else fluid).append((col[k], style))
    sim = []
    if coupled:
        for k, ls in (("f_sim1", "-"), ("f_thr1", "--"), ("f_sim2", "-"), ("f_thr2", "--")):
            if k in col:
                sim.append((col[k], dict(ls=ls, color="C0" if k.endswith("1") else "C3",
                                         label=force_label(k, pair) + (" (flow kernel)" if "sim" in k else " (analytic)"))))
    return fluid, contact, sim


def mark_events(axes, summary, col) -> None:
    """Contact and separation (and every later contact) as vertical lines; rebound apexes on the position panel."""
    contact = summary.get("contact") or {}
    for key, label, ls in (("t_contact_s", "contact (gap = δ_SS)", ":"), ("t_separation_s", "separation", "--")):
        if contact.get(key) is not None:
            for a in axes:
                a.axvline(1e3 * contact[key], color="grey", lw=0.8, ls=ls, label=label)
    bounces = summary.get("bounces") or []
    if len(bounces) < 2:
        return
    for b in bounces[1:]:
        for a in axes:
            a.axvline(1e3 * b["t_contact_s"], color="red", lw=0.6, ls=":", label="later contacts")
    tz = {round(t, 12): z for t, z in zip(col["t"], col["z1"])}
    apex = [b for b in bounces if b.get("t_separation_s") is not None and b.get("t_apex_s") is not None]
    ts = [1e3 * b["t_apex_s"] for b in apex]
    zs = [1e3 * tz.get(round(b["t_apex_s"], 12), float("nan")) for b in apex]
    axes[0].plot(ts, zs, "v", color="k", ms=6, label="apexes (largest gap before next contact)")
    for b, t, z in zip(apex, ts, zs):
        axes[0].annotate("%.2f mm" % (1e3 * b["apex_gap_m"]), (t, z), fontsize=7, xytext=(3, 5), textcoords="offset points")


def run_title(summary) -> str:
    """The scene, its bodies and liquid; impact speed, St, Re and e; the effects."""
    bodies, liquid = bodies_text(scene_bodies(summary.get("scene_file"))), liquid_text(summary.get("fluid"))
    if "μ" in liquid and not liquid.startswith("a liquid"):  # a named liquid: its values in brackets
        liquid = liquid.replace(", μ", " (μ", 1).replace(" kg/m³", " kg/m³)", 1)
    joined = bodies + (" in " if bodies and liquid and liquid != "no liquid" else ", " if bodies and liquid else "") + liquid
    head = summary["scene"] + (": " + joined if joined else "")
    bounces = summary.get("bounces") or []
    u = abs(bounces[0]["impact_velocity_m_s"]) if bounces and bounces[0].get("impact_velocity_m_s") is not None else None
    nums = [f"impact speed {u:.3g} m/s" if u is not None else None]
    st, st62 = summary.get("St"), summary.get("St_B_eq_6_2")
    if st is not None:
        nums.append(f"St_B = {st:.3g} (Table 6.1; eq. 6.2: {st62:.3g})" if st62 is not None else f"St = {st:.3g}")
    if summary.get("Re") is not None:
        nums.append(f"Re = {summary['Re']:.3g}")
    e = summary.get("e")
    nums.append(f"e = {e:.3f} ({summary.get('e_is')})" if e is not None else "no e")
    return head + "\n" + ", ".join(x for x in nums if x) + "; effects: " + ", ".join(EFFECT_WORDS.get(x, x) for x in summary["effects"])


def main() -> int:
    out = out_dir(__doc__)
    if out is None:
        return 2
    rows = read_rows(out / "trajectory.csv")
    summary = json.loads((out / "summary.json").read_text())
    col = {k: [float(r[k]) for r in rows] for k in rows[0]}
    coupled, pair = "H" in col, "z2" in col  # coupled: f_SIM against f_THR in a row of their own
    budget = bool(summary.get("energy_budget"))
    phases = run_phases(summary, col["t"][0], col["t"][-1])
    heights = [1, 1, 1.15] + [1.15] * coupled + [0.85] * budget
    fig = plt.figure(figsize=(13.5, 3.0 * sum(heights) + 0.6))
    gs = fig.add_gridspec(len(heights), len(phases), height_ratios=heights)
    ax_z, ax_u = fig.add_subplot(gs[0, :]), fig.add_subplot(gs[1, :])
    ax_u.sharex(ax_z)
    t_ms = [1e3 * x for x in col["t"]]
    for m, (kz, ku) in enumerate((("z1", "u1"), ("z2", "u2"))):
        if kz in col:
            style = dict(color="k", ls="--" if m else "-", label=f"sphere {m + 1}: position, velocity")
            ax_z.plot(t_ms, [1e3 * v for v in col[kz]], **style)
            ax_u.plot(t_ms, col[ku], **style)
    ax_z.set_ylabel("centre position z (mm)")
    ax_u.set_ylabel("velocity u (m/s)")
    ax_u.set_xlabel("t (ms)")
    fluid, contact, sim = force_series(col, pair, coupled)
    ax_f = draw_phase_row(fig, [gs[2, k] for k in range(len(phases))], col["t"], fluid, phases, "force on the sphere (N)" + (": fluid terms × H" if coupled else ""),
                          right=contact)
    ax_s = draw_phase_row(fig, [gs[3, k] for k in range(len(phases))], col["t"], sim, phases, "fluid force (N)") if coupled else []
    mark_events([ax_z, ax_u] + ax_f + ax_s, summary, col)
    draw_e_fits(ax_z, ax_u, summary)
    ax_e = fig.add_subplot(gs[-1, :]) if budget else None
    if budget:
        draw_energy_budget(ax_e, summary)
    for a in [ax_z, ax_u] + ax_f + ax_s + ([ax_e] if budget else []):
        a.grid(alpha=0.3)
    fig.suptitle(run_title(summary), fontsize=10)
    fig.tight_layout(rect=(0, 0, 0.78, 0.97))
    figure_legend(fig, fig.axes, bbox_to_anchor=(0.78, 0.93))  # every panel's labels once, in the panels' order
    save_png(fig, out / "trajectory.png", dpi=100)
    print(f"wrote {out / 'trajectory.png'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
