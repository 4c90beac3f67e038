// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A force term of the reduced-order model (MODEL.md §2): one effect a scene can list. A term owns its parameters
// (derived from the Scene in its constructor, refusing bad input with InputError) and adds its force on each
// sphere into its own SphereForces slot and its mass into its own Evaluation slot (m_added, m_pair, m_hist).
// CollisionModel sums the slots in a fixed order, so the order of the terms does not change a result's bits.
// Its `model` block lines are fixed when it is built (choices_, set by its constructor).
// Adding a term: a class in its own file here, and one line in make_force_terms (model/force_terms.cpp).
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "model/evaluation.hpp"

namespace imcol::model {

using Choices = std::vector<std::pair<std::string, std::string>>;

/// What a term reads beyond the evaluation's kinematics.
struct TermInput {
  double t = 0;                  // s
  std::span<const double> y;     // the whole state (the history term reads its memory states)
  bool contact_begun = false;    // the first δ_SS crossing has happened (the contact law is consulted from then on)
  bool in_contact = false;       // between an inward δ_SS crossing and the outward one (loading, unloading)
};

class ForceTerm {
 public:
  virtual ~ForceTerm() = default;
  /// Adds this term's force (and mass) at the kinematics in ev.
  virtual void add(const TermInput& in, Evaluation& ev) const = 0;
  /// Its lines of summary.json's `model` block, name → value.
  const Choices& choices() const { return choices_; }

 protected:
  Choices choices_;
};

using ForceTerms = std::vector<std::unique_ptr<ForceTerm>>;

/// The term of type T among terms, or null.
template <class T>
T* find_term(const ForceTerms& terms) {
  for (const auto& t : terms)
    if (auto* p = dynamic_cast<T*>(t.get())) return p;
  return nullptr;
}

/// A number as the `model` block writes it (6 significant digits).
std::string choice_number(double v);

}  // namespace imcol::model
