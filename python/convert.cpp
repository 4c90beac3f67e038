// SPDX-License-Identifier: BSD-3-Clause
#include "python/convert.hpp"

#include <cmath>
#include <cstdint>

namespace py = pybind11;

namespace imcol::python {

py::object to_python(const nlohmann::ordered_json& j) {
  using T = nlohmann::ordered_json::value_t;
  switch (j.type()) {
    case T::null:
    case T::discarded: return py::none();
    case T::boolean: return py::bool_(j.get<bool>());
    case T::number_integer: return py::int_(j.get<std::int64_t>());
    case T::number_unsigned: return py::int_(j.get<std::uint64_t>());
    case T::number_float: return py::float_(j.get<double>());
    case T::string: return py::str(j.get_ref<const std::string&>());
    case T::binary: {
      const auto& b = j.get_binary();
      return py::bytes(reinterpret_cast<const char*>(b.data()), b.size());
    }
    case T::array: {
      py::list out;
      for (const auto& v : j) out.append(to_python(v));
      return out;
    }
    case T::object: {
      py::dict out;
      for (const auto& [k, v] : j.items()) out[py::str(k)] = to_python(v);
      return out;
    }
  }
  return py::none();
}

namespace convert_impl {  // this file's helpers: named, as the module is one unity unit

/// A string as a TOML basic string (quoted, escaped): JSON strings are TOML basic strings.
std::string toml_string(const std::string& s) { return nlohmann::json(s).dump(); }

constexpr int kMaxDepth = 32;  // lists in lists: a list that holds itself ends here, not in a stack overflow

/// Whether `v` is a NumPy scalar or array (or another array library's value with NumPy's `dtype` and `tolist`).
bool is_array_like(const py::handle& v) { return py::hasattr(v, "dtype") && py::hasattr(v, "tolist"); }

std::string scalar_text(const py::handle& v, bool bare_str, int depth = 0) {
  if (py::isinstance<py::bool_>(v)) return v.cast<bool>() ? "true" : "false";
  // int and float subclasses (an IntEnum, numpy.float64) by their value: their own str/repr may be other text
  if (py::isinstance<py::int_>(v)) return py::str(py::reinterpret_steal<py::object>(PyNumber_Long(v.ptr()))).cast<std::string>();
  if (py::isinstance<py::float_>(v)) {
    const double x = v.cast<double>();
    if (std::isnan(x)) return "nan";
    if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
    std::string r = py::repr(py::float_(x)).cast<std::string>();  // shortest text that reads back as the same double
    if (r.find_first_of(".eE") == std::string::npos) r += ".0";
    return r;
  }
  if (py::isinstance<py::str>(v)) return bare_str ? v.cast<std::string>() : toml_string(v.cast<std::string>());
  if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) {
    if (depth >= kMaxDepth) throw py::value_error("a scene value nests lists more than " + std::to_string(kMaxDepth) + " deep");
    std::string s = "[";
    bool first = true;
    for (const auto& e : v) {
      s += (first ? "" : ", ") + scalar_text(e, false, depth + 1);
      first = false;
    }
    return s + "]";
  }
  // NumPy scalars and arrays by their kind, as tolist() gives them: numpy.bool_ a bool, integers an int, floats a
  // float (a float32 its exact value), arrays lists (a 0-d array its element). Other kinds (complex, dates) are refused.
  if (is_array_like(v)) {
    const py::object plain = v.attr("tolist")();
    if (py::isinstance<py::list>(plain) || py::isinstance<py::bool_>(plain) || py::isinstance<py::int_>(plain) ||
        py::isinstance<py::float_>(plain) || py::isinstance<py::str>(plain))
      return scalar_text(plain, bare_str, depth);
  } else if (py::hasattr(v, "__float__")) {  // other numbers: as a float if they convert to one
    return scalar_text(py::float_(v.cast<py::object>()), bare_str);
  }
  throw py::type_error("a scene value must be a str, bool, int, float or a list of them (got " +
                       py::str(py::type::of(v).attr("__name__")).cast<std::string>() + ")");
}

}  // namespace convert_impl

std::string toml_value_text(const py::handle& value) { return convert_impl::scalar_text(value, true); }

std::vector<Override> solver_overrides(const std::optional<py::object>& rtol, const std::optional<py::object>& atol,
                                       const std::optional<std::string>& integrator) {
  std::vector<Override> o;
  if (rtol) o.push_back(parse_override("solver.rtol=" + toml_value_text(*rtol)));
  if (atol) o.push_back(parse_override("solver.atol=" + toml_value_text(*atol)));
  if (integrator) o.push_back(parse_override("solver.integrator=" + convert_impl::toml_string(*integrator)));
  return o;
}

}  // namespace imcol::python
