// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Free-stream drag f_D on each sphere (MODEL.md §2.1): −6πμ a_m U_m φ(Re_m), Re_m = ρ_f 2a_m |U_m|/μ, with
// φ from drag.law (1 Stokes, 1 + 0.15 Re^0.687 Schiller–Naumann). N.
#include "core/scene.hpp"
#include "model/force_term.hpp"
#include "model/pair.hpp"

namespace imcol::model {

std::unique_ptr<ForceTerm> make_drag_term(const Scene& sc, const PairGeometry& p);

}  // namespace imcol::model
