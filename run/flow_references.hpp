// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Analytic references for the flow kernel's forces on spheres on prescribed paths (`imcol flow`): SI units, forces
// in N along +z on each sphere.
#include <utility>
#include <vector>

#include "model/collision_model.hpp"
#include "core/scene.hpp"
#include "flow/flow_scene.hpp"

namespace imcol {

/// An impulsively started sphere (Stokes + Basset, t > 0): F = 6πμaU (1 + a/√(πνt)).
double impulsive_start_force(double mu, double nu, double a, double U, double t);

/// A sphere oscillating in fluid at rest, z = A (1 − cos ωt), U = Aω sin ωt (Stokes 1851; Landau & Lifshitz §24;
/// a ≪ δ not required, A ≪ a): F = −6πμa(1 + a/δ)U − 3πa²√(2μρ/ω)(1 + 2a/(9δ)) dU/dt, δ = √(2ν/ω).
class OscillatingSphereForce {
 public:
  OscillatingSphereForce(double mu, double rho, double a, double amplitude, double frequency);
  double delta() const { return delta_; }  // Stokes layer thickness, m
  double at(double t) const;               // N

 private:
  double mu_, rho_, a_, amplitude_, omega_, delta_;
};

/// One sphere and a wall at z = wall_z: Brenner's (1961) quasi-steady Stokes force −λ(h/a) 6πμaU (no inertia, no
/// history), h the surface gap.
double brenner_wall_force(double mu, const flow::SphereState& b, double wall_z);

/// The collision scene whose model gives f_THR for a flow scene's two spheres: its fluid and spheres (density 2ρ_f,
/// elastic properties that do not enter f_THR), effects drag (Schiller–Naumann), lubrication (the pair default,
/// asymptotic), added mass and elastic, every other setting at parse_scene's default for a pair.
Scene pair_force_scene(const flow::FlowScene& sc);

/// f_THR of two spheres on the scene's prescribed paths, from the collision model's own code
/// (CollisionModel::analytic_fluid_force): Schiller–Naumann drag, the asymptotic gap lubrication (the pair default,
/// not the seed's gap law; docs/model-notes.md, "Pairs"), the added mass's velocity part (accelerations taken as
/// zero: the paths are at constant velocity). History forces are left out (they decay after the impulsive start).
class AnalyticPairForce {
 public:
  explicit AnalyticPairForce(const flow::FlowScene& sc) : model_(pair_force_scene(sc)) {}
  std::pair<double, double> at(const std::vector<flow::SphereState>& s) const;

 private:
  model::CollisionModel model_;
};

}  // namespace imcol
