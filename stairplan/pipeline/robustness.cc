#include "stairplan/pipeline/robustness.h"

#include <cmath>
#include <random>

#include "stairplan/geometry/field_error.h"

namespace stairplan {
namespace {

double NominalRun(const StairSpec& nominal, int i) {
  return nominal.runs.empty() ? nominal.run : nominal.runs[static_cast<std::size_t>(i)];
}

// One staircase with every rise and run perturbed; errors that make nonsense are redrawn.
StairSpec Perturbed(const StairSpec& nominal, const RobustnessSettings& s, std::mt19937& rng) {
  std::normal_distribution<double> rise_error(0.0, s.sigma_rise), run_err(0.0, s.sigma_run);
  const Staircase base(nominal);
  for (int attempt = 0; attempt < 100; ++attempt) {
    StairSpec spec = nominal;
    spec.rises.clear();
    spec.runs.clear();
    for (int i = 0; i < nominal.steps; ++i) spec.rises.push_back(base.rise(i) + rise_error(rng));
    for (int i = 0; i + 1 < nominal.steps; ++i) spec.runs.push_back(NominalRun(nominal, i) + run_err(rng));
    try {
      spec.Validate();
      return spec;
    } catch (const std::invalid_argument&) {
    }
  }
  throw std::invalid_argument("EvaluateRobustness: the error sigmas are too large for these stairs");
}

bool Valid(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map, const Plan& plan,
           const PipelineOptions& options) {
  if (plan.status != PlanStatus::kOk) return false;
  TraversalValidator validator(robot, stairs, map, options.validation);
  return validator.Validate(plan).ok;
}

}  // namespace

void RobustnessSettings::Validate() const {
  if (!std::isfinite(sigma_rise) || sigma_rise < 0.0 || sigma_rise > 0.05) throw FieldError("sigma_rise", "must be in [0, 0.05] m");
  if (!std::isfinite(sigma_run) || sigma_run < 0.0 || sigma_run > 0.1) throw FieldError("sigma_run", "must be in [0, 0.1] m");
  if (trials < 1 || trials > 10000) throw FieldError("trials", "must be from 1 to 10000");
}

Plan PlanOnTrueStairs(const Plan& nominal, const Staircase& true_stairs, const ConstrainedMap& true_map) {
  Plan plan = nominal;
  const auto land = [&](Eigen::Vector3d& p) {
    const double z = true_stairs.HeightAt(p.x(), p.y());
    p.z() = std::isfinite(z) ? z : p.z() - 1.0;  // off the stairs: the foot finds nothing
  };
  for (Eigen::Vector3d& p : plan.initial_feet_W) land(p);
  for (Footstep& f : plan.footsteps) {
    land(f.position_W);
    land(f.from_W);
    f.stair_index = true_map.StairAt(f.position_W.head<2>());
    f.in_step_region = f.stair_index >= 0 && true_map.InStepRegion(f.stair_index, f.position_W.head<2>());
  }
  return plan;
}

std::vector<StairSpec> PerturbedStaircases(const StairSpec& nominal, const RobustnessSettings& settings) {
  settings.Validate();
  std::mt19937 rng(settings.seed);
  std::vector<StairSpec> out;
  for (int trial = 0; trial < settings.trials; ++trial) out.push_back(Perturbed(nominal, settings, rng));
  return out;
}

RobustnessReport EvaluateRobustness(const RobotModel& robot, const StairSpec& nominal, const PipelineOptions& options,
                                    const RobustnessSettings& settings) {
  settings.Validate();
  const Staircase nominal_stairs(nominal);
  const PipelineResult planned = RunPipeline(robot, nominal_stairs, options);
  RobustnessReport report;
  report.trials = settings.trials;
  report.nominal_valid = planned.validated && planned.validation.ok ? 1 : 0;
  PipelineOptions no_validation = options;
  no_validation.validate = false;
  for (const StairSpec& spec : PerturbedStaircases(nominal, settings)) {
    const Staircase stairs(spec);
    double run_error = 0.0;
    for (int i = 0; i + 1 < nominal.steps; ++i) run_error += spec.runs[static_cast<std::size_t>(i)] - NominalRun(nominal, i);
    report.worst_cumulative_run_error = std::max(report.worst_cumulative_run_error, std::abs(run_error));
    const ConstrainedMap map = BuildPipelineMap(robot, stairs, options);
    report.open_loop_ok += Valid(robot, stairs, map, PlanOnTrueStairs(planned.plan, stairs, map), options) ? 1 : 0;
    const PipelineResult replanned = RunPipeline(robot, stairs, no_validation);
    report.replanned_ok += Valid(robot, stairs, replanned.map, replanned.plan, options) ? 1 : 0;
  }
  return report;
}

}  // namespace stairplan
