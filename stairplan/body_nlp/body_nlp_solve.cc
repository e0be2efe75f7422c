// One window of the body NLP, solved: the solver settings of a round (Ipopt's or SLSQP's) and the
// screening rounds that add the constraints a solution breaks until none is, so the answer is
// the whole NLP's with smaller linear systems.
#include <chrono>
#include <ctime>
#include <string>
#include <vector>

#include "stairplan/body_nlp/body_nlp_internal.h"
#include "stairplan/solvers/ipopt_solver.h"
#include "stairplan/solvers/nlopt_solver.h"

namespace stairplan {
namespace body_nlp_detail {
namespace {

// Constraint screening: the solvers first see only the bound sides within this margin of the
// initial point and the acceleration rows above this fraction of their limit; the rest are
// checked at the solution and added when broken (see SolveWindow).
constexpr double kScreenMargin = 0.03;       // [m]
constexpr double kScreenAccelFraction = 0.3;
constexpr int kMaxRounds = 4;                 // the last round sees every constraint

// One round's solve; `duals` (Ipopt only) are the multipliers to start from; `cold`: the window
// has no previous solution to start from.
optim::SolveResult SolveProgram(const optim::Program& prog, const BodyNlpSettings& ns,
                                const optim::IpoptDualGuess* duals, bool cold) {
  optim::SolveResult result;
  if (ns.solver == "nlopt") {
    optim::NloptSettings s;
    s.xtol_rel = ns.tolerance * 1e-2;
    s.ftol_rel = ns.tolerance * 1e-4;
    s.constraint_tol = 1e-7;
    s.max_evaluations = ns.max_iterations * 20;
    // The costs' curvature spans 1e2 to 1e5 per variable: unscaled, SLSQP's identity start
    // took ~390 evaluations here, scaled by it ~13-26.
    s.scale_by_hessian = true;
    optim::NloptSolver solver(s);
    solver.Solve(prog, &result);
    return result;
  }
  optim::IpoptSettings s;
  s.tolerance = ns.tolerance;
  s.max_iterations = ns.max_iterations;
  // The initial point is a plan already (the QP's or a previous solution): start the barrier
  // small and close to it instead of Ipopt's mu 0.1 and 1% push, which re-centre it first.
  s.numeric_options["mu_init"] = 1e-5;
  s.numeric_options["bound_push"] = 1e-6;
  s.numeric_options["bound_frac"] = 1e-6;
  // Feasibility is what the plan is checked on: no bound broken by more than 0.1 um (Ipopt's
  // default allows 1e-4, i.e. 0.1 mm), also for the acceptable stop below.
  s.numeric_options["constr_viol_tol"] = 1e-7;
  s.numeric_options["acceptable_constr_viol_tol"] = 1e-7;
  // Stop at the first feasible iterate whose optimality error is small: the blended slopes at
  // the bounds' cell edges keep the last digits of the dual error from converging fast, and
  // they do not move the plan (objective changes there are ~1e-7 relative).
  s.integer_options["acceptable_iter"] = 1;
  s.numeric_options["acceptable_tol"] = 1e-2;
  s.numeric_options["acceptable_dual_inf_tol"] = 1e-1;
  s.numeric_options["acceptable_compl_inf_tol"] = 1e-3;
  // MUMPS's per-call overhead is most of an iteration here: one back-solve per step unless its
  // residual asks for refinement (Ipopt still refines then), and a workspace 5% above MUMPS's
  // estimate instead of 1000% (Ipopt grows it when short); together ~10-15% less CPU per solve.
  s.integer_options["min_refinement_steps"] = 0;
  s.integer_options["mumps_mem_percent"] = 5;
  // From the QP's plan, Mehrotra's predictor-corrector (Ipopt's option for convex problems, and
  // these costs are convex, the bounds nearly linear in the height) reached the same solution in
  // 19 iterations instead of 36 here; from a previous solution it took more (4.9 instead of
  // 3.25), so warm windows keep the monotone barrier.
  if (cold) s.string_options["mehrotra_algorithm"] = "yes";
  if (duals != nullptr) {
    // From a solution's multipliers: keep the point where it is (Ipopt's 1e-3 pushes would move
    // it back into the interior). Multipliers below 1e-3 are raised to it: a constraint that is
    // new or inactive has 0, and at a slack s the barrier wants mu / s (about 1e-3 for the
    // 1e-2-sized slacks of the acceleration rows); at 1e-6 Ipopt's first step there was 1 m.
    s.numeric_options["warm_start_bound_push"] = 1e-6;
    s.numeric_options["warm_start_bound_frac"] = 1e-6;
    s.numeric_options["warm_start_slack_bound_push"] = 1e-6;
    s.numeric_options["warm_start_slack_bound_frac"] = 1e-6;
    s.numeric_options["warm_start_mult_bound_push"] = 1e-3;
  }
  optim::IpoptSolver solver(s);
  if (duals != nullptr) solver.SetDualGuess(*duals);
  solver.Solve(prog, &result);
  return result;
}

}  // namespace

// The NLP over knots t0 + k dt with `guess` as the initial point (knot 0 pinned to it).
//
// Constraint screening: most bound sides and acceleration rows are far from active, and each
// one costs Ipopt a slack and two rows in the linear system it factorises every iteration
// (MUMPS's time there grows with that size, not with the few nonzeros) and SLSQP rows of its
// dense subproblem. So the first round
// holds only the constraints near active at the guess; its solution is checked against every
// constraint, the broken ones (and those near active there) are added, and the program is
// solved again from that solution, up to kMaxRounds times, the last with every constraint. A
// solution that breaks none of the left-out constraints leaves them inactive, so it is a
// solution of the whole NLP: the answer is the same as with every constraint from the start.
//
// Multipliers: Ipopt's first round starts from `warm`'s (the previous window's, already shifted
// to t0) when given. `solution` gets the knots and the last round's multipliers.
BodyNlpWindow SolveWindow(BodyPlanner& planner, const BodyNlpSettings& ns, double t0,
                          const std::vector<BodyState>& guess, const BodyNlpSolution* warm,
                          BodyNlpSolution* solution) {
  const BodyPlannerSettings& set = planner.settings();
  const FootSchedule& schedule = planner.schedule();
  const int n = static_cast<int>(guess.size());
  const WindowData d = Prepare(planner, t0, n);

  Eigen::VectorXd x0(3 * n);
  for (int k = 0; k < n; ++k) {
    const BodyState& g = guess[static_cast<std::size_t>(k)];
    x0.segment<3>(Z(k)) << g.z, g.pitch, g.com_shift;
  }
  Selection sel;
  sel.sides.assign(d.rows.size(), {false, false});
  sel.accel.assign(static_cast<std::size_t>(3 * (n - 2)), false);
  Screen(d, x0, kScreenMargin, kScreenAccelFraction, &sel);
  if (!ns.screen_constraints) sel.All();

  BodyNlpWindow window;
  window.qp_bound_distance = d.BoundDistance(x0);
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  Eigen::VectorXd x = x0;
  WindowDuals duals = warm != nullptr ? FromSolution(d, *warm) : ZeroDuals(d);
  bool have_duals = warm != nullptr && ns.solver == "ipopt";
  for (int round = 0; round < kMaxRounds; ++round) {
    if (round + 1 == kMaxRounds) sel.All();
    optim::Program prog;
    std::vector<optim::VariableBlock> blocks;
    for (int k = 0; k < n; ++k) blocks.push_back(prog.AddVariables("knot" + std::to_string(k), 3));
    for (int k = 0; k < n; ++k) {
      Eigen::Vector3d lo(-optim::kInf, -set.max_pitch, -set.max_shift), hi = -lo;
      if (k == 0) lo = hi = x0.segment<3>(0);  // knot 0 is the state
      prog.SetVariableBounds(blocks[static_cast<std::size_t>(k)], lo, hi);
    }
    AddCosts(d, blocks, &prog);
    const RowMap map = AddConstraints(d, sel, blocks, &prog);
    prog.MutableInitialGuess() = x;
    if (round == 0) window.qp_objective = prog.Objective(x0);
    const optim::IpoptDualGuess start_duals = have_duals ? ToProgram(duals, map) : optim::IpoptDualGuess{};
    const optim::SolveResult result = SolveProgram(prog, ns, have_duals ? &start_duals : nullptr, warm == nullptr);
    // The next round starts from this solution without its multipliers: with them (the rows it
    // adds at 0) cold starts took 44 iterations instead of 36 here.
    if (!FromProgram(d, result, map, &duals)) duals = ZeroDuals(d);  // NLopt has none
    have_duals = false;
    window.status = result.status;
    window.iterations += result.info.iterations;
    if (result.x.size() == x.size() && result.x.allFinite()) x = result.x;
    window.nlp_objective = prog.Objective(x);
    // Done when no left-out constraint is broken (the selection then already holds all).
    Selection broken = sel;
    if (Screen(d, x, 0.0, 1.0, &broken) == 0) break;
    // A broken constraint means the solution moved far from the guess (a cold start): the
    // next round holds every acceleration row, the cheap linear ones, rather than creeping up
    // on them round by round.
    Screen(d, x, kScreenMargin, kScreenAccelFraction, &sel);
    std::fill(sel.accel.begin(), sel.accel.end(), true);
  }
  window.solve_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  window.solve_cpu_ms = 1e3 * static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  window.nlp_bound_distance = d.BoundDistance(x);
  solution->t0 = t0;
  std::vector<BodyState>* out = &solution->knots;
  out->resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    BodyState& b = (*out)[static_cast<std::size_t>(k)];
    b.t = t0 + k * set.knot_dt;
    b.z = x[Z(k)];
    b.pitch = x[P(k)];
    b.com_shift = x[S(k)];
    b.com_shift_y = guess[static_cast<std::size_t>(k)].com_shift_y;  // the QP's sideways shift is kept
    b.x = d.neutral_x[k] + d.heading * b.com_shift;
    b.y = d.neutral_y[k] + d.heading * b.com_shift_y;
    b.yaw = schedule.yaw();
  }
  ToSolution(d, duals, solution);
  return window;
}

}  // namespace body_nlp_detail
}  // namespace stairplan
