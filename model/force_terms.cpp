// SPDX-License-Identifier: BSD-3-Clause
#include "model/force_terms.hpp"

#include <sstream>

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

ForceTerms make_force_terms(const Scene& sc, const PairGeometry& p) {
  ForceTerms t;
  if (sc.has(Effect::drag)) t.push_back(make_drag_term(sc, p));
  if (sc.has(Effect::gravity)) t.push_back(make_gravity_term(sc, p));
  if (sc.has(Effect::lubrication)) t.push_back(make_gap_resistance_term(sc, p));
  if (sc.has(Effect::added_mass)) t.push_back(make_added_mass_term(sc, p));
  if (sc.has(Effect::elastic)) t.push_back(make_contact_term(sc, p));
  if (sc.has(Effect::history)) t.push_back(make_history_term(sc, p));
  return t;
}

}  // namespace imcol::model
