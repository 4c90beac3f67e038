// SPDX-License-Identifier: BSD-3-Clause
// The data folder the module reads scenes, materials, fluids and reference tables from (core/data_dir.hpp): the
// installed package sets its own imcol/data at import.
#include <pybind11/stl.h>

#include "core/data_dir.hpp"
#include "python/bindings.hpp"

namespace py = pybind11;

namespace imcol::python {

void bind_data_dir(py::module_& m) {
  m.def("data_dir", &imcol::data_dir,
        "The folder imcol reads its shipped data from (scenes/, materials.csv, fluids.csv, reference/): "
        "$IMCOL_DATA_DIR if set, else the installed package's imcol/data, else the source tree's data/.");
  m.def("_set_data_dir", &imcol::set_data_dir, py::arg("dir"),
        "Sets the data folder below $IMCOL_DATA_DIR (the package calls it at import); \"\" clears it.");
}

}  // namespace imcol::python
