// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Scene description (MODEL.md §1) and its TOML parser. All quantities SI unless noted.
#include <optional>
#include <string>
#include <vector>

#include "core/choices.hpp"
#include "core/flow_spec.hpp"

namespace imcol {

enum class Effect { drag, lubrication, added_mass, elastic, gravity, history, flow };
const char* to_string(Effect e);
std::optional<Effect> effect_from_string(const std::string& s);
/// Every effect's name, in the order of the enum.
std::vector<std::string> effect_names();

/// The effects a scene lists, as a bit set (the right-hand side asks for them on every evaluation);
/// iterated in the order of the enum.
class EffectSet {
  static constexpr int kCount = static_cast<int>(Effect::flow) + 1;
  static constexpr unsigned bit(Effect e) { return 1u << static_cast<unsigned>(e); }

 public:
  class iterator {
   public:
    iterator(unsigned bits, int i) : bits_(bits), i_(i) { skip(); }
    Effect operator*() const { return static_cast<Effect>(i_); }
    iterator& operator++() {
      ++i_;
      skip();
      return *this;
    }
    bool operator==(const iterator& o) const { return i_ == o.i_; }

   private:
    void skip() {
      while (i_ < kCount && !((bits_ >> i_) & 1u)) ++i_;
    }
    unsigned bits_;
    int i_;
  };
  void insert(Effect e) { bits_ |= bit(e); }
  void erase(Effect e) { bits_ &= ~bit(e); }
  bool contains(Effect e) const { return (bits_ & bit(e)) != 0; }
  iterator begin() const { return {bits_, 0}; }
  iterator end() const { return {bits_, kCount}; }
  bool operator==(const EffectSet&) const = default;

 private:
  unsigned bits_ = 0;
};

struct Solid {
  std::string material;          // name in data/materials.csv, or "" for inline properties
  double density = 0;            // kg/m^3 (unused for a wall)
  double youngs_modulus = 0;     // Pa
  double poisson_ratio = 0;      // -
  std::optional<double> e_dry;   // dry restitution of the material
  std::optional<double> roughness;  // m, the material's roughness height (data/materials.csv roughness_m)
};

struct SphereSpec : Solid {
  double diameter = 0;  // m
  double position = 0;  // z of the centre, m
  double velocity = 0;  // m/s along z (+ is toward the target)
};

struct WallSpec : Solid {
  double position = 0;  // z of the wall plane, m
};

struct FluidSpec {
  double density = 0;    // kg/m^3
  double viscosity = 0;  // Pa s
  std::string name;      // `fluid`: a liquid of data/fluids.csv; "" = inline values only
  std::optional<double> mass_fraction;  // glycerol mass fraction (glycerol-water), -
  std::optional<double> temperature;    // °C (a liquid whose properties are correlations)
  std::string density_source, viscosity_source;  // "scene" (inline) or the table's source
};

struct Scene {
  std::string path;  // file it came from
  std::string name;  // file stem unless `name` is given
  std::string description;

  std::optional<FluidSpec> fluid;    // none = dry collision
  std::vector<SphereSpec> spheres;   // impact sphere first, optional target second
  std::optional<WallSpec> wall;      // instead of a target sphere
  double gravity = -9.81;            // m/s^2 along z, used only with the `gravity` effect
  EffectSet effects;

  struct Drag { DragLaw law = DragLaw::stokes; } drag;                  // stokes | schiller-naumann
  struct Lubrication {
    LubricationModel model = LubricationModel::asymptotic;  // brenner (wall only) | asymptotic | seed; default: brenner for a wall
    double cutoff = 1e-4;     // smallest effective gap, units of D (impact sphere)
    double h_c = 1.0;         // asymptotic model acts for h < h_c, units of a*
    LubricationLimit limit = LubricationLimit::cutoff;  // cutoff | roughness (the solids touch at the roughness height)
    double roughness = -1;    // m, with limit = roughness: the gap where the surfaces touch; <0: the materials' roughness_m summed
  } lubrication;
  struct AddedMass {
    AddedMassModel model = AddedMassModel::lagrangian;  // lagrangian (pair kinetic energy; = seed for a wall and equal spheres) | seed (6.8, per sphere)
    double dw_floor = -1;        // units of a*; <0: delta_ss
  } added_mass;
  struct Contact {
    double delta_ss = 0;      // units of D; default 0.024 (sphere) / 0.017 (wall)
    double delta_sl = 0.1;    // units of D
    double e_dry = -1;        // <0: from the materials
    double beta = 0;          // F(x) steepness; 0 = energy-consistent (MODEL.md §2.4)
    ContactLawKind law = ContactLawKind::ramp;  // f_SS (contact/contact_law.hpp)
  } contact;
  struct History {
    KernelKind kernel = KernelKind::basset;  // basset | mei-adrian | kim | dorgan-loth (MODEL.md §2.3)
    HistoryEvaluator evaluator = HistoryEvaluator::soe_step;  // soe-step (sum of exponentials, modes advanced per step
                                                       // outside the integrator's state; default) | soe (modes as states) | direct
    double tolerance = 1e-6;           // soe: relative accuracy of the exponential fit of s^(-1/2)
    long modes = 0;                    // soe: > 0 fixes the number of exponentials instead of `tolerance`
    double min_lag = 0;                // s; shortest lag the exponentials resolve; 0 = automatic
    double horizon = 0;                // s; longest lag they resolve; 0 = solver.t_end
    HistoryStart start = HistoryStart::steady;  // steady (moving at U(0) for ever) | impulsive (started from rest at t = 0)
    HistoryReynolds reynolds = HistoryReynolds::instantaneous;  // Re of a finite-Re kernel: instantaneous |U| | initial |U(0)|
    WallCorrection wall_correction = WallCorrection::none;  // K_H: none (1) | added-mass (1 + 3W(δ**), choice)
    double direct_step = 0;            // s; the direct evaluator's fixed step; 0 = automatic
    bool interpolate_outputs = true;   // soe-step, Basset: outputs inside a step from its interpolant where accurate
  } history;
  struct Solver {
    IntegratorMethod integrator = IntegratorMethod::cvode;  // cvode | ida
    LinearSolverChoice linear_solver = LinearSolverChoice::automatic;  // auto | dense | schur | gmres (the last two: cvode)
    double krylov_tol = 0.05;          // gmres: linear tolerance relative to the Newton tolerance (CVodeSetEpsLin)
    double rtol = 1e-8;
    double atol = 1e-10;      // dimensionless; scaled per component (see integrators/)
    double t_end = 1.0;       // s
    double max_step = 0;      // s; 0 = automatic (a fraction of the contact-zone crossing time)
    long max_steps = 100000;  // internal steps between two outputs or events
    double step_budget = 1e7;  // a run whose step cap forces more than this many steps up to t_end is refused
  } solver;
  struct Measure {
    double window = 0.010;    // s: fit_time's lines before and after contact, St and the impact velocities, and how
                              // long a `first` run goes on after the separation (not the default e)
    double instant_gap = -1;  // units of D, gap at which e_instant is taken; <0: delta_ss (set by the reader)
    double stall_fraction = 0.01;  // an approach without contact has stopped when U_rel < this × U_rel(0)
    BouncesMode bounces = BouncesMode::first;  // first (stop after the first rebound is measured) | all (follow every contact)
    double fit_distance = 0.1;  // units of D: e_measures.fit_distance fits z over this distance beyond delta_ss
    double at_gap = 0.1;        // units of D: e_measures.at_gap takes the velocities at this gap
    // The named measure reported as `e` (docs/bounces.md). Without the key, the experiments' procedure for the scene's
    // kind: joseph_2001 (the camera's lines over 0.1 D) for a sphere and a wall, yang_hunt_2006 (the seed's eq. 6.1,
    // lines over 10 ms) for a pair.
    EMeasure e = EMeasure::joseph_2001;
    bool e_given = false;  // measure.e was in the scene (or an override)
    double ends_distance = 0.02;  // units of D: contact_ends fits over the time to travel this at the impact speed
    double ends_speed_change = 0.25;  // contact_ends windows end before U_rel has changed by more than this fraction
    double ends_tolerance = 0.02;     // warn where contact_ends' end slopes differ from U_rel at δ_SS by more (× impact speed)
    int samples_per_window = 32;  // the measures' own sampling: at least this many samples per contact_ends window
    double disagreement = 0.05;   // warn where a named measure's e differs from `e` by more than this
    double max_samples = 1e7;     // refuse a run whose measures would sample it more often than this up to t_end
    bool energy_budget = true;    // carry the work of each force beside the solver (summary `energy_budget`)
  } measure;
  struct Output { double dt = 0; } output;  // s, trajectory rows; 0 = measure.window/100 (set by the reader)
  FlowSpec flow;  // the embedded flow kernel, used with the `flow` effect

  bool has(Effect e) const { return effects.contains(e); }
  bool two_spheres() const { return spheres.size() == 2; }
  bool has_target() const { return two_spheres() || wall.has_value(); }
};

/// One command-line override "dotted.key=value" (value in TOML syntax; bare words are strings).
struct Override {
  std::string key;
  std::string value;
};
Override parse_override(const std::string& text);  // throws InputError
/// A dotted key's path as overrides apply it: "a.b[1].c" and "a.b.1.c" are a, b, 1, c.
std::vector<std::string> key_path(const std::string& key);

/// Parses, applies overrides, validates. Throws InputError naming the file, line and key.
Scene load_scene(const std::string& path, const std::vector<Override>& overrides = {});
Scene parse_scene(const std::string& toml_text, const std::string& path,
                  const std::vector<Override>& overrides = {});

}  // namespace imcol
