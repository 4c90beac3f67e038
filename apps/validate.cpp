// SPDX-License-Identifier: BSD-3-Clause
#include "apps/validate.hpp"

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "apps/format.hpp"
#include "apps/output_unit.hpp"
#include "apps/plot.hpp"
#include "core/errors.hpp"
#include "core/work_scope.hpp"
#include "core/report.hpp"

namespace imcol {

namespace {

namespace fs = std::filesystem;

using study::ValidateResult;
using study::ValidateRow;

/// The table's title and the models' legend on stdout.
void print_validate_legend(bool flow) {
  std::cout << "Seed Table 6.1 (Li 2010) against imcol, " << (flow ? "coupled (f_SIM from the flow kernel, blended by H) and reduced-order"
                                                                  : "reduced-order (no f_SIM)") << "\n"
            << "  models (only the gap law differs; the scenes keep lagrangian added mass, K_H = 1, lambda without Re_h):\n"
            << "    seed       = the seed's gap law as we read its (6.7): 6 pi mu a_m (lambda(h/a*) - 1) U_rel on sphere m\n"
            << "    asymptotic = 6 pi mu [a*^2/h + c_log ln(a*/h)] U_rel, shifted to vanish at h_c (Jeffrey & Onishi; exact as h -> 0)\n"
            << "  St_B(T6.1) = the seed's Table 6.1 convention, half of St_B(eq6.2) = m* U_rel / (6 pi mu a*^2)\n"
            << "  each run twice: at the printed V_Io, and at the approach speed V that gives the printed St_B (same time before contact)\n";
}

/// One block's heading and column heads.
void print_block_heading(study::SpeedSet set, bool flow) {
  std::cout << "\n"
            << (set == study::SpeedSet::V_Io ? "At V_Io (the printed approach speed):"
                                             : "At St_B (V scaled so that St_B(T6.1) is the printed St_B; the seed plots e against it):")
            << "\n";
  std::cout << std::left << std::setw(4) << "run" << std::setw(13) << "pair" << std::setw(11) << "model" << std::right << std::setw(8)
            << "V cm/s" << std::setw(10) << "St_B seed" << std::setw(11) << "St_B(T6.1)" << std::setw(12) << "St_B(eq6.2)" << std::setw(8)
            << "e seed" << std::setw(8) << (flow ? "e flow" : "e") << std::setw(8) << "diff";
  if (flow) std::cout << std::setw(10) << "e reduced" << std::setw(8) << "diff";
  std::cout << std::setw(8) << "e_inst" << std::setw(10) << "U_G mm/s" << std::setw(10) << (flow ? "wall s" : "wall ms");
  if (flow) std::cout << std::setw(9) << "ms/step";
  std::cout << "\n";
}

/// v with p digits after the point; "n/a" for a missing (NaN) value.
std::string shown(double v, int p) { return std::isnan(v) ? std::string("n/a") : fixed(v, p); }

void print_validate_row(const ValidateResult& res, const ValidateRow& r) {
  const auto& s = r.run;
  const study::SeedRun& sr = res.seed_of(r);
  std::cout << std::left << std::setw(4) << sr.run << std::setw(13) << sr.pair << std::setw(11) << res.model_of(r).name << std::right
            << std::setw(8) << fixed(100 * r.V, 2) << std::setw(10) << sr.St_B << std::setw(11) << shown(s.St_B_table_6_1, 1)
            << std::setw(12) << shown(s.St_B_eq_6_2, 1) << std::setw(8) << sr.e << std::setw(8) << shown(s.e, 3) << std::setw(8)
            << shown(s.e - sr.e_value, 3);
  if (res.flow) std::cout << std::setw(10) << shown(r.reduced.e, 3) << std::setw(8) << shown(r.reduced.e - sr.e_value, 3);
  std::cout << std::setw(8) << shown(s.e_instant, 3) << std::setw(10)
            << (std::isnan(s.group_velocity_m_s) ? std::string("-") : fixed(1e3 * s.group_velocity_m_s, 2))
            << std::setw(10) << (res.flow ? fixed(s.wall_time_s, 2) : fixed(1e3 * s.wall_time_s, 1));
  if (res.flow) std::cout << std::setw(9) << fixed(s.flow_ms_per_step, 1);
  std::cout << "\n";
}

std::string agreement_text(const study::Agreement& a, double tol) {
  std::ostringstream os;
  os << "|e - e_seed| <= " << tol << " in " << a.within << " of " << a.runs << " runs; largest " << fixed(a.worst, 3) << " (run "
     << a.worst_run << ")";
  return os.str();
}

/// Prints one set's block: its rows and each model's agreement with the seed's e.
void print_validate_block(const ValidateResult& res, study::SpeedSet set) {
  print_block_heading(set, res.flow);
  for (const auto& r : res.rows)
    if (r.set == set) print_validate_row(res, r);
  const std::size_t m = res.models.size(), base = static_cast<std::size_t>(set) * m;
  for (std::size_t k = 0; k < m; ++k) {
    std::cout << "  " << res.models[k].name << (res.flow ? ", coupled: " : ": ") << agreement_text(res.agreement[base + k], res.tolerance) << "\n";
    if (res.flow)
      std::cout << "  " << res.models[k].name << ", reduced-order: " << agreement_text(res.agreement_reduced[base + k], res.tolerance) << "\n";
  }
}

/// validate_seed.csv: the columns of study::validate_columns.
std::string validate_csv(const ValidateResult& res) {
  const auto columns = study::validate_columns(res.flow);
  std::ostringstream csv;
  for (std::size_t c = 0; c < columns.size(); ++c) csv << (c ? "," : "") << columns[c].name;
  csv << "\n";
  for (const auto& r : res.rows) {
    const study::ValidateCell cell{res, r};
    for (std::size_t c = 0; c < columns.size(); ++c)
      csv << (c ? "," : "") << (columns[c].kind == study::ValidateColumn::word ? columns[c].text(cell) : csv_number(columns[c].value(cell)));
    csv << "\n";
  }
  return csv.str();
}

/// The rows' warnings on stderr.
void print_warnings(const ValidateResult& res) {
  for (const auto& r : res.rows)
    if (!r.warning.empty())
      std::cerr << "imcol: warning: run " << res.seed_of(r).run << " (" << res.model_of(r).name << "): " << r.warning << "\n";
}

}  // namespace

int cmd_validate(const std::string& what, const ValidateOptions& opt, const std::vector<Override>& overrides) {
  if (what != "seed") throw InputError("validate", what, "unknown validation set (expected 'seed')");
  study::check_validate_options(opt, overrides);
  study::validate_models(opt.models);
  study::read_table_6_1();  // a bad table is refused before the output folder is taken
  OutputUnit unit(opt.out, fs::path("out") / (opt.flow ? "validate_seed_flow" : "validate_seed"));
  print_validate_legend(opt.flow);
  const ValidateResult res = study::validate_seed(opt, overrides, study::threads(1));  // one run at a time: wall times not shared
  this_thread_work().stop.throw_if_requested();  // Ctrl-C: nothing printed or kept of a stopped study
  print_warnings(res);
  for (const auto set : {study::SpeedSet::V_Io, study::SpeedSet::St_B}) print_validate_block(res, set);
  write_file_atomic(unit.dir() / "validate_seed.csv", validate_csv(res));
  if (opt.plot) {
    std::cout.flush();
    run_plot_script("plot_validate_seed.py", unit, "validate_seed.png");
  }
  unit.commit();
  std::cout << "wrote " << (unit.target() / "validate_seed.csv").string() << "\n";
  return 0;
}

}  // namespace imcol
