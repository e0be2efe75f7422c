// The exact body NLP's public entry points (see body_nlp.h): the settings' check, one window's
// solve, cold or warm, and the offline refinement of a whole plan. The pieces are in
// body_nlp_window.cc (data, screening), body_nlp_program.cc (costs, constraints),
// body_nlp_duals.cc (multipliers), body_nlp_solve.cc (the rounds) and body_nlp_warm.cc (shift).
#include "stairplan/body_nlp/body_nlp.h"

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "stairplan/body_nlp/body_nlp_internal.h"
#include "stairplan/planning/body/kinematic_body_bounds.h"
#include "stairplan/planning/body/plan_body.h"

namespace stairplan {

using body_nlp_detail::SolveWindow;

void BodyNlpSettings::Validate() const {
  if (solver != "ipopt" && solver != "nlopt") {
    throw std::invalid_argument("solver: must be 'ipopt' or 'nlopt' (got '" + solver + "')");
  }
  if (!(tolerance > 0.0 && tolerance < 1.0)) throw std::invalid_argument("tolerance: must be in (0, 1)");
  if (max_iterations < 1) throw std::invalid_argument("max_iterations: must be positive");
}

BodyNlpWindow SolveBodyNlp(BodyPlanner& planner, const BodyNlpSettings& settings, double now,
                           std::vector<BodyState>* knots) {
  return SolveBodyNlpFrom(planner, settings, now, planner.output().knots, knots);
}

BodyNlpWindow SolveBodyNlpFrom(BodyPlanner& planner, const BodyNlpSettings& settings, double t0,
                               const std::vector<BodyState>& guess, std::vector<BodyState>* knots) {
  BodyNlpSolution solution;
  const BodyNlpWindow window = SolveBodyNlpFrom(planner, settings, t0, guess, &solution);
  *knots = std::move(solution.knots);
  return window;
}

BodyNlpWindow SolveBodyNlpFrom(BodyPlanner& planner, const BodyNlpSettings& settings, double t0,
                               const std::vector<BodyState>& guess, BodyNlpSolution* solution) {
  settings.Validate();
  if (guess.size() < 3) throw std::invalid_argument("SolveBodyNlpFrom: guess needs at least 3 knots");
  return SolveWindow(planner, settings, t0, guess, nullptr, solution);
}

BodyNlpWindow SolveBodyNlpWarm(BodyPlanner& planner, const BodyNlpSettings& settings, double t0,
                               const BodyState& state, const BodyNlpSolution& previous, BodyNlpSolution* solution) {
  settings.Validate();
  const BodyNlpSolution start = ShiftBodyNlpSolution(previous, t0, planner.settings(), state);
  return SolveWindow(planner, settings, t0, start.knots, &start, solution);
}

Plan RefineBodyNlp(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map, Plan plan,
                   const BodyPlannerSettings& settings, const BodyNlpSettings& nlp, BodyNlpWindow* summary) {
  settings.Validate();
  nlp.Validate();
  if (plan.status != PlanStatus::kOk && plan.status_reason.rfind("body", 0) != 0) return plan;  // no footsteps
  if (plan.body.size() < 3) return plan;
  const auto start = std::chrono::steady_clock::now();
  BodyPlanner planner(robot, stairs, map, plan, settings);
  const std::size_t window = static_cast<std::size_t>(settings.knots);
  BodyNlpWindow worst;
  worst.qp_bound_distance = worst.nlp_bound_distance = std::numeric_limits<double>::infinity();
  worst.status = optim::SolveStatus::kSolved;
  std::string failure;
  std::vector<BodyState> guess;
  BodyNlpSolution solution;
  for (std::size_t i0 = 0; i0 + 1 < plan.body.size(); i0 += window - 1) {
    const std::size_t count = std::min(window, plan.body.size() - i0);
    if (count < 3) break;
    guess.assign(plan.body.begin() + static_cast<std::ptrdiff_t>(i0), plan.body.begin() + static_cast<std::ptrdiff_t>(i0 + count));
    const BodyNlpWindow w = SolveWindow(planner, nlp, guess.front().t, guess, nullptr, &solution);
    worst.qp_objective += w.qp_objective;
    worst.nlp_objective += w.nlp_objective;
    worst.qp_bound_distance = std::min(worst.qp_bound_distance, w.qp_bound_distance);
    worst.nlp_bound_distance = std::min(worst.nlp_bound_distance, w.nlp_bound_distance);
    worst.solve_ms += w.solve_ms;
    worst.solve_cpu_ms += w.solve_cpu_ms;
    worst.iterations += w.iterations;
    ++worst.windows;
    if (w.status != optim::SolveStatus::kSolved) worst.status = w.status;
    // A window's solution replaces the QP's only when it is solved, or at least inside the
    // bounds and cheaper (the kinks of the tabulated bounds can stall a solver at a good point);
    // otherwise the QP's values stay, so refining never makes a plan worse.
    const bool usable = w.status == optim::SolveStatus::kSolved ||
                        (w.nlp_bound_distance >= -1e-6 && w.nlp_objective <= w.qp_objective);
    if (!usable) continue;
    ++worst.windows_refined;
    for (std::size_t k = 0; k < count; ++k) plan.body[i0 + k] = solution.knots[k];
  }
  auto& bounds = static_cast<KinematicBodyBounds&>(planner.bounds());
  const BodyPlanCheck check = CheckBodyTrajectory(bounds, planner.schedule(), plan.body, RecheckMargins(settings, plan.gait));
  if (!check.ok()) failure = "body NLP re-check: " + check.Summary();
  plan.status = failure.empty() ? PlanStatus::kOk : PlanStatus::kInfeasible;
  plan.status_reason = failure;
  if (worst.windows_refined > 0) plan.body_planner = BodyPlannerKind::kRecedingHorizonNlp;
  plan.timing_us.emplace_back("body_nlp", std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count());
  if (summary != nullptr) *summary = worst;
  return plan;
}

}  // namespace stairplan
