#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Plot one imcol run: positions, velocities and force terms against time, and the first collision's energy budget.

Usage: /usr/bin/python3 scripts/plot_run.py OUT_DIR   (writes OUT_DIR/trajectory.png)
Needs Debian's python3-matplotlib (importable from /usr/bin/python3 only).
"""
import json
import sys

from imcol_plot import FORCE_NAMES, force_label, out_dir, plt, read_rows, save_png


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


# One function (85 lines): the panels of trajectory.png share the figure, its time axis and the summary read once.
def main() -> int:
    out = out_dir(__doc__)
    if out is None:
        return 2
    rows = read_rows(out / "trajectory.csv")
    summary = json.loads((out / "summary.json").read_text())
    col = {k: [float(r[k]) for r in rows] for k in rows[0]}
    t_ms = [1e3 * x for x in col["t"]]

    coupled = "H" in col  # the flow effect: f_SIM against f_THR and the blend in a panel of their own
    pair = "z2" in col
    n_time = 4 if coupled else 3
    budget = bool(summary.get("energy_budget"))  # a panel of its own below the time axis (none for a free sphere)
    fig, ax_all = plt.subplots(n_time + budget, 1, figsize=(10.5, 3.25 * n_time + 3.25 * budget),
                               gridspec_kw={"height_ratios": [1] * n_time + [0.8] * budget})
    ax, ax_energy = list(ax_all[:n_time]), (ax_all[n_time] if budget else None)
    for a in ax[1:]:
        a.sharex(ax[0])
    for a in ax[:-1]:
        a.tick_params(labelbottom=False)
    # One colour per force term, the same for both spheres (sphere 2 dashed); one colour per sphere for z and u.
    term_colour = {stem: f"C{i}" for i, stem in enumerate(FORCE_NAMES)}
    term_colour.update({"f_sim": "C0", "f_thr": "C1"})
    for m, k in enumerate(("z1", "z2")):
        if k in col:
            ax[0].plot(t_ms, [1e3 * v for v in col[k]], color=f"C{m}", label=f"sphere {m + 1}")
    ax[0].set_ylabel("centre position z (mm)")
    for m, k in enumerate(("u1", "u2")):
        if k in col:
            ax[1].plot(t_ms, col[k], color=f"C{m}", label=f"sphere {m + 1}")
    ax[1].set_ylabel("velocity u (m/s)")
    for k in col:
        if k.startswith("f_") and not k.startswith(("f_sim", "f_thr")):
            stem = k.rstrip("0123456789")
            ax[2].plot(t_ms, col[k], color=term_colour.get(stem), ls="--" if k.endswith("2") else "-", label=force_label(k, pair))
    ax[2].set_yscale("symlog", linthresh=1e-4)
    ax[2].set_ylabel("force acting (N)" + (": fluid terms x H" if coupled else ""))
    if coupled:
        for k, ls in (("f_sim1", "-"), ("f_thr1", "--"), ("f_sim2", "-"), ("f_thr2", "--")):
            if k in col:
                colour = "C0" if k.endswith("1") else "C3"
                ax[3].plot(t_ms, col[k], ls=ls, color=colour, label=force_label(k, pair) + (" (flow kernel)" if "sim" in k else " (analytic)"))
        ax[3].set_yscale("symlog", linthresh=1e-4)
        ax[3].set_ylabel("fluid force (N)")
        h = ax[3].twinx()
        h.plot(t_ms, col["H"], color="k", lw=0.8, label="H (weight of f_THR)")
        h.set_ylim(-0.05, 1.05)
        h.set_ylabel("H")
        h.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.09, 0.3))
    ax[-1].set_xlabel("t (ms)")
    contact = summary.get("contact") or {}
    marks = (("t_contact_s", "contact (gap = delta_SS)", ":"), ("t_separation_s", "separation", "--"))
    for key, label, ls in marks:
        if contact.get(key) is not None:
            for a in ax:
                a.axvline(1e3 * contact[key], color="grey", lw=0.8, ls=ls, label=label)
    # Every contact (summary `bounces`): contacts as vertical lines, apexes as markers on the position.
    bounces = summary.get("bounces") or []
    if len(bounces) > 1:
        for i, b in enumerate(bounces):
            for a in ax:
                a.axvline(1e3 * b["t_contact_s"], color="red", lw=0.6, ls=":", label="contacts" if i == 0 and a is ax[0] else None)
        tz = {round(t, 12): z for t, z in zip(col["t"], col["z1"])}
        bounces = [b for b in bounces if b.get("t_separation_s") is not None]  # apexes of the rebounds
        ax_t = [1e3 * b["t_apex_s"] for b in bounces if b.get("t_apex_s") is not None]
        ax_z = [1e3 * tz.get(round(b["t_apex_s"], 12), float("nan")) for b in bounces if b.get("t_apex_s") is not None]
        ax[0].plot(ax_t, ax_z, "v", color="k", ms=6, label="apexes (largest gap before the next contact)")
        for b, t, z in zip(bounces, ax_t, ax_z):
            ax[0].annotate("%.2f mm" % (1e3 * b["apex_gap_m"]), (t, z), fontsize=7, xytext=(3, 5), textcoords="offset points")
    draw_e_fits(ax[0], ax[1], summary)
    if budget:
        draw_energy_budget(ax_energy, summary)
    for a in ax + ([ax_energy] if budget else []):  # beside the panel (and the H axis), so that no legend hides a curve
        a.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.09 if coupled else 1.01, 1.0))
        a.grid(alpha=0.3)
    e = summary.get("e")
    st = summary.get("St")
    title = f"{summary['scene']}: e = {e:.3f} ({summary.get('e_is')})" if e is not None else summary["scene"]
    if st is not None:
        st62 = summary.get("St_B_eq_6_2")
        title += f", St_B = {st:.1f} (Table 6.1; eq. 6.2: {st62:.1f})" if st62 is not None else f", St = {st:.1f}"
    ax[0].set_title(title + "\neffects: " + ", ".join(summary["effects"]), fontsize=10)
    fig.tight_layout()
    save_png(fig, out / "trajectory.png", dpi=100)
    print(f"wrote {out / 'trajectory.png'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
