#include "apps/commands.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <optional>
#include <set>
#include <sstream>

#include "apps/compare_history.hpp"
#include "apps/format.hpp"
#include "apps/plot.hpp"
#include "core/toml_reader.hpp"
#include "apps/flow_command.hpp"
#include "run/simulate.hpp"
#include "apps/sweep.hpp"
#include "apps/work_precision.hpp"
#include "core/errors.hpp"
#include "core/materials.hpp"
#include "core/report.hpp"

namespace imcol {

namespace {

namespace fs = std::filesystem;

struct CommonOptions {
  std::vector<std::string> sets;
  std::string rtol, atol, integrator;
  std::vector<Override> overrides() const {
    std::vector<Override> o;
    if (!rtol.empty()) o.push_back({"solver.rtol", rtol});
    if (!atol.empty()) o.push_back({"solver.atol", atol});
    if (!integrator.empty()) o.push_back({"solver.integrator", "\"" + integrator + "\""});
    for (const auto& s : sets) o.push_back(parse_override(s));
    return o;
  }
};

void add_common(CLI::App* cmd, CommonOptions& c) {
  cmd->add_option("--rtol", c.rtol, "relative tolerance (same as --set solver.rtol=R)");
  cmd->add_option("--atol", c.atol, "dimensionless absolute tolerance (same as --set solver.atol=A)");
  cmd->add_option("--integrator", c.integrator, "cvode | ida (same as --set solver.integrator=NAME)");
  cmd->add_option("--set", c.sets, "override a scene key: dotted.key=value (TOML value syntax)");
}

std::string json_num(const nlohmann::ordered_json& j, int prec) { return j.is_null() ? "n/a" : fixed(j.get<double>(), prec); }

/// The output directory, created before anything runs (a bad --out or name fails at once, exit 2). If the run
/// fails before anything is written, the directories this created are removed again (no empty folder is left).
class OutDir {
 public:
  OutDir(const std::string& out, const fs::path& fallback) : dir_(out.empty() ? fallback : fs::path(out)) {
    for (fs::path p = dir_; !p.empty() && !fs::exists(p); p = p.parent_path()) {
      created_.push_back(p);
      if (p == p.parent_path()) break;
    }
    std::error_code ec;
    fs::create_directories(dir_, ec);
    if (ec || !fs::is_directory(dir_))
      throw InputError(out.empty() ? "scene key 'name'" : "command line", out.empty() ? "name" : "--out",
                       "cannot create the output directory '" + dir_.string() + "'" + (ec ? ": " + ec.message() : ""));
  }
  ~OutDir() {
    if (kept_) return;
    std::error_code ec;
    for (const auto& p : created_)  // innermost first; fs::remove deletes only empty directories
      if (!fs::is_directory(p, ec) || !fs::is_empty(p, ec) || !fs::remove(p, ec)) break;
  }
  OutDir(const OutDir&) = delete;
  OutDir& operator=(const OutDir&) = delete;
  const fs::path& path() const { return dir_; }
  void keep() { kept_ = true; }

 private:
  fs::path dir_;
  std::vector<fs::path> created_;
  bool kept_ = false;
};

int cmd_run(const std::string& scene_path, const std::string& out, const CommonOptions& c, bool quiet, bool plot) {
  Scene sc = load_scene(scene_path, c.overrides());
  OutDir out_dir(out, fs::path("out") / sc.name);
  const fs::path& dir = out_dir.path();
  RunResult r = simulate(sc, !quiet);
  write_outputs(r, dir);
  out_dir.keep();
  if (!quiet) std::cout << human_summary(r) << "  wrote " << (dir / "trajectory.csv").string() << " and " << (dir / "summary.json").string() << "\n";
  if (plot) {
    std::cout.flush();
    run_plot_script("plot_run.py", dir, "trajectory.png", quiet);
    if (sc.has(Effect::flow) && sc.flow.fields) run_plot_script("plot_coupled_flow.py", dir, "flow_*.png", quiet);
  }
  return 0;
}

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

/// One run of the seed's Table 6.1 (data/reference/li_2010_table_6_1.csv), its cells as printed.
struct SeedRun {
  std::string run, pair, St_B, e, Re;
};

std::vector<SeedRun> read_table_6_1() {
  const std::string table = data_dir() + "/reference/li_2010_table_6_1.csv";
  std::ifstream in(table);
  if (!in) throw InputError(table, "", "cannot open the reference table");
  std::vector<SeedRun> runs;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("run,", 0) == 0) continue;
    std::vector<std::string> cell;
    std::stringstream ss(line);
    for (std::string x; std::getline(ss, x, ',');) cell.push_back(x);
    if (cell.size() < 9) throw InputError(table, "", "malformed row: " + line);
    runs.push_back({cell[0], cell[8], cell[6], cell[7], cell[5]});
  }
  return runs;
}

/// The models `imcol validate seed` runs, by the gap law of the pair (docs/model-notes.md, "Pairs").
struct ValidateModel {
  std::string name;        // as in --models and the CSV's `model` column
  std::string lubrication;  // lubrication.model
};
const std::vector<ValidateModel> kValidateModels = {{"seed", "seed"}, {"exact", "asymptotic"}};

std::vector<ValidateModel> validate_models(const std::vector<std::string>& names) {
  if (names.empty()) return kValidateModels;
  std::vector<ValidateModel> out;
  for (const auto& n : names) {
    auto it = std::find_if(kValidateModels.begin(), kValidateModels.end(), [&](const auto& m) { return m.name == n; });
    if (it == kValidateModels.end()) throw InputError("command line", "--models", "unknown model '" + n + "' (expected seed, exact)");
    if (std::none_of(out.begin(), out.end(), [&](const auto& m) { return m.name == n; })) out.push_back(*it);
  }
  return out;
}

std::string csv_cell(const nlohmann::ordered_json& j) { return j.is_null() ? std::string() : j.dump(); }
std::optional<double> opt_num(const nlohmann::ordered_json& j) { return j.is_null() ? std::nullopt : std::optional<double>(j.get<double>()); }

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

struct ValidateOptions {
  std::string out;
  bool flow = false, plot = true;
  std::vector<std::string> models;
  double tolerance = 0.05;
};

/// The seed's Table 6.1: each run with the seed's own pair equations (lubrication.model = "seed") and with the exact
/// gap law ("asymptotic"), reduced-order, and with --flow also coupled (MODEL.md (6.10)); both St_B conventions.
int cmd_validate(const std::string& what, const ValidateOptions& opt, const CommonOptions& c) {
  if (what != "seed") throw InputError("validate", what, "unknown validation set (expected 'seed')");
  if (!(std::isfinite(opt.tolerance) && opt.tolerance > 0))
    throw InputError("command line", "--tolerance", "must be a positive number (got " + fmt_number(opt.tolerance) + ")");
  const auto models = validate_models(opt.models);
  const auto runs = read_table_6_1();
  OutDir out_dir(opt.out, fs::path("out") / (opt.flow ? "validate_seed_flow" : "validate_seed"));
  const bool flow = opt.flow;
  std::cout << "Seed Table 6.1 (Li 2010) against imcol, " << (flow ? "coupled (f_SIM from the flow kernel, blended by H) and reduced-order"
                                                                  : "reduced-order (no f_SIM)") << "\n"
            << "  models: seed = the seed's pair equations (lubrication.model = \"seed\": 6 pi mu a_m (lambda(h/a*) - 1) U_rel);\n"
            << "          exact = the exact gap law (\"asymptotic\": 6 pi mu a*^2 U_rel / h + ..., Jeffrey & Onishi)\n"
            << "  St_B(6.1) = the table's convention, half of St_B(6.2) = m* U_rel / (6 pi mu a*^2)\n";
  std::cout << std::left << std::setw(4) << "run" << std::setw(13) << "pair" << std::setw(7) << "model" << std::right << std::setw(10)
            << "St_B seed" << std::setw(10) << "St_B(6.1)" << std::setw(10) << "St_B(6.2)" << std::setw(8) << "e seed" << std::setw(8)
            << (flow ? "e flow" : "e") << std::setw(8) << "diff";
  if (flow) std::cout << std::setw(10) << "e reduced" << std::setw(8) << "diff";
  std::cout << std::setw(8) << "e_inst" << std::setw(10) << "U_G mm/s" << std::setw(10) << (flow ? "wall s" : "wall ms");
  if (flow) std::cout << std::setw(9) << "ms/step";
  std::cout << "\n";
  std::ostringstream csv;
  csv << "run,pair,model,lubrication_model,St_B_seed,e_seed,Re_seed,St_B,St_B_table_6_1,St_B_eq_6_2,e,e_minus_e_seed,e_instant,Re,"
         "group_velocity_m_s,steps,wall_time_s";
  if (flow)
    csv << ",e_reduced_order,e_reduced_order_minus_e_seed,St_B_reduced_order,St_B_eq_6_2_reduced_order,wall_time_reduced_order_s,"
           "flow_steps,flow_ms_per_step,cells_per_diameter,flow_dt_s";
  csv << "\n";
  std::vector<Agreement> agree(models.size()), agree_reduced(models.size());
  for (const auto& sr : runs) {
    const std::string path = data_dir() + "/scenes/seed_run" + sr.run + ".toml";
    const double e_seed = std::stod(sr.e);
    for (std::size_t k = 0; k < models.size(); ++k) {
      const auto& model = models[k];
      auto ov = c.overrides();
      ov.push_back({"lubrication.model", "\"" + model.lubrication + "\""});  // the model's law, whatever --set says
      const RunResult red = simulate(load_scene(path, without_flow_keys(ov)));
      const RunResult cpl = flow ? simulate(with_flow(path, ov), true) : RunResult{};
      const auto& s = flow ? cpl.summary : red.summary;
      const auto& rs = red.summary;
      const auto e = opt_num(s["e"]), e_red = opt_num(rs["e"]);
      agree[k].add(sr.run, e, e_seed, opt.tolerance);
      if (flow) agree_reduced[k].add(sr.run, e_red, e_seed, opt.tolerance);
      auto diff = [&](std::optional<double> v) { return v ? std::optional<double>(*v - e_seed) : std::nullopt; };
      auto show = [](std::optional<double> v, int prec) { return v ? fixed(*v, prec) : std::string("n/a"); };
      std::cout << std::left << std::setw(4) << sr.run << std::setw(13) << sr.pair << std::setw(7) << model.name << std::right
                << std::setw(10) << sr.St_B << std::setw(10) << json_num(s["St_B_table_6_1"], 1) << std::setw(10)
                << json_num(s["St_B_eq_6_2"], 1) << std::setw(8) << sr.e << std::setw(8) << show(e, 3) << std::setw(8)
                << show(diff(e), 3);
      if (flow) std::cout << std::setw(10) << show(e_red, 3) << std::setw(8) << show(diff(e_red), 3);
      std::cout << std::setw(8) << json_num(s["e_instant"], 3) << std::setw(10)
                << (s["group_velocity_m_s"].is_null() ? std::string("-") : fixed(1e3 * s["group_velocity_m_s"].get<double>(), 2))
                << std::setw(10) << (flow ? fixed(s["wall_time_s"].get<double>(), 2) : fixed(1e3 * s["wall_time_s"].get<double>(), 1));
      if (flow) std::cout << std::setw(9) << fixed(s["flow"]["ms_per_step"].get<double>(), 1);
      std::cout << "\n";
      auto num = [](std::optional<double> v) { return v ? csv_number(*v) : std::string(); };
      csv << sr.run << "," << sr.pair << "," << model.name << "," << model.lubrication << "," << sr.St_B << "," << sr.e << "," << sr.Re
          << "," << csv_cell(s["St"]) << "," << csv_cell(s["St_B_table_6_1"]) << "," << csv_cell(s["St_B_eq_6_2"]) << "," << num(e)
          << "," << num(diff(e)) << "," << csv_cell(s["e_instant"]) << "," << csv_cell(s["Re"]) << "," << csv_cell(s["group_velocity_m_s"])
          << "," << csv_cell(s["solver"]["steps"]) << "," << csv_cell(s["wall_time_s"]);
      if (flow) {
        const auto& f = s["flow"];
        csv << "," << num(e_red) << "," << num(diff(e_red)) << "," << csv_cell(rs["St_B_table_6_1"]) << "," << csv_cell(rs["St_B_eq_6_2"])
            << "," << csv_cell(rs["wall_time_s"]) << "," << csv_cell(f["steps"]) << "," << csv_cell(f["ms_per_step"]) << ","
            << csv_cell(f["grid"]["cells_per_diameter"]) << "," << csv_cell(f["dt_s"]);
      }
      csv << "\n";
    }
  }
  for (std::size_t k = 0; k < models.size(); ++k) {
    std::cout << "  " << models[k].name << (flow ? ", coupled: " : ": ") << agree[k].text(opt.tolerance) << "\n";
    if (flow) std::cout << "  " << models[k].name << ", reduced-order: " << agree_reduced[k].text(opt.tolerance) << "\n";
  }
  const fs::path& dir = out_dir.path();
  write_file_atomic(dir / "validate_seed.csv", csv.str());
  out_dir.keep();
  std::cout << "wrote " << (dir / "validate_seed.csv").string() << "\n";
  if (opt.plot) {
    std::cout.flush();
    run_plot_script("plot_validate_seed.py", dir, "validate_seed.png");
  }
  return 0;
}

/// What accuracy costs: e and wall time (median of repeats) at each rtol, against the tightest.
int cmd_bench(const std::string& scene_path, const std::vector<double>& rtols, int repeat, const CommonOptions& c) {
  if (repeat < 1) throw InputError("--repeat", "repeat", "must be >= 1");
  if (rtols.empty()) throw InputError("--rtols", "rtols", "give at least one tolerance");
  struct Row { double rtol, e, ms; long steps, rhs; };
  std::vector<Row> rows;
  std::string name;
  for (double rt : rtols) {
    auto ov = c.overrides();
    std::ostringstream v;
    v << std::setprecision(17) << rt;
    ov.push_back({"solver.rtol", v.str()});
    Scene sc = load_scene(scene_path, ov);
    name = sc.name;
    std::vector<double> times;
    RunResult r;
    for (int k = 0; k < repeat; ++k) {
      r = simulate(sc);
      times.push_back(r.summary["wall_time_s"].get<double>());
    }
    std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
    const auto& s = r.summary;
    rows.push_back({rt, s["e"].is_null() ? NAN : s["e"].get<double>(), 1e3 * times[times.size() / 2],
                    s["solver"]["steps"].get<long>(), s["solver"]["rhs_evals"].get<long>()});
  }
  const auto tight = *std::min_element(rows.begin(), rows.end(), [](auto& a, auto& b) { return a.rtol < b.rtol; });
  const double base = rows.front().ms;
  std::cout << "scene " << name << ": median of " << repeat << " runs; error against rtol " << tight.rtol
            << "; time ratio against rtol " << rows.front().rtol << "\n";
  std::cout << std::setw(10) << "rtol" << std::setw(14) << "e" << std::setw(12) << "|e - e_ref|" << std::setw(8) << "steps"
            << std::setw(8) << "rhs" << std::setw(11) << "median ms" << std::setw(8) << "ratio" << "\n";
  for (const auto& r : rows) {
    std::cout << std::setw(10) << std::setprecision(2) << std::scientific << r.rtol << std::setw(14) << std::fixed
              << std::setprecision(9) << r.e << std::setw(12) << std::scientific << std::setprecision(1)
              << std::abs(r.e - tight.e) << std::setw(8) << r.steps << std::setw(8) << r.rhs << std::setw(11) << std::fixed
              << std::setprecision(3) << r.ms << std::setw(8) << std::setprecision(2) << r.ms / base << "\n";
  }
  return 0;
}

/// Which effect does what: the scene with all its effects, then without each one in turn.
int cmd_effects(const std::string& scene_path, const CommonOptions& c) {
  const Scene full = load_scene(scene_path, c.overrides());
  if (full.has_target() && !full.has(Effect::gravity)) {
    // Without gravity nothing can start an approach: no collision, nothing to compare.
    const double u_rel0 = full.spheres[0].velocity - (full.two_spheres() ? full.spheres[1].velocity : 0.0);
    if (!(u_rel0 > 0))
      throw InputError(full.path, "sphere[0].velocity",
                       "the spheres are not approaching (U_rel(0) = " + fmt_number(u_rel0) +
                           " m/s, no gravity): there is no collision, so no e to compare");
  }
  std::vector<std::pair<std::string, EffectSet>> variants = {{"all", full.effects}};
  for (Effect e : full.effects) {
    if (e == Effect::elastic && full.has_target()) continue;  // required: the solids would pass through
    auto fewer = full.effects;
    fewer.erase(e);
    variants.push_back({std::string("without ") + to_string(e), fewer});
  }
  std::cout << "scene " << full.name << ": each effect removed in turn\n";
  // A free sphere has no e: its final velocity says what each effect does.
  const bool free = !full.has_target();
  std::cout << std::left << std::setw(24) << "effects" << std::right << std::setw(10) << (free ? "u_end m/s" : "e") << std::setw(10) << "de"
            << std::setw(10) << "St" << std::setw(13) << "min gap um" << std::setw(13) << "max F_c N" << std::setw(8)
            << "steps" << "\n";
  double e_all = NAN;
  bool first = true;
  for (const auto& [label, effects] : variants) {
    Scene sc = full;  // the scene as read, with fewer effects (its tables for them are simply unused)
    sc.effects = effects;
    const RunResult r = simulate(sc);
    const auto& s = r.summary;
    const double e = free ? s.value("u1_final_m_s", NAN) : (s["e"].is_null() ? NAN : s["e"].get<double>());
    if (first && !free && std::isnan(e))
      throw InputError(full.path, "solver.t_end",
                       "no collision by t_end = " + fmt_number(full.solver.t_end) + " s with all effects: e is undefined (raise solver.t_end)");
    first = false;
    if (label == "all") e_all = e;
    auto cell = [&](double v) { return std::isnan(v) ? std::string("n/a") : fixed(v, free ? 6 : 4); };
    std::cout << std::left << std::setw(24) << label << std::right << std::setw(10) << cell(e) << std::setw(10)
              << (label == "all" ? std::string("-") : cell(e - e_all)) << std::setw(10) << json_num(s["St"], 1)
              << std::setw(13) << (s["min_gap_m"].is_null() ? std::string("n/a") : fixed(1e6 * s["min_gap_m"].get<double>(), 3))
              << std::setw(13) << fixed(s["max_contact_force_N"].get<double>(), 3) << std::setw(8)
              << s["solver"]["steps"].get<long>() << "\n";
  }
  return 0;
}

}  // namespace

int run_cli(int argc, char** argv) {
  CLI::App app{"imcol: head-on collisions of spheres immersed in a viscous liquid"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("imcol ") + IMCOL_VERSION);

  CommonOptions run_opt, val_opt, bench_opt;
  std::string scene, out;
  bool quiet = false, run_no_plot = false;
  auto* run = app.add_subcommand("run", "simulate one scene; writes DIR/trajectory.csv and DIR/summary.json");
  run->add_option("scene", scene, "scene file (TOML)")->required();
  run->add_option("--out", out, "output directory (default out/<scene name>)");
  run->add_flag("--quiet", quiet, "print nothing on success (no progress line)");
  run->add_flag("--no-plot", run_no_plot, "skip DIR/trajectory.png");
  add_common(run, run_opt);

  std::string what;
  ValidateOptions vopt;
  bool val_no_plot = false;
  auto* val = app.add_subcommand("validate", "run a validation set and compare with its reference ('seed': Table 6.1)");
  val->add_option("set", what, "validation set: seed")->required();
  val->add_option("--out", vopt.out, "output directory (default out/validate_seed, or out/validate_seed_flow with --flow)");
  val->add_flag("--flow", vopt.flow, "couple the flow kernel (f_SIM) into every run, beside the reduced-order model");
  val->add_option("--models", vopt.models, "seed (the seed's pair equations), exact (the exact gap law); default both")->delimiter(',');
  val->add_option("--tolerance", vopt.tolerance, "|e - e_seed| counted as agreement in the closing lines (default 0.05)");
  val->add_flag("--no-plot", val_no_plot, "skip DIR/validate_seed.png");
  add_common(val, val_opt);

  std::string bscene;
  std::vector<double> rtols = {1e-6, 1e-8, 1e-10};
  int repeat = 5;
  auto* bench = app.add_subcommand("bench", "what accuracy costs: e and median wall time at several rtol");
  bench->add_option("scene", bscene, "scene file (TOML)")->required();
  bench->add_option("--rtols", rtols, "relative tolerances to compare")->delimiter(',');
  bench->add_option("--repeat", repeat, "runs per tolerance (median reported)");
  add_common(bench, bench_opt);

  std::string escene;
  CommonOptions eff_opt;
  auto* effects = app.add_subcommand("effects", "which effect does what: rerun the scene without each of its effects");
  effects->add_option("scene", escene, "scene file (TOML)")->required();
  add_common(effects, eff_opt);

  std::string hscene;
  CommonOptions hist_opt;
  HistoryCompareOptions hopt;
  bool no_plot = false;
  auto* history = app.add_subcommand("history", "compare history-force kernels and evaluators on one scene (and without history)");
  history->add_option("scene", hscene, "scene file (TOML)")->required();
  history->add_option("--out", hopt.out, "output directory (default out/<scene name>/history)");
  history->add_option("--kernels", hopt.kernels, "kernels to run (default all)")->delimiter(',');
  history->add_option("--evaluators", hopt.evaluators, "soe-step, soe, direct (default all three)")->delimiter(',');
  history->add_flag("--no-plot", no_plot, "skip the PNG plot");
  add_common(history, hist_opt);

  std::string fscene;
  FlowCommandOptions fopt;
  bool f_no_plot = false;
  auto* flowc = app.add_subcommand("flow", "immersed-boundary flow around spheres on the axis: force history, C_D, snapshots");
  flowc->add_option("scene", fscene, "flow scene file (TOML, data/scenes/flow/)")->required();
  flowc->add_option("--out", fopt.out, "output directory (default out/<scene name>)");
  long f_cells = 0, f_levels = 0;
  double f_dt = 0, f_t_end = 0;
  auto* o_cells = flowc->add_option("--cells", f_cells, "override grid.cells_per_diameter");
  auto* o_levels = flowc->add_option("--levels", f_levels, "override grid.levels");
  auto* o_dt = flowc->add_option("--dt", f_dt, "override time.dt");
  auto* o_t_end = flowc->add_option("--t-end", f_t_end, "override time.t_end");
  flowc->add_flag("--allow-long", fopt.allow_long, "run even if the estimated wall time exceeds an hour");
  flowc->add_flag("--no-plot", f_no_plot, "skip the PNG plots");

  std::string wscene;
  CommonOptions wp_opt;
  WorkPrecisionOptions wopt;
  bool wp_no_plot = false;
  auto* wp = app.add_subcommand("work-precision", "what accuracy costs: a tolerance ladder per integrator and history evaluator against a tight reference");
  wp->add_option("scene", wscene, "scene file (TOML)")->required();
  wp->add_option("--out", wopt.out, "output directory (default out/<scene name>/work_precision)");
  wp->add_option("--rtols", wopt.rtols, "the rtol ladder (atol = rtol)")->delimiter(',');
  wp->add_option("--integrators", wopt.integrators, "cvode-dense, cvode-gmres, ida (default all)")->delimiter(',');
  wp->add_option("--evaluators", wopt.evaluators, "history evaluators soe-step, soe, direct (default all three if the scene has history)")->delimiter(',');
  wp->add_option("--direct-steps", wopt.direct_steps, "direct evaluator: multiples of its default step")->delimiter(',');
  wp->add_option("--direct-rtol", wopt.direct_rtol, "direct evaluator: rtol while its step varies");
  wp->add_option("--ref-rtol", wopt.ref_rtol, "reference run: rtol = atol");
  wp->add_option("--ref-history-tolerance", wopt.ref_history_tol, "reference run: soe fit tolerance");
  wp->add_option("--repeat", wopt.repeat, "runs per setting (median wall time reported)");
  wp->add_flag("--add-history", wopt.add_history, "add the history effect (Basset) to a scene without it");
  wp->add_flag("--no-plot", wp_no_plot, "skip the PNG plot");
  add_common(wp, wp_opt);

  std::string sscene;
  CommonOptions sw_opt;
  SweepOptions sopt;
  bool sw_no_plot = false, sw_no_progress = false;
  auto* sw = app.add_subcommand("sweep", "e against St over a range of one quantity, the points in parallel");
  sw->add_option("scene", sscene, "scene file (TOML)")->required();
  sw->add_option("--vary", sopt.vary, "velocity (impactor) | viscosity | diameter | density (every sphere, ratios kept)")
      ->required()->check(CLI::IsMember({"velocity", "viscosity", "diameter", "density"}));
  sw->add_option("--from", sopt.from, "first value (SI units)")->required();
  sw->add_option("--to", sopt.to, "last value (SI units)")->required();
  sw->add_option("--points", sopt.points, "number of points")->required();
  sw->add_option("--spacing", sopt.spacing, "log (default) | linear")->check(CLI::IsMember({"log", "linear"}));
  sw->add_option("--jobs", sopt.jobs, "parallel runs (default: all cores)");
  sw->add_option("--out", sopt.out, "output directory (default out/<scene name>/sweep_<quantity>)");
  sw->add_flag("--no-progress", sw_no_progress, "no progress line on the terminal");
  sw->add_flag("--no-plot", sw_no_plot, "skip the PNG plot");
  add_common(sw, sw_opt);

  // An unknown subcommand is named as such (CLI11 would only say that a subcommand is required).
  if (argc >= 2 && argv[1][0] != '-') {
    std::string known;
    bool found = false;
    for (const auto* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
      found = found || sub->get_name() == argv[1];
      known += (known.empty() ? "" : ", ") + sub->get_name();
    }
    if (!found) {
      std::cerr << "imcol: error: " << InputError("command line", "", std::string("unknown subcommand '") + argv[1] + "' (expected " + known + ")").what() << "\n";
      return 2;
    }
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }

  try {
    if (*run) return cmd_run(scene, out, run_opt, quiet, !run_no_plot);
    if (*val) {
      vopt.plot = !val_no_plot;
      return cmd_validate(what, vopt, val_opt);
    }
    if (*bench) return cmd_bench(bscene, rtols, repeat, bench_opt);
    if (*effects) return cmd_effects(escene, eff_opt);
    if (*flowc) {
      fopt.plot = !f_no_plot;
      if (o_cells->count()) fopt.cells_per_diameter = f_cells;
      if (o_levels->count()) fopt.levels = f_levels;
      if (o_dt->count()) fopt.dt = f_dt;
      if (o_t_end->count()) fopt.t_end = f_t_end;
      return cmd_flow(fscene, fopt);
    }
    if (*sw) {
      sopt.plot = !sw_no_plot;
      sopt.progress = !sw_no_progress;
      return sweep(sscene, sw_opt.overrides(), sopt);
    }
    if (*wp) {
      wopt.plot = !wp_no_plot;
      return work_precision(wscene, wp_opt.overrides(), wopt);
    }
    if (*history) {
      hopt.plot = !no_plot;
      return compare_history(hscene, hist_opt.overrides(), hopt);
    }
  } catch (const InputError& e) {
    std::cerr << "imcol: error: " << e.what() << "\n";
    return 2;
  } catch (const SolverError& e) {
    std::cerr << "imcol: solver failure: " << e.what() << "\n";
    return 3;
  } catch (const std::bad_alloc&) {
    std::cerr << "imcol: error: out of memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "imcol: error: " << e.what() << "\n";
    return 1;
  }
  return 1;
}

}  // namespace imcol
