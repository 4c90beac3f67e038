// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The force terms a scene calls for (MODEL.md §2), one line each in make_force_terms.
#include "core/scene.hpp"
#include "model/force_term.hpp"
#include "model/pair.hpp"

namespace imcol::model {

/// The terms of the effects the scene lists, in the order of their `model` block lines.
ForceTerms make_force_terms(const Scene& sc, const PairGeometry& p);

}  // namespace imcol::model
