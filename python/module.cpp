// SPDX-License-Identifier: BSD-3-Clause
// The extension module imcol._imcol (the package imcol re-exports it).
#include "python/bindings.hpp"

PYBIND11_MODULE(_imcol, m) {
  m.doc() = "imcol: head-on collisions of spheres immersed in a viscous liquid";
  m.attr("__version__") = IMCOL_VERSION;
  imcol::python::init_numpy();  // first: before any call could make an array
  imcol::python::bind_errors(m);
  imcol::python::bind_scene(m);
  imcol::python::bind_run(m);
  imcol::python::bind_sweep(m);
  imcol::python::bind_studies_precision(m);
  imcol::python::bind_choices(m);
  imcol::python::bind_table(m);
  imcol::python::bind_laws(m);
  imcol::python::bind_history(m);
  imcol::python::bind_dem_fit(m);
  imcol::python::bind_data_dir(m);
  imcol::python::bind_calibrate(m);
}
