// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The model choices a scene makes, as enums: the scene reader turns each key's string into one of these
// (an unknown string is an input error there), so nothing below the reader compares strings.
// Each enum's names (the scene's spellings, also written to summary.json) are listed once, in ChoiceNames<E>::list below.
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace imcol {

enum class DragLaw { stokes, schiller_naumann };                  // MODEL.md §2.1
enum class LubricationModel { brenner, asymptotic, seed };
// Where the lubrication force ends: a smooth cut-off gap it acts through, also in contact (cutoff), or the surfaces'
// roughness height, where the solids touch and below which it does not act (roughness; docs/model-notes.md).
enum class LubricationLimit { cutoff, roughness };        // Brenner series (wall) | Jeffrey–Onishi law | seed (our reading of its 6.7)
enum class AddedMassModel { lagrangian, seed };                   // pair kinetic energy | seed (6.8), per sphere
enum class KernelKind { basset, mei_adrian, kim, dorgan_loth };   // history kernel, MODEL.md §2.3
enum class HistoryEvaluator { soe, soe_step, direct };            // sum of exponentials (modes in the state | per step) | product integration
enum class HistoryStart { steady, impulsive };                    // moving at U(0) for ever | from rest at t = 0
enum class HistoryReynolds { instantaneous, initial };            // Re of a finite-Re kernel: |U| | |U(0)|
enum class WallCorrection { none, added_mass };                   // K_H = 1 | 1 + 3W(δ**)
enum class ContactLawKind { ramp, hertz };                       // contact.law: the seed's ramp | Hertz with Tsuji damping (MODEL.md §2.4)
enum class IntegratorMethod { cvode, ida };
enum class LinearSolverChoice { automatic, dense, schur, gmres };
enum class BouncesMode { first, all };                            // measure.bounces
/// The named measures of e (docs/bounces.md); measure.e picks the one reported as `e`.
enum class EMeasure { contact_ends, fit_time, fit_distance, at_gap, peak_rebound, instant, yang_hunt_2006, joseph_2001, gondret_2002 };
/// How the flow exists at t = 0 (the [flow] table).
enum class FlowStart {
  impulsive,  // fluid at rest: the spheres' initial velocities are imposed over one flow step before t = 0
  developed   // the initial velocities are imposed over a stated distance (or time) before t = 0
};
/// How f_SIM varies inside one flow step (MODEL.md §5).
enum class ForceInStep {
  linear,  // linear between its values at t_n and t_{n+1}: damps the alternating mode (measured order in Δt ≈ 0.8)
  held     // the kernel's step force over the whole step (order ≈ 1.3), but an alternating instability grows for
           // light spheres (density ratio 0.5 at 24 cells/D): docs/coupling.md
};

/// Which files hold the flow fields (collision scenes' flow.fields_format, flow scenes' output.fields_format).
enum class FieldsFormat { csv, vtk, both };

template <class E> struct ChoiceNames;
#define IMCOL_CHOICE_NAMES(E, ...)                                                   \
  template <> struct ChoiceNames<E> {                                                \
    static constexpr auto list = std::to_array<std::pair<E, std::string_view>>({__VA_ARGS__}); \
  };
IMCOL_CHOICE_NAMES(DragLaw, {DragLaw::stokes, "stokes"}, {DragLaw::schiller_naumann, "schiller-naumann"})
IMCOL_CHOICE_NAMES(LubricationModel, {LubricationModel::brenner, "brenner"}, {LubricationModel::asymptotic, "asymptotic"},
                   {LubricationModel::seed, "seed"})
IMCOL_CHOICE_NAMES(LubricationLimit, {LubricationLimit::cutoff, "cutoff"}, {LubricationLimit::roughness, "roughness"})
IMCOL_CHOICE_NAMES(AddedMassModel, {AddedMassModel::lagrangian, "lagrangian"}, {AddedMassModel::seed, "seed"})
IMCOL_CHOICE_NAMES(KernelKind, {KernelKind::basset, "basset"}, {KernelKind::mei_adrian, "mei-adrian"}, {KernelKind::kim, "kim"},
                   {KernelKind::dorgan_loth, "dorgan-loth"})
IMCOL_CHOICE_NAMES(HistoryEvaluator, {HistoryEvaluator::soe, "soe"}, {HistoryEvaluator::soe_step, "soe-step"},
                   {HistoryEvaluator::direct, "direct"})
IMCOL_CHOICE_NAMES(HistoryStart, {HistoryStart::steady, "steady"}, {HistoryStart::impulsive, "impulsive"})
IMCOL_CHOICE_NAMES(HistoryReynolds, {HistoryReynolds::instantaneous, "instantaneous"}, {HistoryReynolds::initial, "initial"})
IMCOL_CHOICE_NAMES(WallCorrection, {WallCorrection::none, "none"}, {WallCorrection::added_mass, "added-mass"})
IMCOL_CHOICE_NAMES(ContactLawKind, {ContactLawKind::ramp, "ramp"}, {ContactLawKind::hertz, "hertz"})
IMCOL_CHOICE_NAMES(IntegratorMethod, {IntegratorMethod::cvode, "cvode"}, {IntegratorMethod::ida, "ida"})
IMCOL_CHOICE_NAMES(LinearSolverChoice, {LinearSolverChoice::automatic, "auto"}, {LinearSolverChoice::dense, "dense"},
                   {LinearSolverChoice::schur, "schur"}, {LinearSolverChoice::gmres, "gmres"})
IMCOL_CHOICE_NAMES(BouncesMode, {BouncesMode::first, "first"}, {BouncesMode::all, "all"})
IMCOL_CHOICE_NAMES(EMeasure, {EMeasure::contact_ends, "contact_ends"}, {EMeasure::fit_time, "fit_time"},
                   {EMeasure::fit_distance, "fit_distance"}, {EMeasure::at_gap, "at_gap"}, {EMeasure::peak_rebound, "peak_rebound"},
                   {EMeasure::instant, "instant"}, {EMeasure::yang_hunt_2006, "yang_hunt_2006"}, {EMeasure::joseph_2001, "joseph_2001"},
                   {EMeasure::gondret_2002, "gondret_2002"})
IMCOL_CHOICE_NAMES(FlowStart, {FlowStart::impulsive, "impulsive"}, {FlowStart::developed, "developed"})
IMCOL_CHOICE_NAMES(ForceInStep, {ForceInStep::linear, "linear"}, {ForceInStep::held, "held"})
IMCOL_CHOICE_NAMES(FieldsFormat, {FieldsFormat::csv, "csv"}, {FieldsFormat::vtk, "vtk"}, {FieldsFormat::both, "both"})
#undef IMCOL_CHOICE_NAMES

/// The scene's spelling of a choice.
template <class E>
constexpr const char* to_string(E e) requires requires { ChoiceNames<E>::list; } {
  for (const auto& [v, name] : ChoiceNames<E>::list)
    if (v == e) return name.data();
  return "?";
}

/// The choice spelled `s`, or none.
template <class E>
constexpr std::optional<E> choice_from_string(std::string_view s) {
  for (const auto& [v, name] : ChoiceNames<E>::list)
    if (name == s) return v;
  return std::nullopt;
}

/// Every value of a choice enum, by its spellings, in the order above.
template <class E>
std::vector<std::string> choice_names() {
  std::vector<std::string> out;
  for (const auto& [e, name] : ChoiceNames<E>::list) out.emplace_back(name);
  return out;
}

}  // namespace imcol
