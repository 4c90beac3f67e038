// SPDX-License-Identifier: BSD-3-Clause
#include "apps/validate.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>
#include <tuple>
#include <utility>

#include "apps/format.hpp"
#include "apps/output_unit.hpp"
#include "apps/plot.hpp"
#include "apps/validate_speed.hpp"
#include "core/errors.hpp"
#include "core/materials.hpp"
#include "core/report.hpp"
#include "run/simulate.hpp"

namespace imcol {

namespace {

namespace fs = std::filesystem;

/// The overrides without the [flow] ones (for the reduced-order runs beside coupled ones).
std::vector<Override> without_flow_keys(const std::vector<Override>& ov) {
  std::vector<Override> out;
  for (const auto& o : ov)
    if (o.key.rfind("flow.", 0) != 0) out.push_back(o);
  return out;
}

/// The scene with the `flow` effect added to its effects (coupled runs of the shipped reduced-order scenes).
Scene with_flow(const std::string& path, std::vector<Override> ov) {
  const Scene plain = load_scene(path, without_flow_keys(ov));  // the scene's own effects
  std::string list = "[";
  for (Effect e : plain.effects) list += std::string("\"") + to_string(e) + "\",";
  list += "\"flow\"]";
  ov.push_back({"effects", list});
  return load_scene(path, ov);
}

/// The models, by the gap law of the pair (docs/model-notes.md, "Pairs").
const std::vector<ValidateModel> kValidateModels = {{"seed", LubricationModel::seed}, {"asymptotic", LubricationModel::asymptotic}};

/// Agreement of one model with the seed's e: runs within the tolerance, and the largest miss.
struct Agreement {
  int within = 0, runs = 0;
  double worst = 0;
  std::string worst_run;
  void add(const std::string& run, std::optional<double> e, double e_seed, double tol) {
    ++runs;
    const double d = e ? std::abs(*e - e_seed) : INFINITY;
    if (d <= tol) ++within;
    if (d >= worst) worst = d, worst_run = run;
  }
  std::string text(double tol) const {
    std::ostringstream os;
    os << "|e - e_seed| <= " << tol << " in " << within << " of " << runs << " runs; largest " << fixed(worst, 3) << " (run " << worst_run << ")";
    return os.str();
  }
};

/// The reference table's columns, in order.
constexpr const char* kColumns = "run,mu_cP,rho_l_g_cm3,rho_p_star_g_cm3,V_Io_cm_s,Re_Io,St_B,e,pair";
std::string column_name(int k) {
  std::stringstream ss(kColumns);
  std::string name;
  for (int i = 0; i <= k; ++i) std::getline(ss, name, ',');
  return name;
}

}  // namespace

std::vector<SeedRun> read_table_6_1() {
  const std::string table = data_dir() + "/reference/li_2010_table_6_1.csv";
  std::ifstream in(table);
  if (!in) throw InputError(table, "", "cannot open the reference table");
  std::vector<SeedRun> runs;
  std::string line;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    double e = 0, St_B = 0;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#' || line.rfind("run,", 0) == 0) continue;
    std::vector<std::string> cell;
    std::stringstream ss(line);
    for (std::string x; std::getline(ss, x, ',');) cell.push_back(x);
    const std::string where = table + ":" + std::to_string(line_no);
    if (cell.size() != 9) throw InputError(where, "", "expected 9 columns (" + std::string(kColumns) + "), got " + std::to_string(cell.size()));
    // Every numeric cell must be a finite number (the run number a positive integer naming data/scenes/seed_run<run>.toml).
    for (int k : {0, 1, 2, 3, 4, 5, 6, 7}) {
      const std::string& c = cell[k];
      double v = NAN;
      const auto r = std::from_chars(c.data(), c.data() + c.size(), v);
      const bool ok = !c.empty() && r.ec == std::errc() && r.ptr == c.data() + c.size() && std::isfinite(v) && v >= 0 &&
                      (k != 0 || (v >= 1 && v == std::floor(v) && c.find_first_not_of("0123456789") == std::string::npos));
      if (!ok) throw InputError(where, column_name(k), "'" + c + "' is not " + (k == 0 ? "a run number" : "a non-negative number"));
      if (k == 6) St_B = v;
      if (k == 7) e = v;
    }
    if (e > 1) throw InputError(where, "e", "'" + cell[7] + "' is not a coefficient of restitution in [0, 1]");
    runs.push_back({cell[0], cell[8], cell[6], cell[7], cell[5], e, St_B});
  }
  if (runs.empty()) throw InputError(table, "", "no runs in the reference table");
  return runs;
}

std::vector<ValidateModel> validate_models(const std::vector<std::string>& names) {
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

namespace {

/// The validation set's name, --tolerance, and no gap law by --set (the models differ in it: chosen with --models).
void check_validate_options(const std::string& what, const ValidateOptions& opt, const std::vector<Override>& overrides) {
  if (what != "seed") throw InputError("validate", what, "unknown validation set (expected 'seed')");
  if (!(std::isfinite(opt.tolerance) && opt.tolerance > 0))
    throw InputError("command line", "--tolerance", "must be a positive number (got " + fmt_number(opt.tolerance) + ")");
  for (const auto& o : overrides)
    if (o.key == "lubrication.model" || (o.key == "lubrication" && o.value.find("model") != std::string::npos))
      throw InputError("command line", "lubrication.model",
                       "imcol validate sets the gap law of each model; choose the models with --models seed,asymptotic instead of --set");
}

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
void print_block_heading(const std::string& set, bool flow) {
  std::cout << "\n"
            << (set == "V_Io" ? "At V_Io (the printed approach speed):"
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

std::string validate_csv_header(bool flow) {
  std::string h = "run,pair,model,lubrication_model,speed_set,V_m_s,St_B_seed,e_seed,Re_seed,St_B,St_B_table_6_1,St_B_eq_6_2,e,"
                  "e_minus_e_seed,e_instant,Re,group_velocity_m_s,steps,wall_time_s";
  if (flow)
    h += ",e_reduced_order,e_reduced_order_minus_e_seed,St_B_table_6_1_reduced_order,St_B_eq_6_2_reduced_order,wall_time_reduced_order_s,"
         "flow_steps,flow_ms_per_step,cells_per_diameter,flow_dt_s";
  return h + "\n";
}

/// One run with one model at one speed: `s` the reported run (coupled with --flow), `rs` the reduced-order one.
struct ValidateRow {
  const SeedRun* sr;
  const ValidateModel* model;
  std::string set;  // V_Io | St_B
  double V;         // the approach speed, m/s
  RunSummary s, rs;
  bool flow;
  std::optional<double> diff(std::optional<double> v) const { return v ? std::optional<double>(*v - sr->e_value) : std::nullopt; }
};

void print_validate_row(const ValidateRow& r) {
  const auto& s = r.s;
  auto show = [](std::optional<double> v, int prec) { return v ? fixed(*v, prec) : std::string("n/a"); };
  std::cout << std::left << std::setw(4) << r.sr->run << std::setw(13) << r.sr->pair << std::setw(11) << r.model->name << std::right
            << std::setw(8) << fixed(100 * r.V, 2) << std::setw(10) << r.sr->St_B << std::setw(11) << fixed_or_na(s.St_B_table_6_1, 1)
            << std::setw(12) << fixed_or_na(s.St_B_eq_6_2, 1) << std::setw(8) << r.sr->e << std::setw(8) << show(s.e, 3) << std::setw(8)
            << show(r.diff(s.e), 3);
  if (r.flow) std::cout << std::setw(10) << show(r.rs.e, 3) << std::setw(8) << show(r.diff(r.rs.e), 3);
  std::cout << std::setw(8) << fixed_or_na(s.e_instant, 3) << std::setw(10)
            << (s.group_velocity_m_s ? fixed(1e3 * *s.group_velocity_m_s, 2) : std::string("-"))
            << std::setw(10) << (r.flow ? fixed(s.wall_time_s, 2) : fixed(1e3 * s.wall_time_s, 1));
  if (r.flow) std::cout << std::setw(9) << fixed(s.flow.value().ms_per_step, 1);
  std::cout << "\n";
}

void write_validate_row(std::ostream& csv, const ValidateRow& r) {
  const auto& s = r.s;
  const auto& rs = r.rs;
  auto num = [](std::optional<double> v) { return v ? csv_number(*v) : std::string(); };
  csv << r.sr->run << "," << r.sr->pair << "," << r.model->name << "," << to_string(r.model->lubrication) << "," << r.set << ","
      << csv_number(r.V) << "," << r.sr->St_B << "," << r.sr->e << "," << r.sr->Re << "," << csv_cell(s.St) << ","
      << csv_cell(s.St_B_table_6_1) << "," << csv_cell(s.St_B_eq_6_2) << "," << num(s.e) << "," << num(r.diff(s.e)) << ","
      << csv_cell(s.e_instant) << "," << csv_cell(s.Re) << "," << csv_cell(s.group_velocity_m_s) << ","
      << csv_number(s.solver.stats.steps) << "," << csv_number(s.wall_time_s);
  if (r.flow) {
    const FlowSummary& f = s.flow.value();
    csv << "," << num(rs.e) << "," << num(r.diff(rs.e)) << "," << csv_cell(rs.St_B_table_6_1) << "," << csv_cell(rs.St_B_eq_6_2)
        << "," << csv_number(rs.wall_time_s) << "," << csv_number(f.stats.steps) << "," << csv_number(f.ms_per_step) << ","
        << csv_number(f.stats.cells_per_diameter) << "," << csv_number(f.stats.dt);
  }
  csv << "\n";
}

/// One scene run reduced-order and, with `flow`, coupled: the reported run's summary and the reduced-order one's.
std::pair<RunSummary, RunSummary> run_validate_scene(const std::string& path, const std::vector<Override>& ov, bool flow) {
  RunSummary red = simulate(load_scene(path, without_flow_keys(ov))).summary;
  if (!flow) return {red, red};
  return {simulate(with_flow(path, ov), true).summary, red};
}

/// One Table 6.1 run with one model: its row at V_Io and its row at the speed that gives the printed St_B.
std::pair<ValidateRow, ValidateRow> validate_run(const SeedRun& sr, const ValidateModel& model, std::vector<Override> ov, bool flow) {
  const std::string path = data_dir() + "/scenes/seed_run" + sr.run + ".toml";
  ov.push_back({"lubrication.model", std::string("\"") + to_string(model.lubrication) + "\""});  // the model's law
  const Scene sc = load_scene(path, without_flow_keys(ov));
  const double V_Io = approach_speed(sc);
  auto [s, rs] = run_validate_scene(path, ov, flow);
  ValidateRow at_V{&sr, &model, "V_Io", V_Io, s, rs, flow};
  ValidateRow at_St{&sr, &model, "St_B", V_Io, s, rs, flow};
  if (!(s.St_B_table_6_1 && *s.St_B_table_6_1 > 0)) {
    std::cerr << "imcol: warning: run " << sr.run << " (" << model.name << "): no St_B at V_Io; its St_B row is the run at V_Io\n";
    return {at_V, at_St};
  }
  auto St_at = [&](double scale) {
    auto with_speed = ov;
    for (auto& o : speed_overrides(sc, scale)) with_speed.push_back(o);
    std::tie(at_St.s, at_St.rs) = run_validate_scene(path, with_speed, flow);
    at_St.V = scale * V_Io;
    return at_St.s.St_B_table_6_1;
  };
  scale_to_St(*s.St_B_table_6_1, sr.St_B_value, St_at);
  const auto St = at_St.s.St_B_table_6_1;
  if (!St || std::abs(*St - sr.St_B_value) > 0.01 * sr.St_B_value)
    std::cerr << "imcol: warning: run " << sr.run << " (" << model.name << "): St_B(T6.1) " << fixed_or_na(St, 2)
              << " at the scaled speed, printed " << sr.St_B << "\n";
  return {at_V, at_St};
}

/// Prints one set's block: its rows and each model's agreement with the seed's e.
void print_validate_block(const std::vector<ValidateRow>& rows, const std::string& set, const std::vector<ValidateModel>& models,
                          const ValidateOptions& opt) {
  print_block_heading(set, opt.flow);
  std::vector<Agreement> agree(models.size()), agree_reduced(models.size());
  for (const auto& r : rows) {
    if (r.set != set) continue;
    const std::size_t k = static_cast<std::size_t>(r.model - models.data());
    agree[k].add(r.sr->run, r.s.e, r.sr->e_value, opt.tolerance);
    if (opt.flow) agree_reduced[k].add(r.sr->run, r.rs.e, r.sr->e_value, opt.tolerance);
    print_validate_row(r);
  }
  for (std::size_t k = 0; k < models.size(); ++k) {
    std::cout << "  " << models[k].name << (opt.flow ? ", coupled: " : ": ") << agree[k].text(opt.tolerance) << "\n";
    if (opt.flow) std::cout << "  " << models[k].name << ", reduced-order: " << agree_reduced[k].text(opt.tolerance) << "\n";
  }
}

}  // namespace

/// The seed's Table 6.1: each run with the seed's gap law (lubrication.model = "seed", our reading of its (6.7)) and with
/// the asymptotic one (exact as h -> 0), reduced-order, and with --flow also coupled (MODEL.md (6.10)); both St_B
/// conventions; each at the printed V_Io and at the speed that gives the printed St_B. Only the gap law differs between
/// the models: the rest of the pair model is the scenes' (lagrangian added mass, K_H = 1, λ without the gap Reynolds number).
int cmd_validate(const std::string& what, const ValidateOptions& opt, const std::vector<Override>& overrides) {
  check_validate_options(what, opt, overrides);
  const auto models = validate_models(opt.models);
  const auto runs = read_table_6_1();
  OutputUnit unit(opt.out, fs::path("out") / (opt.flow ? "validate_seed_flow" : "validate_seed"));
  print_validate_legend(opt.flow);
  std::vector<ValidateRow> rows;
  for (const auto& sr : runs)
    for (const auto& model : models) {
      auto [at_V, at_St] = validate_run(sr, model, overrides, opt.flow);
      rows.push_back(std::move(at_V));
      rows.push_back(std::move(at_St));
    }
  std::ostringstream csv;
  csv << validate_csv_header(opt.flow);
  for (const std::string set : {"V_Io", "St_B"}) {
    print_validate_block(rows, set, models, opt);
    for (const auto& r : rows)
      if (r.set == set) write_validate_row(csv, r);
  }
  write_file_atomic(unit.dir() / "validate_seed.csv", csv.str());
  if (opt.plot) {
    std::cout.flush();
    run_plot_script("plot_validate_seed.py", unit, "validate_seed.png");
  }
  unit.commit();
  std::cout << "wrote " << (unit.target() / "validate_seed.csv").string() << "\n";
  return 0;
}

}  // namespace imcol
