// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The force terms a scene calls for (MODEL.md §2), one line each in make_force_terms.
#include "core/scene.hpp"
#include "model/force_term.hpp"
#include "model/pair.hpp"

namespace imcol::model {

/// The terms of the effects the scene lists, placed (place_terms) in registration order: drag, lubrication,
/// added mass, contact, gravity, history. That order is the forces' summation order and their `model` block lines'.
ForceTerms make_force_terms(const Scene& sc, const PairGeometry& p);

/// Gives each term its slot (its index) and its states' place, after the core states and those of the terms before it.
void place_terms(ForceTerms& terms, std::size_t core);

}  // namespace imcol::model
