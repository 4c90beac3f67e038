// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A 1-D replay of LIGGGHTS-PUBLIC's `hooke` normal contact (src/normal_model_hooke.h; the SI unit style,
// nktv2p = 1) for a head-on impact: a re-implementation of its normal force from the source, not LIGGGHTS.
//   Y*  = 1 / ((1 − ν_i²)/E_i + (1 − ν_j²)/E_j)                                   Pa  (global_properties.cpp, Yeff; contact::effective_modulus)
//   k_n = 16/15 √r* Y* (15 m* V_c² / (16 √r* Y*))^(1/5)                            N/m (V_c: characteristicVelocity)
//   γ_n = √(4 m* k_n L² / (L² + π²))                                               kg/s
//   F_n = k_n δ_n − γ_n v_n                                                        N, along e_n (repulsive > 0)
// with v_n = (v_i − v_j)·e_n, e_n from j to i: v_n < 0 while the surfaces approach, > 0 on the rebound.
// L = ln e for a constant restitution e (`viscous off`: coefficientRestitution). With `viscous on`, at every step
//   St = m* v_n / (6 π μ r*²)   (signed, as v_n),   L = ln(MaximumRestitution) + CriticalStokes / St
// so on the approach L = ln e_max − St_c/|St| and on the rebound L = ln e_max + St_c/|St|: L turns positive there
// for |St| < St_c / (−ln e_max). γ_n depends on L² only and stays ≥ 0: −γ_n v_n opposes the motion throughout.
// Where L² overflows (v_n → 0) the source's expression is inf/inf, NaN; the replay takes its limit γ_n = 2√(m* k_n).
// limitForce (off by default) sets a negative (attractive) F_n to 0.
// Time stepping as LIGGGHTS's fix nve/sphere (velocity Verlet): v += ½Δt F/m*, δ += −v Δt, F = F_n(δ, v) at the
// half-step v, v += ½Δt F/m*. The replay starts at first touch (δ = 0, v_n = −U, F = 0) and ends at the first step
// with δ ≤ 0 (no force after it): e = v_n / U there.
#include <functional>
#include <optional>

namespace imcol::study {

/// The contact as LIGGGHTS's hooke model reads it (SI).
struct HookeContact {
  double m_eff = 0;     // kg: m_i m_j / (m_i + m_j), a wall: m_i
  double r_eff = 0;     // m: r_i r_j / (r_i + r_j), a wall: r_i
  double Y_eff = 0;     // Pa
  double char_vel = 0;  // m/s, characteristicVelocity
};

/// k_n (N/m).
double hooke_k_n(const HookeContact& c);
/// γ_n for L = ln e (kg/s); the limit 2√(m* k_n) where L² is not finite.
double hooke_gamma_n(double m_eff, double k_n, double L);
/// The undamped half period π √(m*/k_n) (s).
double hooke_contact_time(const HookeContact& c);

/// `viscous on`: FluidViscosity (Pa s), CriticalStokes, MaximumRestitution (per type pair).
struct ViscousRule {
  double fluid_viscosity = 0;
  double critical_stokes = 0;
  double maximum_restitution = 1;
};

/// St = m* v_n / (6 π μ r*²), signed as v_n.
double viscous_stokes(const HookeContact& c, double mu, double vn);
/// L = ln e_max + St_c / St(v_n) (±inf at v_n = 0).
double viscous_log_e(const HookeContact& c, const ViscousRule& rule, double vn);
/// The impact speed U (m/s) at which St = m* U / (6 π μ r*²) takes the value `St`.
double impact_speed_for_stokes(const HookeContact& c, double mu, double St);

enum class ForceLimit { off, on };  // LIGGGHTS's limitForce

struct ReplayStep {
  int steps_per_contact = 1000;  // Δt = hooke_contact_time / this, unless dt is given
  std::optional<double> dt;      // s
  ForceLimit limit = ForceLimit::off;
  double max_contact_times = 60;  // a contact still on after this many contact times: no rebound (e = 0)
};

struct ReplayResult {
  double e = 0;            // rebound speed / impact speed at separation; 0 without separation
  bool separated = false;
  long steps = 0;          // steps in contact
  double dt = 0;           // s
  double duration = 0;     // s, steps × dt
};

/// The damping coefficient's L as a function of v_n (the rule).
using LogRestitution = std::function<double(double vn)>;

/// Replays an impact at speed U (> 0) with L(v_n) evaluated at every step.
ReplayResult replay_hooke(const HookeContact& c, const LogRestitution& L, double U, const ReplayStep& step = {});
/// `viscous on`: L from the viscous rule at every step.
ReplayResult replay_viscous(const HookeContact& c, const ViscousRule& rule, double U, const ReplayStep& step = {});
/// A constant e for the whole contact (e = 0: critical damping).
ReplayResult replay_constant_e(const HookeContact& c, double e, double U, const ReplayStep& step = {});

}  // namespace imcol::study
