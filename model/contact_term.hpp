// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Solid contact f_SS (MODEL.md §2.4): the scene's contact law (contact/contact_law.hpp, from contact.law) pushes
// the pair apart, −f on sphere 1 and +f on sphere 2, N. The law is consulted once the first contact has begun;
// the model's events drive its state (begin_contact, unload, end_contact).
#include <memory>

#include "contact/contact_law.hpp"
#include "core/scene.hpp"
#include "model/force_term.hpp"
#include "model/pair.hpp"

namespace imcol::model {

class ContactTerm : public ForceTerm {
 public:
  ContactTerm(const Scene& sc, const PairGeometry& p);
  /// The law, for the model's events.
  contact::ContactLaw& law() { return *law_; }

  TermSlot properties() const override { return {ForceKind::contact, "f_contact"}; }
  void add(const TermInput& in, Evaluation& ev) const override;

 private:
  std::unique_ptr<contact::ContactLaw> law_;
  bool pair_ = false;
};

std::unique_ptr<ForceTerm> make_contact_term(const Scene& sc, const PairGeometry& p);

}  // namespace imcol::model
