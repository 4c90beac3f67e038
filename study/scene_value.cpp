// SPDX-License-Identifier: BSD-3-Clause
#include "study/scene_value.hpp"

#include <toml++/toml.h>

#include <regex>

#include "core/toml_reader.hpp"

namespace imcol::study {

namespace {

std::optional<double> solid_value(const Solid& s, const std::string& name) {
  if (name == "density") return s.density;
  if (name == "youngs_modulus") return s.youngs_modulus;
  if (name == "poisson_ratio") return s.poisson_ratio;
  if (name == "e_dry") return s.e_dry;
  return std::nullopt;
}

/// The keys a Scene holds resolved (materials and liquids looked up, defaults filled in).
std::optional<double> resolved_value(const Scene& sc, const std::string& key) {
  static const std::regex sphere(R"(sphere\[(\d+)\]\.(\w+))");
  std::smatch m;
  if (std::regex_match(key, m, sphere)) {
    const std::size_t i = std::stoul(m[1]);
    if (i >= sc.spheres.size()) return std::nullopt;
    const SphereSpec& s = sc.spheres[i];
    const std::string name = m[2];
    if (name == "diameter") return s.diameter;
    if (name == "position") return s.position;
    if (name == "velocity") return s.velocity;
    return solid_value(s, name);
  }
  if (key.rfind("wall.", 0) == 0 && sc.wall) {
    if (key == "wall.position") return sc.wall->position;
    return solid_value(*sc.wall, key.substr(5));
  }
  if (sc.fluid && key == "fluid.density") return sc.fluid->density;
  if (sc.fluid && key == "fluid.viscosity") return sc.fluid->viscosity;
  if (key == "contact.delta_ss") return sc.contact.delta_ss;
  if (key == "contact.delta_sl") return sc.contact.delta_sl;
  if (key == "contact.beta") return sc.contact.beta;
  if (key == "contact.e_dry" && sc.contact.e_dry >= 0) return sc.contact.e_dry;
  if (key == "gravity") return sc.gravity;
  return std::nullopt;
}

std::optional<double> toml_number(const toml::node* n) {
  if (!n) return std::nullopt;
  if (n->is_integer()) return static_cast<double>(*n->value<int64_t>());
  if (n->is_floating_point()) return *n->value<double>();
  return std::nullopt;
}

}  // namespace

std::optional<double> scene_value(const std::string& scene_path, const std::vector<Override>& overrides, const Scene& base,
                                  const std::string& key) {
  if (auto v = resolved_value(base, key)) return v;
  try {
    for (auto o = overrides.rbegin(); o != overrides.rend(); ++o)
      if (o->key == key) {
        const toml::table t = toml::parse("v = " + o->value);
        return toml_number(t.get("v"));
      }
    const toml::table file = toml::parse(read_scene_file(scene_path), scene_path);
    return toml_number(file.at_path(key).node());
  } catch (const std::exception&) {  // the scene was read already: a key this cannot find has no value here
    return std::nullopt;
  }
}

}  // namespace imcol::study
