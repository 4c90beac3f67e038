// SPDX-License-Identifier: BSD-3-Clause
#include "contact/contact_law.hpp"

#include "contact/hertz_law.hpp"
#include "contact/ramp_law.hpp"

namespace imcol::contact {

std::unique_ptr<ContactLaw> make_contact_law(ContactLawKind kind, const ContactPair& pair) {
  switch (kind) {
    case ContactLawKind::ramp: return std::make_unique<RampLaw>(pair);
    case ContactLawKind::hertz: return std::make_unique<HertzLaw>(pair);
  }
  return nullptr;
}

}  // namespace imcol::contact
