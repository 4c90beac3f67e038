// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Shipped nodes of the interpolation tables of contact/formulas.cpp: {f(x_i), x_i f'(x_i)} on
// x_i = x_min (x_max/x_min)^(i/(n−1)), and of the Hertz law's damping relation. Written by imcol_gen_tables (contact/gen_tables.cpp);
// tests/test_formulas.cpp checks them against the series.
namespace imcol::contact::table_data {

constexpr double brenner_min = 1e-5, brenner_max = 1e3;
constexpr int brenner_n = 641;
constexpr double w_min = 1e-6, w_max = 1e3;
constexpr int w_n = 721;
extern const double brenner_nodes[brenner_n][2];  // Brenner's λ(h/a), derivative by central differences
extern const double w_nodes[w_n][2];              // added-mass W(δ), dW/dδ from its series

// Tsuji et al.'s relation (contact/tsuji_impact.hpp): e(α_i) at α_i = tsuji_alpha_max · i/(tsuji_n − 1).
constexpr double tsuji_alpha_max = 20;
constexpr int tsuji_n = 1001;
extern const double tsuji_e_nodes[tsuji_n];

}  // namespace imcol::contact::table_data
