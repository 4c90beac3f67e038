// SPDX-License-Identifier: BSD-3-Clause
// imcol.StudyTable: the columns of a study's CSV as NumPy arrays (python/table.hpp).
#include "python/table.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "python/bindings.hpp"
#include "python/scene.hpp"

namespace py = pybind11;

namespace imcol::python {

namespace table_impl {  // this file's helpers: named, as the module is one unity unit

py::object column_array(const study::TableColumn& c, std::size_t rows) {
  if (c.words) {
    py::list words;
    for (std::size_t i = 0; i < rows; ++i) words.append(c.text[i]);
    return py::module_::import("numpy").attr("array")(words, py::arg("dtype") = "str");
  }
  py::array_t<double> a(static_cast<py::ssize_t>(rows));
  auto v = a.mutable_unchecked<1>();
  for (std::size_t i = 0; i < rows; ++i) v(static_cast<py::ssize_t>(i)) = c.numbers[i];
  return a;
}

}  // namespace table_impl

PyTable make_table(const std::string& kind, const study::Table& t, py::dict info) {
  PyTable r;
  r.kind = kind;
  r.info = std::move(info);
  for (const auto& c : t.columns) {
    r.columns.append(c.name);
    r.table[py::str(c.name)] = table_impl::column_array(c, t.rows);
  }
  return r;
}

py::list dir_with_columns(const py::handle& self, const py::list& columns) {
  py::set names(py::module_::import("builtins").attr("object").attr("__dir__")(self));
  for (const auto& c : columns)
    if (c.attr("isidentifier")().cast<bool>()) names.add(c);
  py::list out(names);
  out.attr("sort")();
  return out;
}

void bind_table(py::module_& m) {
  py::class_<PyTable>(m, "StudyTable",
                      "A study's rows as NumPy arrays, one per column of the command's CSV (`columns`, `table[name]`; every "
                      "column is also an attribute), and what the study found besides (`info`).")
      .def_readonly("kind", &PyTable::kind, "laws, history, history_sweep or dem: the command and file it matches.")
      .def_property_readonly("columns", [](const PyTable& r) { return r.columns.attr("copy")(); }, "The columns, in the CSV's order.")
      .def_readonly("table", &PyTable::table, "Column name -> NumPy array.")
      .def_readonly("info", &PyTable::info, "What the study found besides the rows (a dict).")
      .def("to_dict", [](const PyTable& r) { return py::module_::import("copy").attr("deepcopy")(r.table); },
           "The columns as a dict of NumPy arrays (copies), in the CSV's order: pandas.DataFrame(r.to_dict()).")
      .def("__len__", [](const PyTable& r) { return r.columns.empty() ? 0 : py::len(r.table[r.columns[0]]); })
      .def("__getattr__",
           [](const PyTable& r, const std::string& name) -> py::object {
             if (r.table.contains(name)) return r.table[py::str(name)];
             throw py::attribute_error("imcol.StudyTable has no attribute '" + name + "'");
           })
      .def("__dir__", [](const py::object& self) { return dir_with_columns(self, self.cast<const PyTable&>().columns); })
      .def("__repr__", [](const PyTable& r) {
        const std::size_t n = r.columns.empty() ? 0 : py::len(r.table[r.columns[0]]);
        return "imcol.StudyTable(kind='" + r.kind + "', rows=" + std::to_string(n) + ")";
      });
}

}  // namespace imcol::python
