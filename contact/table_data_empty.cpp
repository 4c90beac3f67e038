// SPDX-License-Identifier: BSD-3-Clause
// Zero nodes for imcol_gen_tables itself (it computes the nodes from the series, never from these).
#include "contact/table_data.hpp"

namespace imcol::contact::table_data {
const double brenner_nodes[brenner_n][2] = {};
const double w_nodes[w_n][2] = {};
const double tsuji_e_nodes[tsuji_n] = {};
}  // namespace imcol::contact::table_data
