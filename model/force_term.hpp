// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A force term of the reduced-order model (MODEL.md §2): one effect a scene can list. A term owns its parameters
// (derived from the Scene in its constructor, refusing bad input with InputError), its force slot (an index into
// each sphere's SphereForces::term, given in registration order), its line of the energy budget, its trajectory
// column and, if it has any, its states (after the core states) with their part of the DynamicalSystem.
// CollisionModel sums the slots in registration order (model/force_terms.cpp), so that order is the summation order.
// Its `model` block lines are fixed when it is built (choices_, set by its constructor).
// Adding a term: a class in its own file here, and one line in make_force_terms (model/force_terms.cpp).
#include <array>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/system.hpp"
#include "model/evaluation.hpp"
#include "model/force_work.hpp"

namespace imcol::model {

using Choices = std::vector<std::pair<std::string, std::string>>;

/// What a term reads beyond the evaluation's kinematics.
struct TermInput {
  double t = 0;                  // s
  std::span<const double> y;     // the whole state (a term with states reads its own slice)
  bool contact_begun = false;    // the first δ_SS crossing has happened (the contact law is consulted from then on)
  bool in_contact = false;       // between an inward δ_SS crossing and the outward one (loading, unloading)
};

/// How a term's share of the velocity mass matrix (SphereForces::mass) is treated.
enum class TermMass {
  none,      // it has none
  implicit,  // kept in the mass matrix in full, with the flow blend too (the added mass, standing for f_SIM's as well)
  blended,   // weighted by H like its force under the flow blend (the history force's κ-like mass)
};

/// What a term's force slot is: its properties, read by the model, the flow blend, the recorder and the budget.
struct TermSlot {
  ForceKind kind;        // its line of the energy budget (model/force_work.hpp); its name is to_string(kind)
  const char* column;    // its trajectory column per sphere, e.g. "f_drag" (f_drag1, f_drag2)
  bool fluid = false;    // a part of f_THR: the flow blend weights it by H (MODEL.md (6.10))
  TermMass mass = TermMass::none;
};

class ForceTerm {
 public:
  virtual ~ForceTerm() = default;
  /// Adds this term's force (and mass) at the kinematics in ev into its slot (f[m].term[slot()], f[m].mass[slot()]).
  virtual void add(const TermInput& in, Evaluation& ev) const = 0;
  virtual TermSlot properties() const = 0;
  /// Its lines of summary.json's `model` block, name → value.
  const Choices& choices() const { return choices_; }
  /// Its index in SphereForces::term, set by the model in registration order.
  std::size_t slot() const { return slot_; }
  void set_slot(std::size_t s) { slot_ = s; }

  // ---- its states (none by default): their place in y is [first, first + states()) ----
  virtual std::size_t states() const { return 0; }
  virtual void place_states(std::size_t first) { (void)first; }
  virtual void append_names(std::vector<std::string>& names) const { (void)names; }
  /// u_floor: the speed below which a velocity error is noise, m/s.
  virtual void append_tolerances(double u_floor, std::vector<double>& t) const { (void)u_floor, (void)t; }
  /// Its initial states in y; it may correct the core states (evaluate_start: the model at the start).
  virtual void initial_states(std::span<double> y, const std::function<Evaluation()>& evaluate_start) const {
    (void)y, (void)evaluate_start;
  }
  /// Its rows of dy/dt, given the spheres' accelerations.
  virtual void state_rhs(const std::array<double, 2>& acc, std::span<const double> y, std::span<double> ydot) const {
    (void)acc, (void)y, (void)ydot;
  }
  /// Its rows of the implicit form F(t, y, y') = 0 (IDA).
  virtual void residual(std::span<const double> y, std::span<const double> yp, std::span<double> r) const { (void)y, (void)yp, (void)r; }
  /// The modal structure of its states (core: the count of core states); false if it has none.
  virtual bool modal_structure(const Evaluation& ev, std::size_t core, ModalStructure& s) const { (void)ev, (void)core, (void)s; return false; }

  // ---- its hooks on the integration ----
  /// A cap on the solver's step, s (infinity: none).
  virtual double step_cap() const { return std::numeric_limits<double>::infinity(); }
  virtual double next_breakpoint() const { return std::numeric_limits<double>::infinity(); }
  virtual void at_breakpoint(double t, const Evaluation& ev) { (void)t, (void)ev; }
  /// After each accepted step (restart: the first after a re-initialisation).
  virtual void at_step(double t, const Evaluation& ev, bool restart) { (void)t, (void)ev, (void)restart; }
  /// A step to (t, ev) is accepted; the outputs inside it follow (rows, the energy quadrature), then at_step.
  virtual void step_accepted(double t, const Evaluation& ev) { (void)t, (void)ev; }

 protected:
  Choices choices_;

 private:
  std::size_t slot_ = 0;
};

using ForceTerms = std::vector<std::unique_ptr<ForceTerm>>;

/// The term of type T among terms, or null.
template <class T>
T* find_term(const ForceTerms& terms) {
  for (const auto& t : terms)
    if (auto* p = dynamic_cast<T*>(t.get())) return p;
  return nullptr;
}

/// The slot of each kind of force among terms (model/force_work.hpp).
KindSlots kind_slots(const ForceTerms& terms);

/// A number as the `model` block writes it (6 significant digits).
std::string choice_number(double v);

}  // namespace imcol::model
