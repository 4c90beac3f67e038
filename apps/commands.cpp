// SPDX-License-Identifier: BSD-3-Clause
#include "apps/commands.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include "apps/calibrate.hpp"
#include "apps/compare_history.hpp"
#include "apps/compare_laws.hpp"
#include "apps/history_sweep.hpp"
#include "apps/format.hpp"
#include "apps/option_rules.hpp"
#include "apps/output_unit.hpp"
#include "apps/plot.hpp"
#include "apps/scenes_command.hpp"
#include "apps/sigint.hpp"
#include "core/toml_reader.hpp"
#include "apps/flow_command.hpp"
#include "run/simulate.hpp"
#include "apps/sweep.hpp"
#include "apps/validate.hpp"
#include "apps/work_precision.hpp"
#include "core/errors.hpp"
#include "core/number_text.hpp"
#include "core/timing.hpp"
#include "core/work_scope.hpp"
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

// The intervals of the scene keys the options stand for (core/scene.cpp).
const Interval kRtol{1e-14, 1, false, true};
const Interval kAtol{0, 1, true, true};
const Interval kPositive{0, 1e30, true, false};

void add_common(CLI::App* cmd, CommonOptions& c) {
  cmd->add_option("--rtol", c.rtol, "relative tolerance (same as --set solver.rtol=R)")->type_name("FLOAT")->check(number_rule("--rtol", kRtol));
  cmd->add_option("--atol", c.atol, "dimensionless absolute tolerance (same as --set solver.atol=A)")->type_name("FLOAT")->check(number_rule("--atol", kAtol));
  cmd->add_option("--integrator", c.integrator, "cvode | ida (same as --set solver.integrator=NAME)")
      ->check(choice_rule("--integrator", choice_names<IntegratorMethod>()));
  cmd->add_option("--set", c.sets, "override a scene key: dotted.key=value (TOML value syntax)");
}

/// The scene argument of a command: a file, or a shipped scene's name (find_scene), replaced by the file it names.
void add_scene(CLI::App* cmd, std::string& scene,
               const std::string& help = "scene: a file (TOML), or a shipped scene's name (default, coupled/gg3462; imcol scenes lists them)") {
  cmd->add_option("scene", scene, help)->required()->transform(scene_rule());
}

/// An option the command sets itself (bench takes its tolerances from --rtols): refused if given.
void refuse_option(const CLI::App* cmd, const std::string& option, const std::string& why) {
  if (cmd->get_option(option)->count()) throw InputError("command line", option, why);
}

int cmd_run(const std::string& scene_path, const std::string& out, const CommonOptions& c, bool quiet, bool plot) {
  Scene sc = load_scene(scene_path, c.overrides());
  OutputUnit unit(out, fs::path("out") / sc.name, sc.path);
  // A coupled run's flow fields go to the staging folder as they are made (many snapshots are never held at once).
  RunResult r = simulate(sc, !quiet, Recording::full, [&unit](const std::string& name, const std::string& content) {
    write_file_atomic(unit.dir() / name, content);
  });
  r.summary_json["run"] = unit.run();
  write_outputs(r, unit.dir());
  // "wrote" names the files where they are once the unit is committed, a moment later.
  if (!quiet) std::cout << human_summary(r) << "  wrote " << (unit.target() / "trajectory.csv").string() << " and " << (unit.target() / "summary.json").string() << "\n";
  if (plot) {
    std::cout.flush();
    run_plot_script("plot_run.py", unit, "trajectory.png", quiet);
    if (sc.has(Effect::flow) && sc.flow.fields) run_plot_script("plot_coupled_flow.py", unit, "flow_*.png", quiet);
  }
  unit.commit();
  return 0;
}

/// What accuracy costs: e and wall time (median of repeats) at each rtol; e against the tightest, time against the first;
/// also the median time of the whole simulate() call (set-up, integration, measures, summary).
int cmd_bench(const std::string& scene_path, const std::vector<double>& rtols, int repeat, const CommonOptions& c) {
  if (repeat < 1) throw InputError("--repeat", "repeat", "must be >= 1");
  if (rtols.empty()) throw InputError("--rtols", "rtols", "give at least one tolerance");
  struct Row { double rtol, e, ms, call_ms; long steps, rhs; };
  std::vector<Row> rows;
  std::string name, no_e;  // why e was not measured (the last run without one), as imcol run says it
  for (double rt : rtols) {
    auto ov = c.overrides();
    ov.push_back({"solver.rtol", toml_float(rt)});
    Scene sc = load_scene(scene_path, ov);
    name = sc.name;
    std::vector<double> times, calls;  // the integration (wall_time_s) and the whole simulate() call
    RunResult r;
    for (int k = 0; k < repeat; ++k) {
      const auto t0 = WallClock::now();
      r = simulate(sc);
      calls.push_back(seconds_since(t0));
      times.push_back(r.summary.wall_time_s);
    }
    auto median = [](std::vector<double>& v) {
      std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
      return v[v.size() / 2];
    };
    const auto& s = r.summary;
    if (!s.e) no_e = s.e_missing.value_or("not measured");
    rows.push_back({rt, s.e.value_or(NAN), 1e3 * median(times), 1e3 * median(calls), s.solver.stats.steps, s.solver.stats.rhs_evals});
  }
  const auto tight = *std::min_element(rows.begin(), rows.end(), [](auto& a, auto& b) { return a.rtol < b.rtol; });
  const double base = rows.front().ms;
  std::cout << "scene " << name << ": median of " << repeat << (repeat == 1 ? " run" : " runs") << "; error against rtol " << tight.rtol
            << "; time ratio against rtol " << rows.front().rtol
            << "; median ms: the integration (wall_time_s), call ms: the whole run with set-up, measures and summary\n";
  std::cout << std::setw(10) << "rtol" << std::setw(14) << "e" << std::setw(12) << "|e - e_ref|" << std::setw(8) << "steps"
            << std::setw(8) << "rhs" << std::setw(11) << "median ms" << std::setw(8) << "ratio" << std::setw(10) << "call ms" << "\n";
  for (const auto& r : rows) {
    // A run without e (a free sphere, no contact by t_end) shows "-" in both e columns; the reason follows the table.
    std::cout << std::setw(10) << std::setprecision(2) << std::scientific << r.rtol << std::setw(14)
              << (std::isnan(r.e) ? "-" : fixed(r.e, 9)) << std::setw(12) << sci(std::abs(r.e - tight.e), 1)
              << std::setw(8) << r.steps << std::setw(8) << r.rhs << std::setw(11) << std::fixed
              << std::setprecision(3) << r.ms << std::setw(8) << std::setprecision(2) << r.ms / base << std::setw(10)
              << std::setprecision(3) << r.call_ms << "\n";
  }
  // As imcol run: a run without e is a result (exit 0) with the reason said.
  if (!no_e.empty()) std::cout << "e not measured: " << no_e << "\n";
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
    const double e = (free ? s.u1_final_m_s : s.e).value_or(NAN);
    if (first && !free && std::isnan(e))
      throw InputError(full.path, "solver.t_end",
                       "no collision by t_end = " + fmt_number(full.solver.t_end) + " s with all effects: e is undefined (raise solver.t_end)");
    first = false;
    if (label == "all") e_all = e;
    auto cell = [&](double v) { return std::isnan(v) ? std::string("n/a") : fixed(v, free ? 6 : 4); };
    std::cout << std::left << std::setw(24) << label << std::right << std::setw(10) << cell(e) << std::setw(10)
              << (label == "all" ? std::string("-") : cell(e - e_all)) << std::setw(10) << fixed_or_na(s.St, 1)
              << std::setw(13) << (s.min_gap_m ? fixed(1e6 * *s.min_gap_m, 3) : std::string("n/a"))
              << std::setw(13) << fixed(s.max_contact_force_N.value(), 3) << std::setw(8) << s.solver.stats.steps << "\n";
  }
  return 0;
}

/// A subcommand and what it does once the command line is parsed (its options live as long as `run`).
struct Subcommand {
  const CLI::App* cmd;
  std::function<int()> run;
};

Subcommand add_run(CLI::App& app) {
  struct Opt { CommonOptions c; std::string scene, out; bool quiet = false, no_plot = false; };
  auto o = std::make_shared<Opt>();
  auto* run = app.add_subcommand("run", "simulate one scene; writes DIR/trajectory.csv and DIR/summary.json");
  add_scene(run, o->scene);
  run->add_option("--out", o->out, "output directory (default out/<scene name>)")->check(path_rule("--out"));
  run->add_flag("--quiet", o->quiet, "print nothing on success (no progress line)");
  run->add_flag("--no-plot", o->no_plot, "skip DIR/trajectory.png");
  add_common(run, o->c);
  return {run, [o] { return cmd_run(o->scene, o->out, o->c, o->quiet, !o->no_plot); }};
}

Subcommand add_validate(CLI::App& app) {
  struct Opt { CommonOptions c; std::string what; ValidateOptions v; bool no_plot = false; };
  auto o = std::make_shared<Opt>();
  auto* val = app.add_subcommand("validate", "run a validation set and compare with its reference ('seed': Table 6.1)");
  val->add_option("set", o->what, "validation set: seed")->required();
  val->add_option("--out", o->v.out, "output directory (default out/validate_seed, or out/validate_seed_flow with --flow)")->check(path_rule("--out"));
  val->add_flag("--flow", o->v.flow, "couple the flow kernel (f_SIM) into every run, beside the reduced-order model");
  val->add_option("--models", o->v.models, "seed (the seed's gap law), asymptotic (Jeffrey & Onishi's leading terms, exact as h -> 0); default both")
      ->delimiter(',')->check(CLI::Validator([](std::string& name) { study::validate_models({name}); return std::string(); }, "seed | asymptotic"));
  val->add_option("--tolerance", o->v.tolerance, "|e - e_seed| counted as agreement in the closing lines (default 0.05)")
      ->check(number_rule("--tolerance", {0, 1, true, false}));
  val->add_flag("--no-plot", o->no_plot, "skip DIR/validate_seed.png");
  add_common(val, o->c);
  return {val, [o] {
    o->v.plot = !o->no_plot;
    return cmd_validate(o->what, o->v, o->c.overrides());
  }};
}

Subcommand add_bench(CLI::App& app) {
  struct Opt { CommonOptions c; std::string scene; std::vector<double> rtols = {1e-6, 1e-8, 1e-10}; int repeat = 5; };
  auto o = std::make_shared<Opt>();
  auto* bench = app.add_subcommand("bench", "what accuracy costs: e and median wall time at several rtol");
  add_scene(bench, o->scene);
  bench->add_option("--rtols", o->rtols, "relative tolerances to compare")->delimiter(',')->check(number_rule("--rtols", kRtol));
  bench->add_option("--repeat", o->repeat, "runs per tolerance (median reported)")->check(integer_rule("--repeat", 1, 1000));
  add_common(bench, o->c);
  return {bench, [o, bench] {
    // An option the command sets itself along its own ladder.
    refuse_option(bench, "--rtol", "bench runs every rtol of --rtols: give the tolerances there");
    return cmd_bench(o->scene, o->rtols, o->repeat, o->c);
  }};
}

Subcommand add_effects(CLI::App& app) {
  struct Opt { CommonOptions c; std::string scene; };
  auto o = std::make_shared<Opt>();
  auto* effects = app.add_subcommand("effects", "which effect does what: rerun the scene without each of its effects");
  add_scene(effects, o->scene);
  add_common(effects, o->c);
  return {effects, [o] { return cmd_effects(o->scene, o->c); }};
}

/// The range of a sweep: --vary, --from, --to, --points, --spacing. imcol sweep requires the range; inside another
/// command (laws, history: `optional`, "sweep: " in the help) a range needs --vary and --vary a range. Returns --vary,
/// for further options that need it.
CLI::Option* add_sweep_range(CLI::App* cmd, SweepOptions& s, bool optional) {
  const std::string tag = optional ? "sweep: " : "";
  auto* vary = cmd->add_option("--vary", s.vary, tag + "velocity (impactor) | viscosity | diameter | density (every sphere, ratios kept)")
                   ->check(choice_rule("--vary", sweep_quantities()));
  auto* from = cmd->add_option("--from", s.from, tag + "first value (SI units)")->check(number_rule("--from", kPositive));
  auto* to = cmd->add_option("--to", s.to, tag + "last value (SI units)")->check(number_rule("--to", kPositive));
  auto* points = cmd->add_option("--points", s.points, tag + "number of points")->check(integer_rule("--points", 1, 100000));
  auto* spacing = cmd->add_option("--spacing", s.spacing, tag + "log (default) | linear")->check(choice_rule("--spacing", {"log", "linear"}));
  if (!optional) {
    for (auto* opt : {vary, from, to, points}) opt->required();
    return vary;
  }
  vary->needs(from)->needs(to)->needs(points);
  for (auto* opt : {from, to, points, spacing}) opt->needs(vary);
  return vary;
}

Subcommand add_history(CLI::App& app) {
  struct Opt { CommonOptions c; std::string scene; HistoryCompareOptions h; bool no_plot = false, no_progress = false; };
  auto o = std::make_shared<Opt>();
  auto* history = app.add_subcommand("history", "compare history-force kernels and evaluators on one scene (and without history); "
                                                "with --vary, e against St per kernel over a sweep");
  add_scene(history, o->scene);
  history->add_option("--out", o->h.out, "output directory (default out/<scene name>-history, a sweep: -history_<quantity>)")->check(path_rule("--out"));
  history->add_option("--kernels", o->h.kernels, "kernels to run (default all)")->delimiter(',')
      ->check(choice_rule("--kernels", choice_names<KernelKind>()));
  auto* evaluators = history->add_option("--evaluators", o->h.evaluators, "soe-step, soe, direct (default all three; a sweep: the scene's)")
                         ->delimiter(',')->check(choice_rule("--evaluators", choice_names<HistoryEvaluator>()));
  // Optionally at each point of a sweep (imcol sweep's quantities, spacing and --jobs): e against St per kernel.
  auto* vary = add_sweep_range(history, o->h.sweep, true);
  history->add_option("--jobs", o->h.sweep.jobs, "sweep: parallel runs (default: all cores)")->check(integer_rule("--jobs", 0, 1024))->needs(vary);
  history->add_flag("--no-progress", o->no_progress, "sweep: no progress line on the terminal")->needs(vary);
  history->add_flag("--no-plot", o->no_plot, "skip the PNG plot");
  add_common(history, o->c);
  return {history, [o, evaluators] {
    o->h.plot = !o->no_plot;
    o->h.evaluators_given = evaluators->count() > 0;
    o->h.sweep.progress = !o->no_progress;
    if (!o->h.sweep.vary.empty()) return history_sweep(o->scene, o->c.overrides(), o->h);
    return compare_history(o->scene, o->c.overrides(), o->h);
  }};
}

Subcommand add_laws(CLI::App& app) {
  struct Opt { CommonOptions c; std::string scene; LawsCompareOptions l; bool no_plot = false; };
  auto o = std::make_shared<Opt>();
  auto* laws = app.add_subcommand("laws", "compare the solid contact laws (contact.law) on one scene: e, contact time, peak force, overlap");
  add_scene(laws, o->scene);
  laws->add_option("--laws", o->l.laws, "contact laws to run (default every shipped law)")->delimiter(',')
      ->check(choice_rule("--laws", choice_names<ContactLawKind>()));
  laws->add_option("--out", o->l.out, "output directory (default out/<scene name>-laws, a sweep: -laws_<quantity>)")->check(path_rule("--out"));
  // Optionally at each point of a sweep (imcol sweep's quantities and spacing): e against St per law.
  add_sweep_range(laws, o->l.sweep, true);
  laws->add_flag("--no-plot", o->no_plot, "skip the PNG plot");
  add_common(laws, o->c);
  return {laws, [o] {
    o->l.plot = !o->no_plot;
    return compare_laws(o->scene, o->c.overrides(), o->l);
  }};
}

Subcommand add_flow(CLI::App& app) {
  struct Opt { std::string scene; FlowCommandOptions f; bool no_plot = false; long cells = 0, levels = 0; double dt = 0, t_end = 0; };
  auto o = std::make_shared<Opt>();
  auto* flowc = app.add_subcommand("flow", "immersed-boundary flow around spheres on the axis: force history, C_D, snapshots");
  add_scene(flowc, o->scene, "flow scene: a file (TOML), or a shipped scene's name (flow/fixed_sphere_re20; imcol scenes flow/)");
  flowc->add_option("--out", o->f.out, "output directory (default out/<scene name>)")->check(path_rule("--out"));
  // The flow scene's ranges (flow/flow_scene.cpp): grid.cells_per_diameter 4-4096, grid.levels 1-16.
  auto* o_cells = flowc->add_option("--cells", o->cells, "override grid.cells_per_diameter")->check(integer_rule("--cells", 4, 4096));
  auto* o_levels = flowc->add_option("--levels", o->levels, "override grid.levels")->check(integer_rule("--levels", 1, 16));
  auto* o_dt = flowc->add_option("--dt", o->dt, "override time.dt")->check(number_rule("--dt", kPositive));
  auto* o_t_end = flowc->add_option("--t-end", o->t_end, "override time.t_end")->check(number_rule("--t-end", kPositive));
  flowc->add_flag("--allow-long", o->f.allow_long, "run even if the estimated wall time exceeds an hour");
  flowc->add_flag("--no-plot", o->no_plot, "skip the PNG plots");
  return {flowc, [o, o_cells, o_levels, o_dt, o_t_end] {
    auto& f = o->f;
    f.plot = !o->no_plot;
    if (o_cells->count()) f.cells_per_diameter = o->cells;
    if (o_levels->count()) f.levels = o->levels;
    if (o_dt->count()) f.dt = o->dt;
    if (o_t_end->count()) f.t_end = o->t_end;
    return cmd_flow(o->scene, f);
  }};
}

Subcommand add_work_precision(CLI::App& app) {
  struct Opt { CommonOptions c; std::string scene; WorkPrecisionOptions w; bool no_plot = false; };
  auto o = std::make_shared<Opt>();
  auto& w = o->w;
  auto* wp = app.add_subcommand("work-precision", "what accuracy costs: a tolerance ladder per integrator and history evaluator against a tight reference");
  add_scene(wp, o->scene);
  wp->add_option("--out", w.out, "output directory (default out/<scene name>-work_precision)")->check(path_rule("--out"));
  wp->add_option("--rtols", w.rtols, "the rtol ladder (atol = rtol)")->delimiter(',')->check(number_rule("--rtols", kRtol));
  wp->add_option("--integrators", w.integrators, "cvode-dense, cvode-gmres, ida (default all)")->delimiter(',')
      ->check(choice_rule("--integrators", {"cvode-dense", "cvode-gmres", "ida"}));
  wp->add_option("--evaluators", w.evaluators, "history evaluators soe-step, soe, direct (default all three if the scene has history)")
      ->delimiter(',')->check(choice_rule("--evaluators", choice_names<HistoryEvaluator>()));
  wp->add_option("--direct-steps", w.direct_steps, "direct evaluator: multiples of its default step")->delimiter(',')
      ->check(number_rule("--direct-steps", {study::kDirectStepMin, study::kDirectStepMax}));
  wp->add_option("--direct-rtol", w.direct_rtol, "direct evaluator: rtol while its step varies")->check(number_rule("--direct-rtol", kRtol));
  wp->add_option("--ref-rtol", w.ref_rtol, "reference run: rtol = atol")->check(number_rule("--ref-rtol", kRtol));
  wp->add_option("--ref-history-tolerance", w.ref_history_tol, "reference run: soe fit tolerance")
      ->check(number_rule("--ref-history-tolerance", {1e-13, 0.1, false, true}));
  wp->add_option("--repeat", w.repeat, "runs per setting (median wall time reported)")->check(integer_rule("--repeat", 1, 1000));
  wp->add_flag("--add-history", w.add_history, "add the history effect (Basset) to a scene without it");
  wp->add_flag("--no-plot", o->no_plot, "skip the PNG plot");
  add_common(wp, o->c);
  return {wp, [o, wp] {
    // Options the command sets itself along its own ladder.
    for (const char* opt : {"--rtol", "--atol", "--integrator"})
      if (wp->get_option(opt)->count()) o->w.ladder_options.push_back(opt);
    o->w.plot = !o->no_plot;
    return work_precision(o->scene, o->c.overrides(), o->w);
  }};
}

Subcommand add_scenes(CLI::App& app) {
  auto pattern = std::make_shared<std::string>();
  auto* sc = app.add_subcommand("scenes", "list the shipped scenes (the names imcol run takes) with their kind and description");
  sc->add_option("pattern", *pattern, "only the scenes whose name or description contains PATTERN (or whose name matches a glob: 'coupled/*')");
  return {sc, [pattern] { return cmd_scenes(*pattern); }};
}

Subcommand add_sweep(CLI::App& app) {
  struct Opt { CommonOptions c; std::string scene; SweepOptions s; bool no_plot = false, no_progress = false; };
  auto o = std::make_shared<Opt>();
  auto& s = o->s;
  auto* sw = app.add_subcommand("sweep", "e against St over a range of one quantity, the points in parallel");
  add_scene(sw, o->scene);
  add_sweep_range(sw, s, false);
  sw->add_option("--jobs", s.jobs, "parallel runs (default: all cores)")->check(integer_rule("--jobs", 0, 1024));
  sw->add_option("--out", s.out, "output directory (default out/<scene name>-sweep_<quantity>)")->check(path_rule("--out"));
  sw->add_flag("--no-progress", o->no_progress, "no progress line on the terminal");
  sw->add_flag("--no-plot", o->no_plot, "skip the PNG plot");
  sw->add_option("--export", s.export_format, "dem: e(St) for a DEM code, a table and fits (docs/dem.md)")->check(choice_rule("--export", {"dem"}));
  add_common(sw, o->c);
  return {sw, [o] {
    o->s.plot = !o->no_plot;
    o->s.progress = !o->no_progress;
    return sweep(o->scene, o->c.overrides(), o->s);
  }};
}

Subcommand add_calibrate(CLI::App& app) {
  struct Opt { CommonOptions c; std::string scene; CalibrateOptions k; double offset_max = 0, factor = 2; bool no_plot = false, no_progress = false; };
  auto o = std::make_shared<Opt>();
  auto& k = o->k;
  auto* cal = app.add_subcommand("calibrate", "fit scene keys to a measured trajectory or e table (docs/calibration.md)");
  add_scene(cal, o->scene);
  cal->add_option("--data", k.data, "the measurement: a trajectory (t,z1,z2) or an e table (scene keys and e), CSV")
      ->required()->check(path_rule("--data"));
  cal->add_option("--fit", k.fits, "a parameter: KEY=LO:HI or KEY=LO:HI:log (a numeric scene key, as --set takes it); repeat for more")
      ->required()->allow_extra_args(false);
  cal->add_option("--window", k.window, "trajectory: the fitted window, A:B seconds around the measured contact (A < 0 < B)")
      ->check(path_rule("--window"));
  auto* offset = cal->add_option("--offset-max", o->offset_max, "trajectory: bound on the fitted time offset |tau| (s)")
                     ->check(number_rule("--offset-max", {0, 1e30}));
  cal->add_option("--scan", k.search.scan, "scan points (default 8 d + 1 for d parameters; 0: only the start)")->check(integer_rule("--scan", 0, 100000));
  cal->add_option("--starts", k.search.starts, "local searches from the best scan points (default 2)")->check(integer_rule("--starts", 0, 1000));
  cal->add_option("--max-evals", k.search.max_evals, "evaluations per local search (default 40)")->check(integer_rule("--max-evals", 1, 100000));
  cal->add_option("--profile-points", k.search.profile_points, "profile points per parameter (default 15; 0: no profiles)")
      ->check(integer_rule("--profile-points", 0, 10000));
  auto* factor = cal->add_option("--factor", o->factor, "profile interval: where the objective stays within FACTOR x the best (replaces --confidence)")
                     ->check(number_rule("--factor", {1, 1e30, true, false}));
  auto* confidence = cal->add_option("--confidence", k.search.confidence,
                                     "profile interval: the confidence interval at this probability under Gaussian noise (default 0.95)")
                         ->check(number_rule("--confidence", {0, 1, true, true}));
  cal->add_option("--refine", k.search.refine, "most bisection rounds refining each interval end (default 16; 0: none)")
      ->check(integer_rule("--refine", 0, 60));
  cal->add_option("--refine-to", k.search.refine_to,
                  "refine an interval end until its bracket is this fraction of the interval's width (default 1/64)")
      ->check(number_rule("--refine-to", {0, 1, true, true}));
  cal->add_option("--validate", k.validate, "a measurement of the same kind, not fitted: scored under the fitted values")->check(path_rule("--validate"));
  cal->add_option("--cache", k.cache,
                  "a file of evaluations: those it holds are not run again, new ones are added (resume a killed calibration, "
                  "or rerun with more profile points)")
      ->check(path_rule("--cache"));
  cal->add_option("--jobs", k.jobs, "parallel evaluations a process (default: all cores)")->check(integer_rule("--jobs", 0, 1024));
  cal->add_option("--out", k.out, "output directory (default out/<scene name>-calibrate)")->check(path_rule("--out"));
  cal->add_flag("--no-progress", o->no_progress, "no progress line on the terminal");
  cal->add_flag("--no-plot", o->no_plot, "skip DIR/calibration.png");
  add_common(cal, o->c);
  return {cal, [o, offset, factor, confidence] {
    if (factor->count() && confidence->count())
      throw InputError("command line", "--confidence", "give either --confidence (the interval at a probability) or --factor (the factor itself), not both");
    if (factor->count()) o->k.search.factor = o->factor;
    o->k.plot = !o->no_plot;
    o->k.progress = !o->no_progress;
    if (offset->count()) o->k.offset_max = o->offset_max;
    return calibrate(o->scene, o->c.overrides(), o->k);
  }};
}

/// An unknown subcommand is named as such (CLI11 would only say that a subcommand is required): prints the error
/// and returns false. `found`: argv[1] names a subcommand.
bool known_subcommand(CLI::App& app, int argc, char** argv, bool& found) {
  found = false;
  if (argc < 2 || argv[1][0] == '-') return true;
  std::string known;
  for (const auto* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    found = found || sub->get_name() == argv[1];
    known += (known.empty() ? "" : ", ") + sub->get_name();
  }
  if (!found)
    std::cerr << "imcol: error: " << InputError("command line", "", std::string("unknown subcommand '") + argv[1] + "' (expected " + known + ")").what() << "\n";
  return found;
}

/// The line and exit status of a command stopped by Ctrl-C.
int interrupted() {
  std::cerr << "imcol: interrupted\n";
  return kInterruptedExit;
}

/// The parsed command's action, with the exit status of each kind of failure (Ctrl-C: 130, nothing committed).
int run_action(const std::function<int()>& action) {
  SigintStop sigint;
  WorkScope scope({sigint.token(), nullptr});  // Ctrl-C stops the work at its next step
  try {
    const int status = action();
    return sigint.requested() ? interrupted() : status;
  } catch (const Interrupted&) {
    return interrupted();
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
    if (sigint.requested()) return interrupted();  // a stop that a library reported as its own failure (NLopt)
    std::cerr << "imcol: error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace

int run_cli(int argc, char** argv) {
  set_command_line(argc, argv);
  CLI::App app{"imcol: head-on collisions of spheres immersed in a viscous liquid"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("imcol ") + IMCOL_VERSION);
  const std::vector<Subcommand> subcommands = {add_run(app),     add_validate(app), add_bench(app),          add_effects(app),
                                               add_history(app), add_flow(app),     add_work_precision(app), add_sweep(app),
                                               add_laws(app),    add_scenes(app),   add_calibrate(app)};
  bool found = false;
  if (!known_subcommand(app, argc, argv, found)) return 2;

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // CLI11's own messages (a missing argument, an unknown option), on one line like every other error.
    std::cerr << "imcol: error: " << InputError("command line", "", e.what()).what() << " (see imcol " << (found ? std::string(argv[1]) + " " : "") << "--help)\n";
    return 2;
  } catch (const InputError& e) {  // an option's value (apps/option_rules.hpp)
    std::cerr << "imcol: error: " << e.what() << "\n";
    return 2;
  }
  for (const auto& sub : subcommands)
    if (*sub.cmd) return run_action(sub.run);
  return 1;
}

}  // namespace imcol
