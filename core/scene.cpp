// SPDX-License-Identifier: BSD-3-Clause
#include "core/scene.hpp"

#include <toml++/toml.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "core/errors.hpp"
#include "core/scene_keys.hpp"
#include "core/scene_kind.hpp"
#include "core/toml_reader.hpp"
#include "core/fluids.hpp"
#include "core/materials.hpp"

namespace imcol {

const char* to_string(Effect e) {
  switch (e) {
    case Effect::drag: return "drag";
    case Effect::lubrication: return "lubrication";
    case Effect::added_mass: return "added_mass";
    case Effect::elastic: return "elastic";
    case Effect::gravity: return "gravity";
    case Effect::history: return "history";
    case Effect::flow: return "flow";
  }
  return "?";
}

namespace {
constexpr Effect kEffects[] = {Effect::drag, Effect::lubrication, Effect::added_mass, Effect::elastic, Effect::gravity, Effect::history, Effect::flow};
}  // namespace

std::optional<Effect> effect_from_string(const std::string& s) {
  for (Effect e : kEffects)
    if (s == to_string(e)) return e;
  return std::nullopt;
}

std::vector<std::string> effect_names() {
  std::vector<std::string> out;
  for (Effect e : kEffects) out.emplace_back(to_string(e));
  return out;
}

namespace {

using Reader = TableReader;

constexpr double kMaxViscosity = 1e12;  // Pa s

/// Material properties: either `material = "name"` or inline values; inline values override the material.
void read_solid(Reader& r, Solid& s, bool need_density) {
  if (auto name = r.string("material")) {
    const Material* m = MaterialTable::builtin().find(*name);
    if (!m)
      r.fail("material", "unknown material '" + *name + "' (known: " + MaterialTable::builtin().names() + ")" +
                             did_you_mean(*name, MaterialTable::builtin().name_list()));
    s.material = *name;
    s.density = m->density;
    s.youngs_modulus = m->youngs_modulus;
    s.poisson_ratio = m->poisson_ratio;
    s.e_dry = m->e_dry;
    s.roughness = m->roughness;
  }
  const bool have_material = !s.material.empty();
  auto prop = [&](const char* key, double& field) {
    if (auto v = r.number(key)) field = *v;
    else if (!have_material) r.fail(key, "missing (give `material` or inline properties)");
  };
  if (need_density) prop("density", s.density);
  prop("youngs_modulus", s.youngs_modulus);
  prop("poisson_ratio", s.poisson_ratio);
  if (auto v = r.number("e_dry")) s.e_dry = *v;
  if (need_density) r.positive("density", s.density);
  r.positive("youngs_modulus", s.youngs_modulus);
  r.in_range("poisson_ratio", s.poisson_ratio, -1.0, 0.5, true, false);
  if (s.e_dry) r.in_range("e_dry", *s.e_dry, 0.0, 1.0, false, false);
}

toml::array* array_at(toml::node* n) { return n ? n->as_array() : nullptr; }

/// An override that names an array where a table belongs ('sphere.velocity'): the error names its elements and the
/// key with an index ('sphere[0].velocity'). `at`: the index of the segment after the array's name.
[[noreturn]] void array_needs_index(const Override& ov, const std::vector<std::string>& seg, std::size_t at, const toml::array& arr) {
  std::string head;  // the key up to the array, as written with indices
  for (std::size_t j = 0; j < at; ++j) {
    const bool index = !seg[j].empty() && seg[j].find_first_not_of("0123456789") == std::string::npos;
    head += index ? "[" + seg[j] + "]" : (head.empty() ? "" : ".") + seg[j];
  }
  std::string tail;
  for (std::size_t j = at; j < seg.size(); ++j) tail += "." + seg[j];
  std::string elements = head + "[0]";
  if (arr.size() == 2) elements += " and " + head + "[1]";
  if (arr.size() > 2) elements += " to " + head + "[" + std::to_string(arr.size() - 1) + "]";
  const std::string lead = seg[at - 1] == "sphere" ? "a scene's spheres are " : "'" + head + "' is an array: its elements are ";
  throw InputError("--set", ov.key, lead + elements + ": use '" + head + "[0]" + tail + "'");
}

void apply_override(toml::table& root, const Override& ov) {
  const std::vector<std::string> seg = key_path(ov.key);
  if (seg.empty()) throw InputError("--set", ov.key, "empty key");

  toml::table parsed;
  try {
    parsed = toml::parse("v = " + ov.value);
  } catch (const toml::parse_error&) {
    parsed = toml::table{{"v", ov.value}};  // a bare word is a string
  }

  toml::node* here = &root;
  for (std::size_t i = 0; i + 1 < seg.size(); ++i) {
    const std::string& s = seg[i];
    if (auto* arr = array_at(here)) {
      char* end = nullptr;
      long idx = std::strtol(s.c_str(), &end, 10);
      if (*end != '\0' && !arr->empty() && arr->is_array_of_tables()) array_needs_index(ov, seg, i, *arr);
      if (*end != '\0' || idx < 0 || static_cast<std::size_t>(idx) >= arr->size())
        throw InputError("--set", ov.key, "no element '" + s + "' in this array");
      here = arr->get(static_cast<std::size_t>(idx));
    } else if (auto* tbl = here->as_table()) {
      if (!tbl->contains(s)) tbl->insert(s, toml::table{});
      here = tbl->get(s);
    } else {
      throw InputError("--set", ov.key, "'" + s + "' is not a table");
    }
  }
  auto* tbl = here->as_table();
  if (const auto* arr = here->as_array(); arr && !arr->empty() && arr->is_array_of_tables()) array_needs_index(ov, seg, seg.size() - 1, *arr);
  if (!tbl) throw InputError("--set", ov.key, "cannot set a value inside a non-table");
  parsed["v"].node()->visit([&](auto&& value) { tbl->insert_or_assign(seg.back(), value); });
}

/// `name` and `description` (top level).
void read_name(Reader& top, Scene& sc) {
  if (auto v = top.string("name")) {
    if (v->empty() || v->find_first_of("/\\") != std::string::npos || *v == "." || *v == "..")
      top.fail("name", "must be a plain file name (it names the default output directory)");
    if (v->size() > 200) top.fail("name", "must be at most 200 bytes (it names the default output directory; got " + std::to_string(v->size()) + ")");
    for (unsigned char c : *v)
      if (c < 0x20 || c == 0x7f) top.fail("name", "must not contain control characters (it names the default output directory)");
    sc.name = *v;
  }
  if (auto v = top.string("description")) sc.description = *v;
}

/// The value of one property of the named liquid `e` at (w, t), after checking the correlation's ranges.
double table_value(Reader& r, const FluidEntry& e, const FluidProperty& p, const char* property, double w, double t) {
  if (p.value) return *p.value;
  auto range = [&](const char* key, double v, double lo, double hi, const char* unit) {
    if (!(v >= lo && v <= hi))
      r.fail(key, fmt_number(v) + unit + " is outside [" + fmt_number(lo) + ", " + fmt_number(hi) + "]" + unit + ", the range of the " +
                      e.name + " " + property + " correlation (" + p.source + "); give `" + property + "` inline instead");
  };
  range("temperature", t, p.t_min, p.t_max, " °C");
  if (p.uses_mass_fraction()) range("mass_fraction", w, *p.w_min, *p.w_max, "");
  return p.at(w, t);
}

/// `fluid = NAME` (data/fluids.csv) with `mass_fraction`/`temperature` where its correlations take them, and inline
/// `density`/`viscosity`, which override the table's values.
void read_fluid(Reader& top, Scene& sc) {
  const auto* f = top.table("fluid");
  if (!f) return;
  Reader r(*f, "fluid", sc.path, scene_keys::fluid);
  FluidSpec fl;
  const auto density = r.number("density"), viscosity = r.number("viscosity");
  const auto w = r.number("mass_fraction"), t = r.number("temperature");
  const FluidEntry* e = nullptr;
  if (auto name = r.string("fluid")) {
    e = FluidTable::builtin().find(*name);
    if (!e)
      r.fail("fluid", "unknown fluid '" + *name + "' (known: " + FluidTable::builtin().names() + ")" +
                          did_you_mean(*name, FluidTable::builtin().name_list()));
    fl.name = *name;
  }
  if (w && !(e && e->takes_mass_fraction()))
    r.fail("mass_fraction", e ? "'" + e->name + "' is not given by mass fraction (only glycerol-water is)"
                              : std::string("needs `fluid` naming a mixture given by mass fraction (glycerol-water)"));
  if (t && !(e && e->takes_temperature()))
    r.fail("temperature", e ? "'" + e->name + "' has fixed values (as its experiment reports them): give density and viscosity inline for another temperature"
                            : std::string("needs `fluid` naming a liquid whose properties depend on temperature (water, glycerol-water)"));
  if (e && e->takes_mass_fraction() && !w)
    throw InputError(r.where(nullptr), "fluid.mass_fraction", "missing (required for " + e->name + ": the glycerol mass fraction, 0 to 1)");
  constexpr double kDefaultTemperatureC = 20.0;
  if (e && e->takes_temperature()) fl.temperature = t.value_or(kDefaultTemperatureC);
  if (w) {
    r.in_range("mass_fraction", *w, 0.0, 1.0, false, false);
    fl.mass_fraction = *w;
  }
  auto property = [&](const char* key, const std::optional<double>& inline_value, const FluidProperty* p, double& field,
                      std::string& source) {
    if (inline_value) {
      field = *inline_value;
      source = "scene";
    } else if (e) {
      field = table_value(r, *e, *p, key, fl.mass_fraction.value_or(0.0), fl.temperature.value_or(kDefaultTemperatureC));
      source = p->source;
    } else {
      throw InputError(r.where(nullptr), r.full(key), "missing (required without `fluid`; or name a liquid: fluid = \"water\")");
    }
  };
  property("density", density, e ? &e->density : nullptr, fl.density, fl.density_source);
  property("viscosity", viscosity, e ? &e->viscosity : nullptr, fl.viscosity, fl.viscosity_source);
  r.positive("density", fl.density);
  r.positive("viscosity", fl.viscosity);
  // Above 1e12 Pa s (glass at its transition) a "liquid" is a solid on any laboratory time scale; the drag and
  // history forces would also dwarf every other force by more than double precision resolves.
  if (fl.viscosity > kMaxViscosity)
    r.fail("viscosity", "must be at most " + fmt_number(kMaxViscosity) + " Pa s (glass at its transition; got " +
                            fmt_number(fl.viscosity) + "): a stiffer material is a solid, not a liquid");
  r.finish();
  sc.fluid = fl;
}

/// Positions are held to 16 digits and the gap is their difference: beyond 1e6 D from z = 0 (D the impact
/// sphere's diameter) it could no longer resolve a contact (indentations of ~1e-5 D) to better than 1e-5 of it.
void position_near_origin(Reader& r, double z, double D) {
  if (std::abs(z) > 1e6 * D)
    r.fail("position", "must lie within 1e6 impact-sphere diameters (" + fmt_number(1e6 * D) + " m) of z = 0 (got " +
                           fmt_number(z) + "): farther out the gap loses its digits");
}

/// `[[sphere]]`: one or two; the impact sphere first.
void read_spheres(Reader& top, Scene& sc) {
  const toml::node* sph = top.node("sphere");
  if (!sph) throw InputError(sc.path, "sphere", "missing (give one or two [[sphere]] tables)");
  const toml::array* arr = sph->as_array();
  if (!arr || !arr->is_array_of_tables()) top.fail("sphere", "must be an array of tables ([[sphere]])");
  if (arr->empty() || arr->size() > 2) top.fail("sphere", "give one or two spheres (got " + std::to_string(arr->size()) + ")");
  for (std::size_t i = 0; i < arr->size(); ++i) {
    Reader r(*arr->get(i)->as_table(), "sphere[" + std::to_string(i) + "]", sc.path, scene_keys::sphere);
    SphereSpec s;
    read_solid(r, s, true);
    s.diameter = r.required_positive("diameter");
    s.position = r.required_number("position");
    position_near_origin(r, s.position, sc.spheres.empty() ? s.diameter : sc.spheres[0].diameter);
    s.velocity = r.number("velocity", 0.0);
    const double mass = s.density * std::pow(s.diameter, 3) * 3.141592653589793 / 6;
    if (!(mass > 0) || !std::isfinite(mass)) r.fail("diameter", "gives a sphere mass that double precision cannot hold");
    r.finish();
    sc.spheres.push_back(s);
  }
}

void read_wall(Reader& top, Scene& sc) {
  const auto* w = top.table("wall");
  if (!w) return;
  if (sc.two_spheres()) top.fail("wall", "a scene has either a target sphere or a wall, not both");
  Reader r(*w, "wall", sc.path, scene_keys::wall);
  WallSpec wall;
  read_solid(r, wall, false);
  wall.position = r.required_number("position");
  position_near_origin(r, wall.position, sc.spheres[0].diameter);
  r.finish();
  sc.wall = wall;
}

/// `effects`: an explicit list, or everything that applies to the scene.
void read_effects(Reader& top, Scene& sc) {
  if (const toml::node* n = top.node("effects")) {
    const toml::array* ea = n->as_array();
    if (!ea) top.fail("effects", "must be an array of names");
    for (const auto& item : *ea) {
      auto name = item.value<std::string>();
      if (!name) top.fail("effects", "must be an array of strings");
      auto e = effect_from_string(*name);
      if (!e) {
        std::string list;
        for (const auto& n : effect_names()) list += (list.empty() ? "" : ", ") + n;
        top.fail("effects", "unknown effect '" + *name + "' (expected " + list + ")" + did_you_mean(*name, effect_names()));
      }
      sc.effects.insert(*e);
    }
    return;
  }
  // The seed's whole model (f_THR = f_D + f_AM + f_H, lubrication, the contact ramp), gravity where the scene sets it.
  if (sc.has_target()) sc.effects.insert(Effect::elastic);
  if (sc.fluid) {
    sc.effects.insert(Effect::drag);
    if (sc.has_target()) sc.effects.insert(Effect::lubrication);
    sc.effects.insert(Effect::added_mass);
    sc.effects.insert(Effect::history);
  }
  if (top.has("gravity")) sc.effects.insert(Effect::gravity);
}

/// The effects against the fluid and the target.
void check_effects(Reader& top, const Scene& sc) {
  for (Effect e : {Effect::drag, Effect::lubrication, Effect::added_mass, Effect::history, Effect::flow})
    if (sc.has(e) && !sc.fluid)
      top.fail("effects", std::string("effect '") + to_string(e) + "' needs a [fluid] table");
  if ((sc.has(Effect::lubrication) || sc.has(Effect::elastic)) && !sc.has_target())
    top.fail("effects", "lubrication and elastic need a target sphere or a [wall]");
  if (sc.has_target() && !sc.has(Effect::elastic))
    top.fail("effects", "a target sphere or wall needs 'elastic' (without it the solids would pass through each other)");
}

void read_drag(Reader& top, Scene& sc) {
  const auto* t = top.table("drag");
  if (!t) return;
  Reader r(*t, "drag", sc.path, scene_keys::drag);
  r.choice("law", sc.drag.law);
  r.finish();
}

/// The gap at which two surfaces' asperities touch: the sum of the materials' roughness heights (m). An input error on
/// lubrication.limit when neither surface has one.
double materials_roughness(Reader& r, const Scene& sc) {
  std::optional<double> a = sc.spheres[0].roughness, b = sc.wall ? sc.wall->roughness : sc.spheres[1].roughness;
  if (!a && !b)
    r.fail("limit", "'roughness' needs the surfaces' roughness height: give lubrication.roughness (m), or materials with roughness_m"
                     " (data/materials.csv)");
  return a.value_or(0.0) + b.value_or(0.0);
}

/// Default model: brenner for a wall, asymptotic for a pair.
void read_lubrication(Reader& top, Scene& sc) {
  auto& l = sc.lubrication;
  l.model = sc.wall ? LubricationModel::brenner : LubricationModel::asymptotic;
  const auto* t = top.table("lubrication");
  if (!t) return;
  Reader r(*t, "lubrication", sc.path, scene_keys::lubrication);
  r.choice("model", l.model);
  if (l.model == LubricationModel::brenner && sc.two_spheres())
    r.fail("model", "'brenner' is the sphere-wall series; use 'asymptotic' or 'seed' for two spheres");
  l.cutoff = r.number("cutoff", l.cutoff);
  r.positive("cutoff", l.cutoff);
  // h_c is the asymptotic law's range; the other laws act at every gap and would ignore it.
  if (r.has("h_c") && l.model != LubricationModel::asymptotic)
    r.fail("h_c", std::string("applies only to model = 'asymptotic' (the model is '") + to_string(l.model) + "', which acts at every gap)");
  l.h_c = r.number("h_c", l.h_c);
  r.positive("h_c", l.h_c);
  r.choice("limit", l.limit);
  if (r.has("roughness") && l.limit != LubricationLimit::roughness) r.fail("roughness", "applies only to limit = 'roughness'");
  l.roughness = r.number("roughness", l.roughness);
  if (r.has("roughness")) r.positive("roughness", l.roughness);
  if (l.limit == LubricationLimit::roughness && l.roughness < 0) l.roughness = materials_roughness(r, sc);
  // Down to the roughness height the film is resolved: the smooth bound then only keeps a trial state below it finite.
  if (l.limit == LubricationLimit::roughness && !r.has("cutoff")) l.cutoff = 0.1 * l.roughness / sc.spheres[0].diameter;
  r.finish();
}

void read_added_mass(Reader& top, Scene& sc) {
  const auto* t = top.table("added_mass");
  if (!t) return;
  Reader r(*t, "added_mass", sc.path, scene_keys::added_mass);
  r.choice("model", sc.added_mass.model);
  sc.added_mass.dw_floor = r.number("dw_floor", sc.added_mass.dw_floor);
  if (r.has("dw_floor")) r.positive("dw_floor", sc.added_mass.dw_floor);
  r.finish();
}

/// The [contact] table's keys (none without it).
void read_contact_table(const toml::table* t, Scene& sc) {
  auto& c = sc.contact;
  const bool rough = sc.lubrication.limit == LubricationLimit::roughness;
  if (!t) return;
  Reader r(*t, "contact", sc.path, scene_keys::contact);
  c.delta_ss = r.number("delta_ss", c.delta_ss);
  r.in_range("delta_ss", c.delta_ss, 0.0, 1.0, true, true);  // units of D
  if (rough && r.has("delta_ss"))
    r.fail("delta_ss", "with lubrication.limit = 'roughness' the contact starts at the roughness height: set lubrication.roughness instead");
  c.delta_sl = r.number("delta_sl", c.delta_sl);
  r.positive("delta_sl", c.delta_sl);
  c.e_dry = r.number("e_dry", -1.0);
  if (r.has("e_dry")) r.in_range("e_dry", c.e_dry, 0.0, 1.0, false, false);
  c.beta = r.number("beta", 0.0);
  if (r.has("beta")) r.positive("beta", c.beta);
  r.choice("law", c.law);
  if (r.has("beta") && c.law != ContactLawKind::ramp) r.fail("beta", "applies only to law = 'ramp'");
  r.finish();
}

/// Default delta_ss: 0.017 D for a wall, 0.024 D for a pair.
void read_contact(Reader& top, Scene& sc) {
  auto& c = sc.contact;
  c.delta_ss = sc.wall ? 0.017 : 0.024;
  const bool rough = sc.lubrication.limit == LubricationLimit::roughness;
  if (rough) c.delta_ss = sc.lubrication.roughness / sc.spheres[0].diameter;  // the solids touch at the roughness height
  read_contact_table(top.table("contact"), sc);
  if (rough && c.law != ContactLawKind::hertz)
    throw InputError(sc.path, "lubrication.limit", "'roughness' needs contact.law = \"hertz\": the solids touch at the roughness height");
}

void read_history(Reader& top, Scene& sc) {
  const auto* t = top.table("history");
  if (!t) return;
  Reader r(*t, "history", sc.path, scene_keys::history);
  if (!sc.has(Effect::history)) r.fail("kernel", "a [history] table needs the 'history' effect in `effects`");
  auto& h = sc.history;
  r.choice("kernel", h.kernel);
  r.choice("evaluator", h.evaluator);
  h.tolerance = r.number("tolerance", h.tolerance);
  r.in_range("tolerance", h.tolerance, 1e-13, 0.1, false, true);
  if (auto v = r.integer("modes")) h.modes = *v;
  if (r.has("modes") && h.modes != 0 && (h.modes < 2 || h.modes > 400))
    r.fail("modes", "must be 0 (automatic, from tolerance) or in [2, 400] (got " + std::to_string(h.modes) + ")");
  h.min_lag = r.number("min_lag", 0.0);
  if (h.min_lag != 0) r.positive("min_lag", h.min_lag);  // 0 = automatic
  h.horizon = r.number("horizon", 0.0);
  if (h.horizon != 0) r.positive("horizon", h.horizon);  // 0 = solver.t_end
  r.choice("start", h.start);
  r.choice("reynolds", h.reynolds);
  r.choice("wall_correction", h.wall_correction);
  h.direct_step = r.number("direct_step", 0.0);
  if (h.direct_step != 0) r.positive("direct_step", h.direct_step);  // 0 = automatic
  h.interpolate_outputs = r.boolean("interpolate_outputs", h.interpolate_outputs);
  if (h.min_lag > 0 && h.horizon > 0 && h.horizon < 10 * h.min_lag)
    r.fail("horizon", "must be at least 10 × min_lag (" + fmt_number(h.min_lag) + " s)");
  r.finish();
}

void read_solver(Reader& top, Scene& sc) {
  const auto* t = top.table("solver");
  if (!t) return;
  Reader r(*t, "solver", sc.path, scene_keys::solver);
  auto& s = sc.solver;
  r.choice("integrator", s.integrator);
  r.choice("linear_solver", s.linear_solver);
  const auto ls = s.linear_solver;
  if ((ls == LinearSolverChoice::gmres || ls == LinearSolverChoice::schur) && s.integrator != IntegratorMethod::cvode)
    r.fail("linear_solver", std::string("'") + to_string(ls) + "' is implemented for the cvode integrator only");
  // Their preconditioner works on the memory modes, which are integrator states only with the soe evaluator.
  if ((ls == LinearSolverChoice::gmres || ls == LinearSolverChoice::schur) &&
      !(sc.has(Effect::history) && sc.history.evaluator == HistoryEvaluator::soe))
    r.fail("linear_solver", std::string("'") + to_string(ls) +
                                "' needs memory modes in the integrator's state: the history effect with history.evaluator = \"soe\" (auto picks it where it applies)");
  s.krylov_tol = r.number("krylov_tol", s.krylov_tol);
  r.in_range("krylov_tol", s.krylov_tol, 0.0, 1.0, true, false);
  s.rtol = r.number("rtol", s.rtol);
  s.atol = r.number("atol", s.atol);
  s.t_end = r.number("t_end", s.t_end);
  r.positive("t_end", s.t_end);
  s.max_step = r.number("max_step", s.max_step);
  if (s.max_step != 0) r.positive("max_step", s.max_step);  // 0 = automatic
  if (auto v = r.integer("max_steps")) s.max_steps = *v;
  if (s.max_steps < 1) r.fail("max_steps", "must be >= 1");
  s.step_budget = r.number("step_budget", s.step_budget);
  r.positive("step_budget", s.step_budget);
  // Tolerances: rtol must be positive and above what double precision can deliver.
  r.in_range("rtol", s.rtol, 1e-14, 1.0, false, true);
  r.in_range("atol", s.atol, 0.0, 1.0, true, true);
  r.finish();
}

/// Default instant_gap: contact.delta_ss.
void read_measure(Reader& top, Scene& sc) {
  auto& m = sc.measure;
  m.e = sc.spheres.size() == 2 ? EMeasure::yang_hunt_2006 : EMeasure::joseph_2001;
  if (const auto* t = top.table("measure")) {
    Reader r(*t, "measure", sc.path, scene_keys::measure);
    m.window = r.number("window", m.window);
    r.positive("window", m.window);
    m.instant_gap = r.number("instant_gap", -1.0);
    if (r.has("instant_gap")) r.positive("instant_gap", m.instant_gap);
    m.stall_fraction = r.number("stall_fraction", m.stall_fraction);
    r.in_range("stall_fraction", m.stall_fraction, 0.0, 1.0, false, true);
    r.choice("bounces", m.bounces);
    m.fit_distance = r.number("fit_distance", m.fit_distance);
    r.positive("fit_distance", m.fit_distance);
    m.at_gap = r.number("at_gap", m.at_gap);
    r.positive("at_gap", m.at_gap);
    m.e_given = r.has("e");
    r.choice("e", m.e);
    m.ends_distance = r.number("ends_distance", m.ends_distance);
    r.in_range("ends_distance", m.ends_distance, 0.0, 10.0, true, false);
    m.ends_speed_change = r.number("ends_speed_change", m.ends_speed_change);
    r.in_range("ends_speed_change", m.ends_speed_change, 0.0, 1.0, true, false);
    m.ends_tolerance = r.number("ends_tolerance", m.ends_tolerance);
    r.positive("ends_tolerance", m.ends_tolerance);
    const long spw = r.integer("samples_per_window", m.samples_per_window);
    if (spw < 4 || spw > 10000) r.fail("samples_per_window", "must lie in [4, 10000] (got " + std::to_string(spw) + ")");
    m.samples_per_window = static_cast<int>(spw);
    m.disagreement = r.number("disagreement", m.disagreement);
    r.in_range("disagreement", m.disagreement, 0.0, 1.0, true, false);
    m.max_samples = r.number("max_samples", m.max_samples);
    r.in_range("max_samples", m.max_samples, 1e3, 1e9, false, false);
    m.energy_budget = r.boolean("energy_budget", m.energy_budget);
    r.finish();
  }
  if (m.instant_gap < 0) m.instant_gap = sc.contact.delta_ss;
}

void read_flow(Reader& top, Scene& sc) {
  const auto* t = top.table("flow");
  if (!t) return;
  Reader r(*t, "flow", sc.path, scene_keys::flow);
  if (!sc.has(Effect::flow)) top.fail("flow", "a [flow] table needs the 'flow' effect in `effects`");
  read_flow_spec(r, sc.flow);
  if (sc.flow.dt > sc.solver.t_end)
    r.fail("dt", "a flow step of " + fmt_number(sc.flow.dt) + " s is longer than the run (solver.t_end = " +
                     fmt_number(sc.solver.t_end) + " s)");
  if (!sc.flow.added_mass_estimate && sc.has(Effect::added_mass))
    r.fail("added_mass_estimate", "false needs a scene without the 'added_mass' effect (its added mass is implicit anyway)");
}

/// Default dt: measure.window / 100.
void read_output(Reader& top, Scene& sc) {
  if (const auto* t = top.table("output")) {
    Reader r(*t, "output", sc.path, scene_keys::output);
    sc.output.dt = r.number("dt", 0.0);
    if (r.has("dt")) r.positive("dt", sc.output.dt);
    r.finish();
  }
  if (sc.output.dt == 0) sc.output.dt = sc.measure.window / 100.0;
  if (sc.solver.t_end / sc.output.dt > 1e7)
    throw InputError(sc.path, top.has("output") ? "output.dt" : "measure.window",
                     "t_end / output.dt = " + fmt_number(sc.solver.t_end / sc.output.dt) +
                         " samples exceeds 1e7: raise output.dt (default window/100) or lower solver.t_end");
}

/// The initial gap to the target: positive, and outside the contact zone unless the solids approach.
void check_start_gap(const Scene& sc, const std::string& key, double gap) {
  const double D = sc.spheres[0].diameter;
  const double u_rel0 = sc.spheres[0].velocity - (sc.two_spheres() ? sc.spheres[1].velocity : 0.0);
  if (gap <= 0) {
    if (sc.two_spheres())
      throw InputError(sc.path, key, "spheres overlap or touch (gap " + fmt_number(gap) + " m); the target must lie at larger z");
    throw InputError(sc.path, key, "sphere overlaps or touches the wall (gap " + fmt_number(gap) + " m); the wall must lie at larger z");
  }
  if (sc.has(Effect::elastic) && gap <= sc.contact.delta_ss * D && !(u_rel0 > 0))
    throw InputError(sc.path, key, "initial gap " + fmt_number(gap) + " m is inside the contact zone delta_ss*D = " + fmt_number(sc.contact.delta_ss * D) + " m and the solids are not approaching: the contact force is undefined");
}

/// Checks across tables, once every table is read: the lubrication cutoff inside the contact zone, the target ahead
/// of the impact sphere and not touching it, a dry restitution for the contact.
void check_scene(const Scene& sc) {
  if (sc.has(Effect::lubrication) && sc.lubrication.cutoff >= sc.contact.delta_ss)
    throw InputError(sc.path, "lubrication.cutoff", "must be smaller than contact.delta_ss (" + fmt_number(sc.contact.delta_ss) + " D)");
  const auto& s1 = sc.spheres[0];
  if (sc.two_spheres()) {
    const auto& s2 = sc.spheres[1];
    check_start_gap(sc, "sphere[1].position", s2.position - s1.position - 0.5 * (s1.diameter + s2.diameter));
  } else if (sc.wall) {
    check_start_gap(sc, "wall.position", sc.wall->position - s1.position - 0.5 * s1.diameter);
  }
  if (sc.has(Effect::elastic)) {
    bool any = sc.contact.e_dry >= 0 || s1.e_dry || (sc.two_spheres() && sc.spheres[1].e_dry) || (sc.wall && sc.wall->e_dry);
    if (!any) throw InputError(sc.path, "contact.e_dry", "missing: no material in the scene gives a dry restitution");
  }
}

}  // namespace

std::vector<std::string> key_path(const std::string& key) {
  std::vector<std::string> seg;
  std::string cur;
  for (char ch : key) {
    if (ch == '.' || ch == '[' || ch == ']') {
      if (!cur.empty()) seg.push_back(std::move(cur));
      cur.clear();
    } else {
      cur += ch;
    }
  }
  if (!cur.empty()) seg.push_back(std::move(cur));
  return seg;
}

Override parse_override(const std::string& text) {
  auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) throw InputError("--set", text, "expected key=value");
  // TOML would end the value at a line break and read what follows as further keys: one --set sets one key.
  if (text.find_first_of("\n\r") != std::string::npos)
    throw InputError("--set", text.substr(0, eq), "the value holds a line break (one --set sets one key; give each key its own --set)");
  return {text.substr(0, eq), text.substr(eq + 1)};
}

Scene load_scene(const std::string& path, const std::vector<Override>& overrides) {
  return parse_scene(read_scene_file(path), path, overrides);
}

Scene parse_scene(const std::string& text, const std::string& path, const std::vector<Override>& overrides) {
  toml::table root;
  try {
    root = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw InputError(path + ":" + std::to_string(e.source().begin.line), "",
                     "TOML syntax error: " + std::string(e.description()));
  }
  if (scene_kind(root) == SceneKind::flow) throw InputError(path, "", other_scene_kind_message(SceneKind::flow));
  for (const auto& ov : overrides) apply_override(root, ov);

  Scene sc;
  sc.path = path;
  sc.name = std::filesystem::path(path).stem().string();
  Reader top(root, "", path, scene_keys::top);
  read_name(top, sc);
  read_fluid(top, sc);
  read_spheres(top, sc);
  read_wall(top, sc);
  if (auto g = top.number("gravity")) sc.gravity = *g;
  read_effects(top, sc);
  check_effects(top, sc);
  read_drag(top, sc);
  read_lubrication(top, sc);
  read_added_mass(top, sc);
  read_contact(top, sc);
  read_history(top, sc);
  read_solver(top, sc);
  read_measure(top, sc);
  read_flow(top, sc);
  read_output(top, sc);
  top.finish();
  check_scene(sc);
  return sc;
}

}  // namespace imcol
