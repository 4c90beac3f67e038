// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Gravity and buoyancy on each sphere (MODEL.md §2, seed (6.4)): (m_p,m − m_f,m) g, N along z.
#include "core/scene.hpp"
#include "model/force_term.hpp"
#include "model/pair.hpp"

namespace imcol::model {

std::unique_ptr<ForceTerm> make_gravity_term(const Scene& sc, const PairGeometry& p);

}  // namespace imcol::model
