// SPDX-License-Identifier: BSD-3-Clause
// The seed validation's inputs (study/validate.hpp): Table 6.1 read and checked, the models, the options.
#include "study/validate.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/errors.hpp"
#include "core/materials.hpp"

namespace imcol::study {

namespace validate_impl {  // this file's helpers: named, as study/ is built in unity batches

/// The models, by the gap law of the pair (docs/model-notes.md, "Pairs").
const std::vector<ValidateModel> kValidateModels = {{"seed", LubricationModel::seed}, {"asymptotic", LubricationModel::asymptotic}};

/// The reference table's columns, in order.
constexpr const char* kColumns = "run,mu_cP,rho_l_g_cm3,rho_p_star_g_cm3,V_Io_cm_s,Re_Io,St_B,e,pair";
std::string column_name(int k) {
  std::stringstream ss(kColumns);
  std::string name;
  for (int i = 0; i <= k; ++i) std::getline(ss, name, ',');
  return name;
}

/// Every numeric cell must be a finite number (the run number a positive integer naming data/scenes/seed_run<run>.toml).
double seed_cell(const std::vector<std::string>& cell, int k, const std::string& where) {
  const std::string& c = cell[static_cast<std::size_t>(k)];
  double v = NAN;
  const auto r = std::from_chars(c.data(), c.data() + c.size(), v);
  const bool ok = !c.empty() && r.ec == std::errc() && r.ptr == c.data() + c.size() && std::isfinite(v) && v >= 0 &&
                  (k != 0 || (v >= 1 && v == std::floor(v) && c.find_first_not_of("0123456789") == std::string::npos));
  if (!ok) throw InputError(where, column_name(k), "'" + c + "' is not " + (k == 0 ? "a run number" : "a non-negative number"));
  return v;
}

/// One line of the table as a run.
SeedRun seed_run(const std::string& line, const std::string& where) {
  std::vector<std::string> cell;
  std::stringstream ss(line);
  for (std::string x; std::getline(ss, x, ',');) cell.push_back(x);
  if (cell.size() != 9) throw InputError(where, "", "expected 9 columns (" + std::string(kColumns) + "), got " + std::to_string(cell.size()));
  double e = 0, St_B = 0;
  for (int k : {0, 1, 2, 3, 4, 5, 6, 7}) {
    const double v = seed_cell(cell, k, where);
    if (k == 6) St_B = v;
    if (k == 7) e = v;
  }
  if (e > 1) throw InputError(where, "e", "'" + cell[7] + "' is not a coefficient of restitution in [0, 1]");
  return {cell[0], cell[8], cell[6], cell[7], cell[5], e, St_B};
}

}  // namespace validate_impl

std::vector<SeedRun> read_table_6_1() {
  const std::string table = data_dir() + "/reference/li_2010_table_6_1.csv";
  std::ifstream in(table);
  if (!in) throw InputError(table, "", "cannot open the reference table");
  std::vector<SeedRun> runs;
  std::string line;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#' || line.rfind("run,", 0) == 0) continue;
    runs.push_back(validate_impl::seed_run(line, table + ":" + std::to_string(line_no)));
  }
  if (runs.empty()) throw InputError(table, "", "no runs in the reference table");
  return runs;
}

std::vector<ValidateModel> validate_models(const std::vector<std::string>& names) {
  using validate_impl::kValidateModels;
  if (names.empty()) return kValidateModels;
  std::vector<ValidateModel> out;
  for (const auto& n : names) {
    auto it = std::find_if(kValidateModels.begin(), kValidateModels.end(), [&](const auto& m) { return m.name == n; });
    if (it == kValidateModels.end()) throw InputError("command line", "--models", "unknown model '" + n + "' (expected seed, asymptotic" +
                                                         (n == "exact" ? "; 'exact' is called 'asymptotic' since 0.3.0)" : ")"));
    if (std::none_of(out.begin(), out.end(), [&](const auto& m) { return m.name == n; })) out.push_back(*it);
  }
  return out;
}

const char* to_string(SpeedSet s) { return s == SpeedSet::V_Io ? "V_Io" : "St_B"; }

void Agreement::add(const std::string& run, double e, double e_seed, double tol) {
  ++runs;
  const double d = std::isnan(e) ? INFINITY : std::abs(e - e_seed);
  if (d <= tol) ++within;
  if (d >= worst) worst = d, worst_run = run;
}

void check_validate_options(const ValidateOptions& opt, const std::vector<Override>& overrides) {
  if (!(std::isfinite(opt.tolerance) && opt.tolerance > 0))
    throw InputError("command line", "--tolerance", "must be a positive number (got " + fmt_number(opt.tolerance) + ")");
  for (const auto& o : overrides)
    if (o.key == "lubrication.model" || (o.key == "lubrication" && o.value.find("model") != std::string::npos))
      throw InputError("command line", "lubrication.model",
                       "imcol validate sets the gap law of each model; choose the models with --models seed,asymptotic instead of --set");
}

}  // namespace imcol::study
