// The physics outcome of every point of a sweep (`stairplan sweep --simulate`): each planned point
// is executed in MuJoCo and its verdict set beside the validator's, for a CSV of physics columns
// keyed by point index and the validator/physics agreement report.
#pragma once

#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "stairplan/pipeline/plan_pipeline.h"
#include "stairplan/simulation/sim_settings.h"
#include "stairplan/simulation/verdict_agreement.h"
#include "stairplan/sweep/sweep_grid.h"

namespace stairplan {

/// One sweep point's physics outcome, condensed.
struct PhysicsRow {
  int index = 0;  ///< the sweep point's index
  std::string label;             ///< "up rise=0.17 run=0.27"
  std::string validator;         ///< "valid" or "invalid"
  std::string validator_cause;  ///< the validator's first violation, when invalid
  std::string status;            ///< SimStatus, or "error" when the simulation could not run
  bool passed = false;  ///< SimulationOutcome::Passed()
  bool passed_with_clearance = false;  ///< passed, and no leg link came within the validator's margin
  double min_link_clearance_m = 0.0;  ///< smallest non-foot link distance to the stairs over the run [m]
  std::string closest_link;  ///< "<link> to <stair geom>" for that distance
  std::string cause;             ///< SimulationOutcome::FirstCause()
  int landings = 0;  ///< footsteps landed
  double max_landing_error_m = 0.0;  ///< largest landing error [m]
  int other_contacts = 0;  ///< non-foot links that touched the stairs
  double max_torque_ratio = 0.0;  ///< largest peak torque / effort limit
  double real_time_factor = 0.0;  ///< simulated seconds per wall-clock second
};

/// Simulates `result`'s plan when it has one (status ok); nothing for points without a plan. Never
/// throws: a simulation that cannot run gives status "error" and the message as cause.
std::optional<PhysicsRow> SimulateSweepPoint(const SweepPoint& point, const RobotModel& robot, const Staircase& stairs,
                                             const PipelineResult& result, const SimSettings& settings,
                                             double clearance);

/// The physics CSV's column header (without newline).
std::string PhysicsCsvHeader();
/// One row's CSV line, without newline.
std::string PhysicsCsvLine(const PhysicsRow& row);
/// A row from its CSV line; throws std::invalid_argument.
PhysicsRow PhysicsRowFromCsvLine(const std::string& line);

/// Collects physics rows from a sweep's worker threads.
class SweepPhysics {
 public:
  /// `clearance` is the validator's margin that PhysicsRow::passed_with_clearance applies.
  explicit SweepPhysics(const SimSettings& settings = {}, double clearance = 0.005);

  /// Simulates `result`'s plan when it has one (status ok); points without a plan are skipped.
  /// Thread-safe; never throws (a failed simulation gives status "error").
  void Record(const SweepPoint& point, const RobotModel& robot, const Staircase& stairs, const PipelineResult& result);
  /// Adds a row computed elsewhere (another rank, a resumed run's file). Thread-safe.
  void Add(const PhysicsRow& row);
  ///@{
  /// The settings Record simulates with, and its clearance margin.
  const SimSettings& settings() const { return settings_; }
  double clearance() const { return clearance_; }
  ///@}

  /// Rows in point order.
  std::vector<PhysicsRow> Rows() const;
  /// index,direction_label,validator,physics_status,physics_passed,physics_cause,... CSV text.
  std::string Csv() const;
  /// Validator against physics over the simulated points: physics passes when the robot got there
  /// without any non-foot contact, or, `with_clearance`, also never came within the margin.
  AgreementReport Agreement(bool with_clearance = false) const;

 private:
  SimSettings settings_;
  double clearance_ = 0.005;
  mutable std::mutex mutex_;
  std::vector<PhysicsRow> rows_;
};

}  // namespace stairplan
