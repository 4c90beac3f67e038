// SPDX-License-Identifier: BSD-3-Clause
// The names a scene or a call may choose from, listed from the code that reads them: the choice enums' spellings
// (core/choices.hpp), the effects (core/scene.hpp), the sweep quantities (study/sweep_points.hpp) and the shipped
// scenes (study/scene_catalog.hpp, as `imcol scenes PATTERN` lists them).
#include <pybind11/stl.h>

#include "core/choices.hpp"
#include "core/scene.hpp"
#include "python/bindings.hpp"
#include "study/scene_catalog.hpp"
#include "study/sweep_points.hpp"

namespace py = pybind11;

namespace imcol::python {

namespace choices_impl {  // this file's helpers: named, as the module is one unity unit

/// Every choice key of a scene -> its allowed values. The keys are the scene reader's (core/scene.cpp,
/// core/flow_spec.cpp TableReader::choice calls); the values come from the enum each key is read into.
py::dict scene_choices() {
  py::dict d;
  d["drag.law"] = choice_names<DragLaw>();
  d["lubrication.model"] = choice_names<LubricationModel>();
  d["lubrication.limit"] = choice_names<LubricationLimit>();
  d["added_mass.model"] = choice_names<AddedMassModel>();
  d["contact.law"] = choice_names<ContactLawKind>();
  d["history.kernel"] = choice_names<KernelKind>();
  d["history.evaluator"] = choice_names<HistoryEvaluator>();
  d["history.start"] = choice_names<HistoryStart>();
  d["history.reynolds"] = choice_names<HistoryReynolds>();
  d["history.wall_correction"] = choice_names<WallCorrection>();
  d["solver.integrator"] = choice_names<IntegratorMethod>();
  d["solver.linear_solver"] = choice_names<LinearSolverChoice>();
  d["measure.bounces"] = choice_names<BouncesMode>();
  d["measure.e"] = choice_names<EMeasure>();
  d["flow.start"] = choice_names<FlowStart>();
  d["flow.force_in_step"] = choice_names<ForceInStep>();
  d["flow.fields_format"] = choice_names<FieldsFormat>();
  d["effects"] = effect_names();
  return d;
}

}  // namespace choices_impl

void bind_choices(py::module_& m) {
  using namespace choices_impl;
  m.def("history_kernels", &choice_names<KernelKind>, "history.kernel's values (imcol history --kernels).");
  m.def("integrators", &choice_names<IntegratorMethod>, "solver.integrator's values (imcol.run(integrator=…), --integrator).");
  m.def("contact_laws", &choice_names<ContactLawKind>, "contact.law's values (imcol laws --laws).");
  m.def("lubrication_models", &choice_names<LubricationModel>, "lubrication.model's values.");
  m.def("drag_laws", &choice_names<DragLaw>, "drag.law's values.");
  m.def("e_measures", &choice_names<EMeasure>, "The named measures of e: measure.e's values (docs/bounces.md).");
  m.def("effects", &effect_names, "The names `effects` may list.");
  m.def("sweep_quantities", &study::sweep_quantities, "What imcol.sweep can vary (imcol sweep --vary).");
  m.def("scenes", &study::matching_scenes, py::arg("pattern") = "",
        "The shipped scenes' names (imcol.Scene.load takes them) that `imcol scenes PATTERN` lists: PATTERN a part of "
        "the name or description (case-insensitive) or a glob on the name ('coupled/*'); \"\" lists all.");
  m.def("choices", &scene_choices, "Every choice key of a scene -> its allowed values (as Scene.set and --set check them).");
}

}  // namespace imcol::python
