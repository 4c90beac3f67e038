// SPDX-License-Identifier: BSD-3-Clause
#include "model/force_terms.hpp"

#include <sstream>
#include <stdexcept>

#include "model/added_mass_term.hpp"
#include "model/contact_term.hpp"
#include "model/drag_term.hpp"
#include "model/gap_resistance_term.hpp"
#include "model/gravity_term.hpp"
#include "model/history_term.hpp"

namespace imcol::model {

std::string choice_number(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

KindSlots kind_slots(const ForceTerms& terms) {
  KindSlots s;
  for (const auto& t : terms) s[static_cast<std::size_t>(t->properties().kind)].push_back(t->slot());
  return s;
}

ForceTerms make_force_terms(const Scene& sc, const PairGeometry& p) {
  ForceTerms t;
  // The registration order is the summation order of the forces and of the mass matrix's diagonal.
  if (sc.has(Effect::drag)) t.push_back(make_drag_term(sc, p));
  if (sc.has(Effect::lubrication)) t.push_back(make_gap_resistance_term(sc, p));
  if (sc.has(Effect::added_mass)) t.push_back(make_added_mass_term(sc, p));
  if (sc.has(Effect::elastic)) t.push_back(make_contact_term(sc, p));
  if (sc.has(Effect::gravity)) t.push_back(make_gravity_term(sc, p));
  if (sc.has(Effect::history)) t.push_back(make_history_term(sc, p));
  place_terms(t, 2 * p.n_spheres);
  return t;
}

void place_terms(ForceTerms& terms, std::size_t core) {
  if (terms.size() > kMaxTerms) throw std::logic_error("more force terms than SphereForces has slots");
  std::size_t first = core;
  for (std::size_t i = 0; i < terms.size(); ++i) {
    terms[i]->set_slot(i);
    terms[i]->place_states(first);
    first += terms[i]->states();
  }
}

}  // namespace imcol::model
