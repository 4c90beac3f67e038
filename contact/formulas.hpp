// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Analytic force laws of the reduced-order collision model (MODEL.md §2). SI units throughout.
#include <array>
#include <functional>
#include <string>

#include "core/choices.hpp"

namespace imcol::contact {

constexpr double pi = 3.141592653589793238462643383279502884;
constexpr double zeta3_minus_1 = 0.2020569031595942854;  // W(0) = ζ(3) − 1

// ---------- Pair geometry (MODEL.md §1) ----------
double reduced(double x1, double x2);  // (1/x1 + 1/x2)^-1; x2 = +inf gives x1
/// 1/E* = (1−ν1²)/E1 + (1−ν2²)/E2  [Pa]
double effective_modulus(double E1, double nu1, double E2, double nu2);

// ---------- Hertz contact (seed eq. 6.12, 6.13; MODEL.md §2.4) ----------
/// W(ε) = (4/3) E* √a* ε^{3/2}  [N], ε indentation [m]
double hertz_force(double E_star, double a_star, double eps);
/// ε_max = (15 m* U² / (16 E* √a*))^{2/5}  [m]: peak indentation of a dry impact at speed U
double hertz_max_indentation(double m_star, double U, double E_star, double a_star);
/// W_o = W(ε_max)  [N]
double hertz_peak_force(double m_star, double U, double E_star, double a_star);
/// Contact duration t_c ≈ 2.94 ε_max / U  [s] (Hertz impact, coefficient 2.943)
double hertz_contact_time(double m_star, double U, double E_star, double a_star);

// ---------- Elastic-like ramp F(x), x = δ/δ_SS (MODEL.md §2.4, choice) ----------
/// F(x) = (e^{β(1−x)} − 1)/(e^β − 1) on [0, 1], 0 for x ≥ 1, linear C¹ continuation for x < 0.
double ramp_F(double x, double beta);
/// ∫_0^1 F dx = 1/β − 1/(e^β − 1)
double ramp_F_integral(double beta);
/// β such that δ_SS ∫_0^1 F dx = (2/5) ε_max, i.e. the ramp stores the Hertz energy ½ m* U².
double energy_consistent_beta(double delta_ss, double eps_max);

// ---------- Blend H(x), x = δ/δ_SL (MODEL.md §2.5, choice: smoothstep on [0, 2]) ----------
double blend_H(double x);

// ---------- Drag (MODEL.md §2.1) ----------
/// φ(Re): 1 (Stokes) or 1 + 0.15 Re^0.687 (Schiller–Naumann); drag = −6πμ a U φ
double drag_factor(DragLaw law, double Re);
/// Terminal speed U (m/s) of a sphere of diameter D (m) and density rho_p in a liquid (rho_f, mu) under |g| (m/s²):
/// |ρ_p − ρ_f| g πD³/6 = 3πμ D U φ(Re), Re = ρ_f U D/μ, with the drag factor φ ≥ 1 given (drag_factor, or
/// C_D Re/24 of a drag curve); bisection in ln U. 0 when ρ_p = ρ_f.
double terminal_speed(double D, double rho_p, double rho_f, double mu, double g, const std::function<double(double)>& phi);

// ---------- Lubrication (MODEL.md §2.1) ----------
/// Brenner (1961) exact series λ(h/a) for a sphere approaching a plane wall; direct summation.
double brenner_lambda_series(double h_over_a);
/// Same, fast: tabulated for 1e-5 ≤ h/a ≤ 1e3, series above, Cox–Brenner asymptote
/// 1/δ + (1/5) ln(1/δ) + const below (constant matched to the series).
double brenner_lambda(double h_over_a);
/// c_log = a1 a2 (a1² + 7 a1 a2 + a2²) / (5 (a1 + a2)³) [m]; a2 = +inf gives a1/5 (Jeffrey & Onishi 1984)
double lubrication_log_coefficient(double a1, double a2);
/// Gap resistance length R(h) [m]: the gap force on sphere 1 is −6πμ R(h) U_rel.
/// asymptotic: a*²/h + c_log ln(a*/h), shifted to vanish at h_c, zero for h ≥ h_c.
double asymptotic_resistance(double h, double a_star, double c_log, double h_c);
/// Smooth lower bound on the gap used by the lubrication law: ½(h + √(h² + 4 h_min²)) ≥ 0.
double regularised_gap(double h, double h_min);

/// The pair's geometry as the gap laws see it: radii a1, a2 (a2 = +inf for a wall), a* and c_log [m], h_c [m].
struct GapGeometry {
  double a1 = 0, a2 = 0, a_star = 0, c_log = 0, h_c = 0;
};
/// Gap (lubrication) resistance lengths [m] of each sphere for the relative velocity U_rel = U1 − U2:
/// the gap force on sphere 1 is −6πμ R1 U_rel, on sphere 2 +6πμ R2 U_rel (MODEL.md §2.1), at the gap h [m] (> 0).
///   brenner     (wall) R1 = a1 (λ(h/a1) − 1), Brenner (1961): exact for a sphere and a plane.
///   asymptotic  R1 = R2 = a*²/h + c_log ln(a*/h) shifted to vanish at h_c (Jeffrey & Onishi 1984): the two leading
///               small-gap terms, exact as h → 0, equal and opposite; its a2 → ∞ limit is Cox & Brenner's (1967) wall law.
///   seed        R_m = a_m (λ(h/a*) − 1): our reading of the seed's (6.7), which our copy lacks, from its (6.8), (6.9)
///               and "λ(δ**, Re*_h) in the same manner as (4.3)": Yang's wall law with δ* = h/a replaced by δ** = h/a*,
///               times 6πμ a_m of each sphere. Our choices: λ multiplies U_rel (free-stream drag stays on U_m), the +
///               sign on sphere 2, no Re_h. For a wall it is `brenner`; for an equal pair twice `asymptotic`
///               (R → 2 a*²/h); for unequal spheres R2/R1 = a2/a1, so the pair's momentum is not conserved.
struct GapResistance {
  double on1 = 0, on2 = 0;  // m
};
GapResistance gap_resistance(LubricationModel model, const GapGeometry& g, double h);

// ---------- Added mass (seed eq. 6.8; MODEL.md §2.2) ----------
/// W(δ) = Σ_{n≥2} (sinh α / sinh nα)³, cosh α = 1 + δ; direct summation.
double added_mass_W_series(double delta);
double added_mass_dW_series(double delta);  // dW/dδ, direct summation
/// Fast versions (tabulated for 1e-6 ≤ δ ≤ 1e3, far-field series above, linear to W(0) below).
double added_mass_W(double delta);
double added_mass_dW(double delta);

/// Node i of the shipped interpolation tables, {f, x df/dx}, recomputed from the series (generator and test).
enum class TableKind { brenner_lambda, added_mass_W };
std::array<double, 2> table_node(TableKind kind, int i);

}  // namespace imcol::contact
