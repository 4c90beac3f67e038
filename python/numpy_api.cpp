// SPDX-License-Identifier: BSD-3-Clause
// NumPy for the module's arrays. pybind11 (2.10) keeps NumPy's C API table in a function-local static
// (detail::npy_api::get()) whose initialiser imports NumPy. Made first in a call, two threads deadlock: one holds the
// static's initialisation lock and waits for the GIL (NumPy's import hands the GIL round), the other holds the GIL
// and waits for that lock. So the table is made at the module's import, under the import's GIL; when NumPy cannot be
// imported then, the module still imports, and what returns arrays raises ImportError saying so (require_numpy).
#include <pybind11/numpy.h>

#include "python/bindings.hpp"

namespace py = pybind11;

namespace imcol::python {

namespace numpy_impl {  // this file's helpers: named, as the module is one unity unit

bool ready = false;  // the API table is made; read and written with the GIL held

/// Imports NumPy, then makes the API table. NumPy being fully imported, the static's initialiser runs no Python code
/// that could hand the GIL to another thread (its imports find the modules loaded). Throws error_already_set.
void make_api() {
  py::module_::import("numpy");
  py::array_t<double> probe(0);  // npy_api::get(), and the dtype lookups the module's arrays use
  py::array_t<long long> index(0);
  ready = true;
}

}  // namespace numpy_impl

void init_numpy() {
  try {
    numpy_impl::make_api();
  } catch (const std::exception&) {  // no NumPy, or a broken one: require_numpy says which when arrays are asked for
  }
}

void require_numpy(const std::string& what) {
  if (numpy_impl::ready) return;
  std::string why;
  try {
    numpy_impl::make_api();  // NumPy may have become importable since the module's import (sys.path changed)
    return;
  } catch (const py::error_already_set& e) {
    why = py::str(e.value());
  } catch (const std::exception& e) {
    why = e.what();
  }
  throw py::import_error(what + " needs NumPy, which could not be imported (" + why + "); install it (Debian: python3-numpy)");
}

}  // namespace imcol::python
