// The body planner's exact variant: the same problem as the QP over a window of knots, with the
// hip heights from sin/cos of the pitch instead of the fixed row coefficients, the bounds taken
// at each knot's exact hip offset and pitch (not the worst case over a trust region), and the
// FCL clearance bound (the lowest clear hip height per foothold, from the same cache) as
// constraints. Solved with Ipopt or NLopt's SLSQP. It refines plans offline and measures how
// conservative the per-cycle QP is (objective gap, distance to the bounds). Ipopt gets the exact
// Hessian of the costs (and finite-difference curvature of the bounds), SLSQP variables scaled by
// that curvature; both first see only the constraints near active at the initial point, and the
// solution is checked against all of them and re-solved with the broken ones until none is (see
// body_nlp_solve.cc), so the answer is the whole NLP's.
//
// In a loop (one window per cycle), SolveBodyNlpWarm starts each window from the previous one's
// solution shifted in time, multipliers included, so Ipopt needs a few iterations, not a dozen:
//
//   BodyNlpSolution solution;
//   SolveBodyNlpFrom(planner, settings, now, planner.output().knots, &solution);   // cold, once
//   for (;;) {                                                                      // every cycle
//     now += dt; planner.Update(state, command, now);
//     SolveBodyNlpWarm(planner, settings, now, state, solution, &solution);
//   }
#pragma once

#include <array>
#include <string>

#include "stairplan/planning/body/body_check.h"
#include "stairplan/planning/body/body_planner.h"
#include "stairplan/optim/solve_result.h"

namespace stairplan {

/// The NLP's solver and its stopping rules.
struct BodyNlpSettings {
  std::string solver = "ipopt";  ///< "ipopt" or "nlopt" (SLSQP)
  double tolerance = 1e-4;       ///< the solver's convergence tolerance
  int max_iterations = 200;  ///< the solver's iteration limit per solve
  /// Solve with the constraints near active at the initial point first and add the ones the
  /// solution breaks (same answer, smaller linear systems); false: every constraint at once.
  bool screen_constraints = true;
  /// Throws std::invalid_argument naming the field.
  void Validate() const;
};

/// One NLP solve and how it compares with the QP plan it started from.
struct BodyNlpWindow {
  optim::SolveStatus status = optim::SolveStatus::kInvalidInput;  ///< how the solve ended
  double qp_objective = 0.0;   ///< the NLP's objective at the QP plan
  double nlp_objective = 0.0;  ///< ... at its own solution
  double qp_bound_distance = 0.0;   ///< smallest distance of a stance hip from its exact bounds, QP plan [m]
  double nlp_bound_distance = 0.0;  ///< ... NLP solution [m] (negative: a bound is broken)
  double solve_ms = 0.0;      ///< wall-clock time of the solve (all screening rounds)
  double solve_cpu_ms = 0.0;  ///< ... CPU time of this process over it (what the load does not inflate)
  int iterations = 0;       ///< the solver's iterations (NLopt: evaluations), summed over screening rounds
  int windows = 0;          ///< RefineBodyNlp: windows solved
  int windows_refined = 0;  ///< ... whose NLP solution replaced the QP's values
};

/// An NLP solution with its multipliers: what the next window warm-starts from. The multipliers
/// are kept by what they constrain (signs as in optim::SolveResult: <= 0 on an active lower side,
/// >= 0 on an active upper one, 0 inactive), so that a window shifted in time finds them.
struct BodyNlpSolution {
  double t0 = 0.0;                ///< the window's first knot time
  std::vector<BodyState> knots;   ///< at t0 + k * knot_dt
  /// Per knot k and leg l (index k * kBodyLegs + l): the stance foothold (-1: swing) and the
  /// multipliers of its lowest- and highest-hip bounds.
  std::vector<int> stance_foothold;
  /// Per knot and leg, as stance_foothold: the multipliers of its two bounds.
  std::vector<std::array<double, 2>> stance_duals;
  /// Per acceleration row: quantity q (0 height, 1 pitch, 2 shift) over knots k .. k + 2 at
  /// q * (knots - 2) + k.
  std::vector<double> accel_duals;
  /// Per variable: knot k's height, pitch and shift at 3k, 3k + 1, 3k + 2.
  std::vector<double> bound_duals;
};

/// The NLP over the planner's horizon at `now` (call after planner.Update(state, ..., now)): the
/// planner's knots are the initial guess, knot 0 stays pinned. Writes the solution into `knots`
/// (sized like the planner's). Not per cycle: builds a Program and allocates.
BodyNlpWindow SolveBodyNlp(BodyPlanner& planner, const BodyNlpSettings& settings, double now,
                           std::vector<BodyState>* knots);

/// The NLP over the knots t0 + k * knot_dt starting from `guess` (knot 0 pinned to guess[0]):
/// the QP's plan for a cold start, a previous NLP solution for a warm one.
BodyNlpWindow SolveBodyNlpFrom(BodyPlanner& planner, const BodyNlpSettings& settings, double t0,
                               const std::vector<BodyState>& guess, std::vector<BodyState>* knots);

/// SolveBodyNlpFrom that also returns the multipliers (`solution`, for SolveBodyNlpWarm).
BodyNlpWindow SolveBodyNlpFrom(BodyPlanner& planner, const BodyNlpSettings& settings, double t0,
                               const std::vector<BodyState>& guess, BodyNlpSolution* solution);

/// The next window of a loop: the NLP over t0 + k * knot_dt (as many knots as `previous`), warm-
/// started from `previous` shifted to t0: its knots interpolated in time (extrapolated from the
/// last two beyond its end), knot 0 moved to `state` with the difference faded out over the next
/// knots within the acceleration limits, and each knot's multipliers from the previous knot
/// nearest in time where the same constraint exists (0 for new ones). Knot 0 stays pinned to
/// `state`. `solution` gets this window's (it may be `&previous`). Throws std::invalid_argument
/// naming the field when t0 is before previous.t0 or `previous` is not a solution's shape.
BodyNlpWindow SolveBodyNlpWarm(BodyPlanner& planner, const BodyNlpSettings& settings, double t0,
                               const BodyState& state, const BodyNlpSolution& previous, BodyNlpSolution* solution);

/// `previous` moved to the window at t0 as SolveBodyNlpWarm starts from it (exposed for tests).
BodyNlpSolution ShiftBodyNlpSolution(const BodyNlpSolution& previous, double t0, const BodyPlannerSettings& settings,
                                     const BodyState& state);

/// The offline refinement behind `stairplan plan --nlp`: the plan's body (from PlanBody) is cut
/// into windows of settings.knots samples, each re-solved by the NLP from the QP's values with its
/// first sample pinned to the previous window's end. A window's solution is kept when it is
/// solved, or inside the bounds and cheaper; otherwise the QP's values stay. Then the whole
/// trajectory is re-checked exactly (IK and FCL): the plan is infeasible when the check fails.
/// `summary` (optional) gets the summed objectives, the worst bound distances and the last
/// non-solved status over the windows.
Plan RefineBodyNlp(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map, Plan plan,
                   const BodyPlannerSettings& settings = {}, const BodyNlpSettings& nlp = {},
                   BodyNlpWindow* summary = nullptr);

}  // namespace stairplan
