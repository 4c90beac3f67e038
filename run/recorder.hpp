#pragma once
// Samples a collision run into trajectory rows (one per output time and event) with the force terms of the
// effects that ran (or, for sweeps, the kinematics alone), lets the model observe each sample (it may end the
// run: at rest), and shows progress.
#include <span>
#include <string>
#include <vector>

#include "contact/collision_model.hpp"
#include "core/scene.hpp"
#include "core/system.hpp"
#include "core/timing.hpp"

namespace imcol::run {

class Recorder : public Observer {
 public:
  /// `progress`: a run still going after 2 s shows a progress line on stderr (a terminal only). `forces`: the rows
  /// carry the force terms and accelerations; without, only the kinematic columns and the event flag.
  Recorder(contact::CollisionModel& model, const Scene& sc, bool progress, bool forces = true);

  void sample(double t, std::span<const double> y, bool at_event) override;
  void stepped(long steps) override { steps_ = steps; }
  /// Clears the progress line, if one was shown.
  void finish_progress();

  const std::vector<std::string>& columns() const { return columns_; }
  std::vector<std::vector<double>>& rows() { return rows_; }
  double min_gap() const { return min_gap_; }          // m, over the samples
  bool forces() const { return forces_; }
  double max_contact_force() const { return max_force_; }  // N, sphere 1 (forces() only)
  double max_history_force() const { return max_history_; }  // N, any sphere (forces() only)

 private:
  void show_progress(double t);

  contact::CollisionModel& model_;
  const Scene& sc_;
  std::vector<std::string> columns_;
  std::vector<double contact::SphereForces::*> fields_;  // the force columns of each sphere, in column order
  std::vector<std::vector<double>> rows_;
  double min_gap_, max_force_ = 0, max_history_ = 0;
  long steps_ = 0;
  bool forces_ = true, progress_ = false, shown_ = false;
  WallClock::time_point start_ = WallClock::now(), last_ = start_;
};

}  // namespace imcol::run
