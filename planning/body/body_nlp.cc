// The exact body NLP: its data per window, its costs and constraints as an optim::Program (with
// Hessians for Ipopt), the constraint screening that keeps Ipopt's linear systems small, and the
// offline refinement of a whole plan.
#include "planning/body/body_nlp.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "planning/body/kinematic_body_bounds.h"
#include "planning/optim/ipopt_solver.h"
#include "planning/optim/nlopt_solver.h"
#include "planning/optim/program.h"

namespace stairplan {
namespace {

// Central-difference step of the tabulated bounds' derivatives [m or rad]. The bounds are
// bilinear per grid cell (0.03 m x 0.1 rad) and their slopes jump at cell edges; a step of a few
// percent of a cell blends the two slopes near an edge, so the derivatives the solvers see are
// continuous and a solution sitting on an edge converges instead of cycling across it (with
// 1e-5 Ipopt cycled there until its iteration limit). The values stay exact.
constexpr double kFiniteStep = 2e-3;
// Constraint screening: the solvers first see only the bound sides within this margin of the
// initial point and the acceleration rows above this fraction of their limit; the rest are
// checked at the solution and added when broken (see SolveWindow).
constexpr double kScreenMargin = 0.03;       // [m]
constexpr double kScreenAccelFraction = 0.3;
constexpr int kMaxRounds = 4;                 // the last round sees every constraint

struct StanceRow {
  int knot = 0, leg = 0, foothold = 0;
  double contact_x = 0.0, contact_z = 0.0;
};

Eigen::MatrixXd FirstDifferences(int n) {
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(n - 1, n);
  for (int k = 0; k + 1 < n; ++k) d(k, k) = -1.0, d(k, k + 1) = 1.0;
  return d;
}

Eigen::MatrixXd SecondDifferences(int n) {
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(n - 2, n);
  for (int k = 0; k + 2 < n; ++k) d(k, k) = 1.0, d(k, k + 1) = -2.0, d(k, k + 2) = 1.0;
  return d;
}

// Variables: one block per knot, [z, pitch, shift]; each knot's constraints then touch only
// its own block, so the solvers see a sparse Jacobian instead of a dense one.
int Z(int k) { return 3 * k; }
int P(int k) { return 3 * k + 1; }
int S(int k) { return 3 * k + 2; }

// What one window's NLP is made of: per knot the neutral body, the references and the feet's
// heights; the stance rows; and the exact margins of a stance row's hip from its bounds.
struct WindowData {
  BodyPlanner* planner = nullptr;
  int n = 0;
  double t0 = 0.0, heading = 1.0;
  Eigen::VectorXd neutral_x, neutral_y, pitch_ref, shift_ref, foot_z;
  std::vector<StanceRow> rows;

  // (hip height - lowest valid, highest valid - hip height) at the exact hip offset and pitch.
  Eigen::Vector2d Margins(const StanceRow& r, double z, double p, double s) const {
    const double h = z + planner->HipDz(r.leg, p) - r.contact_z;
    HipBox box;
    box.leg = r.leg;
    box.foothold = r.foothold;
    box.dx_lo = box.dx_hi = heading * (neutral_x[r.knot] - r.contact_x) + s + planner->HipDx(r.leg, p);
    box.pitch_lo = box.pitch_hi = p;
    const HeightRange range = planner->bounds().HipHeight(box);
    if (range.empty()) return Eigen::Vector2d(-1.0, -1.0);  // no valid height here
    return Eigen::Vector2d(h - range.lo, range.hi - h);
  }
  Eigen::Vector2d Margins(const StanceRow& r, const Eigen::VectorXd& x) const {
    return Margins(r, x[Z(r.knot)], x[P(r.knot)], x[S(r.knot)]);
  }
  // The smallest margin over every stance row [m].
  double BoundDistance(const Eigen::VectorXd& x) const {
    double worst = std::numeric_limits<double>::infinity();
    for (const StanceRow& r : rows) worst = std::min(worst, Margins(r, x).minCoeff());
    return worst;
  }
};

WindowData Prepare(BodyPlanner& planner, double t0, int n) {
  const BodyPlannerSettings& set = planner.settings();
  const FootSchedule& schedule = planner.schedule();
  WindowData d;
  d.planner = &planner;
  d.n = n;
  d.t0 = t0;
  d.heading = schedule.heading();
  d.neutral_x.resize(n);
  d.neutral_y.resize(n);
  d.pitch_ref.resize(n);
  d.shift_ref.resize(n);
  d.foot_z.resize(n * kBodyLegs);
  for (int k = 0; k < n; ++k) {
    const double t = t0 + k * set.knot_dt;
    const Eigen::Vector2d xy = schedule.NeutralBodyXY(t);
    d.neutral_x[k] = xy.x();
    d.neutral_y[k] = xy.y();
    const double feet_pitch = schedule.FeetPitch(t);
    d.pitch_ref[k] = std::clamp(feet_pitch, -set.max_pitch, set.max_pitch);
    const double stairness =
        planner.stairs_pitch() > 0.0 ? std::clamp(std::abs(feet_pitch) / planner.stairs_pitch(), 0.0, 1.0) : 0.0;
    d.shift_ref[k] = set.stairs_com_shift * stairness;
    for (int l = 0; l < kBodyLegs; ++l) {
      const LegPhase phase = schedule.Phase(l, t);
      d.foot_z[k * kBodyLegs + l] = phase.foot_W.z();
      if (k == 0 || !phase.stance) continue;
      const Eigen::Vector3d& c = schedule.footholds()[static_cast<std::size_t>(phase.foothold)].contact_W;
      d.rows.push_back({k, l, phase.foothold, c.x(), c.z()});
    }
  }
  return d;
}

// Which constraints a round's program holds: per stance row its lower and upper side, per
// acceleration row (quantity q, knot k at q * (n - 2) + k) whether it is there.
struct Selection {
  std::vector<std::array<bool, 2>> sides;
  std::vector<bool> accel;
  void All() {
    std::fill(sides.begin(), sides.end(), std::array<bool, 2>{true, true});
    std::fill(accel.begin(), accel.end(), true);
  }
};

// The acceleration of quantity q over knots k .. k + 2 [per knot^2] and its limit.
double AccelAt(const Eigen::VectorXd& x, int q, int k) { return x[3 * k + q] - 2.0 * x[3 * (k + 1) + q] + x[3 * (k + 2) + q]; }
double AccelLimit(const BodyPlannerSettings& set, int q) {
  const double dt2 = set.knot_dt * set.knot_dt;
  return (q == 0 ? set.max_height_accel : q == 1 ? set.max_pitch_accel : set.max_shift_accel) * dt2;
}

// Adds to `sel` every constraint within `margin` (bounds) or above `fraction` of its limit
// (accelerations) at x; returns how many it added.
int Screen(const WindowData& d, const Eigen::VectorXd& x, double margin, double fraction, Selection* sel) {
  int added = 0;
  for (std::size_t i = 0; i < d.rows.size(); ++i) {
    const Eigen::Vector2d m = d.Margins(d.rows[i], x);
    for (int side = 0; side < 2; ++side) {
      if (m[side] < margin && !sel->sides[i][static_cast<std::size_t>(side)]) {
        sel->sides[i][static_cast<std::size_t>(side)] = true;
        ++added;
      }
    }
  }
  const BodyPlannerSettings& set = d.planner->settings();
  for (int q = 0; q < 3; ++q) {
    for (int k = 0; k + 2 < d.n; ++k) {
      const std::size_t row = static_cast<std::size_t>(q * (d.n - 2) + k);
      if (!sel->accel[row] && std::abs(AccelAt(x, q, k)) > fraction * AccelLimit(set, q)) {
        sel->accel[row] = true;
        ++added;
      }
    }
  }
  return added;
}

// The multipliers of a window's constraints by what they constrain (its stance rows' two sides,
// the acceleration rows, the variables) rather than by program row, since each round selects
// other rows and the next cycle's window, shifted in time, has other knots. Signs as in
// optim::SolveResult; a constraint a round left out has 0 (it was inactive there).
struct WindowDuals {
  std::vector<std::array<double, 2>> sides;  // per stance row: lowest- and highest-hip side
  std::vector<double> accel;                 // per acceleration row q * (n - 2) + k
  Eigen::VectorXd bounds;                    // per variable
};

WindowDuals ZeroDuals(const WindowData& d) {
  WindowDuals w;
  w.sides.assign(d.rows.size(), {0.0, 0.0});
  w.accel.assign(static_cast<std::size_t>(3 * (d.n - 2)), 0.0);
  w.bounds = Eigen::VectorXd::Zero(3 * d.n);
  return w;
}

// Where a round's program holds the selected constraints: the acceleration row of each linear
// row and the (stance row, side) of each nonlinear row, in the program's order.
struct RowMap {
  std::vector<int> accel;
  std::vector<std::pair<std::size_t, int>> sides;
};

optim::IpoptDualGuess ToProgram(const WindowDuals& w, const RowMap& map) {
  optim::IpoptDualGuess g;
  g.row_duals.resize(static_cast<Eigen::Index>(map.accel.size()));
  for (std::size_t i = 0; i < map.accel.size(); ++i) {
    g.row_duals[static_cast<Eigen::Index>(i)] = w.accel[static_cast<std::size_t>(map.accel[i])];
  }
  g.nonlinear_duals.resize(static_cast<Eigen::Index>(map.sides.size()));
  for (std::size_t i = 0; i < map.sides.size(); ++i) {
    const auto [row, side] = map.sides[i];
    g.nonlinear_duals[static_cast<Eigen::Index>(i)] = w.sides[row][static_cast<std::size_t>(side)];
  }
  g.bound_duals = w.bounds;
  return g;
}

// The multipliers of a round's solution into `w`; false (w unchanged) when the solver gave none.
bool FromProgram(const WindowData& d, const optim::SolveResult& r, const RowMap& map, WindowDuals* w) {
  if (r.row_duals.size() != static_cast<Eigen::Index>(map.accel.size()) ||
      r.nonlinear_duals.size() != static_cast<Eigen::Index>(map.sides.size()) || r.bound_duals.size() != 3 * d.n ||
      !r.row_duals.allFinite() || !r.nonlinear_duals.allFinite() || !r.bound_duals.allFinite()) {
    return false;
  }
  *w = ZeroDuals(d);
  for (std::size_t i = 0; i < map.accel.size(); ++i) {
    w->accel[static_cast<std::size_t>(map.accel[i])] = r.row_duals[static_cast<Eigen::Index>(i)];
  }
  for (std::size_t i = 0; i < map.sides.size(); ++i) {
    const auto [row, side] = map.sides[i];
    w->sides[row][static_cast<std::size_t>(side)] = r.nonlinear_duals[static_cast<Eigen::Index>(i)];
  }
  w->bounds = r.bound_duals;
  return true;
}

// A solution's multipliers (per knot and leg) onto this window's stance rows: a row finds its
// knot and leg's when they belong to the same foothold, else 0.
WindowDuals FromSolution(const WindowData& d, const BodyNlpSolution& s) {
  WindowDuals w = ZeroDuals(d);
  for (std::size_t i = 0; i < d.rows.size(); ++i) {
    const std::size_t at = static_cast<std::size_t>(d.rows[i].knot * kBodyLegs + d.rows[i].leg);
    if (s.stance_foothold[at] == d.rows[i].foothold) w.sides[i] = s.stance_duals[at];
  }
  w.accel = s.accel_duals;
  w.bounds = Eigen::Map<const Eigen::VectorXd>(s.bound_duals.data(), static_cast<Eigen::Index>(s.bound_duals.size()));
  return w;
}

void ToSolution(const WindowData& d, const WindowDuals& w, BodyNlpSolution* s) {
  const std::size_t cells = static_cast<std::size_t>(d.n * kBodyLegs);
  s->stance_foothold.assign(cells, -1);
  s->stance_duals.assign(cells, {0.0, 0.0});
  for (std::size_t i = 0; i < d.rows.size(); ++i) {
    const std::size_t at = static_cast<std::size_t>(d.rows[i].knot * kBodyLegs + d.rows[i].leg);
    s->stance_foothold[at] = d.rows[i].foothold;
    s->stance_duals[at] = w.sides[i];
  }
  s->accel_duals = w.accel;
  s->bound_duals.assign(w.bounds.data(), w.bounds.data() + w.bounds.size());
}

// The quadratic costs (pitch and shift references, smoothness) and the exact hip-height cost
// with its Hessian.
void AddCosts(const WindowData& d, const std::vector<optim::VariableBlock>& blocks, optim::Program* prog) {
  const BodyPlannerSettings& set = d.planner->settings();
  const int n = d.n;
  const double dt = set.knot_dt;
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(n, n);
  const Eigen::MatrixXd d1 = FirstDifferences(n), d2 = SecondDifferences(n);
  const Eigen::MatrixXd smooth = 2.0 * set.velocity_weight / (dt * dt) * d1.transpose() * d1 +
                                 2.0 * set.acceleration_weight / (dt * dt * dt * dt) * d2.transpose() * d2;
  const Eigen::MatrixXd hp = 2.0 * set.pitch_weight * identity + smooth;
  const Eigen::MatrixXd hs = 2.0 * set.shift_weight * identity + smooth;
  Eigen::MatrixXd& hessian = prog->MutableHessian();
  Eigen::VectorXd& linear = prog->MutableLinearCost();
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      hessian(Z(i), Z(j)) = smooth(i, j);
      hessian(P(i), P(j)) = hp(i, j);
      hessian(S(i), S(j)) = hs(i, j);
    }
    linear[P(i)] = -2.0 * set.pitch_weight * d.pitch_ref[i];
    linear[S(i)] = -2.0 * set.shift_weight * d.shift_ref[i];
  }
  prog->AddConstant(set.pitch_weight * d.pitch_ref.squaredNorm() + set.shift_weight * d.shift_ref.squaredNorm());

  // Exact hip heights: sum over knots and legs of w (z + hip_dz(pitch) - foot_z - wanted)^2.
  const double wh = set.height_weight, wanted = d.planner->desired_hip_height();
  const BodyPlanner& planner = *d.planner;
  const Eigen::VectorXd& foot_z = d.foot_z;
  optim::NonlinearCost height;
  height.name = "hip_height";
  height.blocks = blocks;
  height.value = [&planner, &foot_z, wh, wanted, n](const Eigen::VectorXd& x) {
    double f = 0.0;
    for (int k = 0; k < n; ++k) {
      for (int l = 0; l < kBodyLegs; ++l) {
        const double r = x[Z(k)] + planner.HipDz(l, x[P(k)]) - foot_z[k * kBodyLegs + l] - wanted;
        f += wh * r * r;
      }
    }
    return f;
  };
  height.gradient = [&planner, &foot_z, wh, wanted](const Eigen::VectorXd& x, int k, Eigen::Ref<Eigen::VectorXd> g) {
    g.setZero();
    const double p = x[P(k)];
    for (int l = 0; l < kBodyLegs; ++l) {
      const double r = x[Z(k)] + planner.HipDz(l, p) - foot_z[k * kBodyLegs + l] - wanted;
      const Eigen::Vector3d& h = planner.hip_B(l);
      g[0] += 2.0 * wh * r;
      g[1] += 2.0 * wh * r * (-std::cos(p) * h.x() - std::sin(p) * h.z());
    }
  };
  // Its exact Hessian, one 2x2 [z, pitch] per knot (d2 HipDz / dpitch2 = -HipDz): with it Ipopt
  // takes Newton steps instead of a quasi-Newton model of a problem it mostly knows exactly.
  height.hessian = [&planner, &foot_z, wh, wanted](const Eigen::VectorXd& x, int k, int, Eigen::Ref<Eigen::MatrixXd> h) {
    h.setZero();
    const double p = x[P(k)];
    for (int l = 0; l < kBodyLegs; ++l) {
      const double dz = planner.HipDz(l, p);
      const double r = x[Z(k)] + dz - foot_z[k * kBodyLegs + l] - wanted;
      const Eigen::Vector3d& hip = planner.hip_B(l);
      const double dr = -std::cos(p) * hip.x() - std::sin(p) * hip.z();
      h(0, 0) += 2.0 * wh;
      h(1, 0) += 2.0 * wh * dr;
      h(1, 1) += 2.0 * wh * (dr * dr - r * dz);
    }
    h(0, 1) = h(1, 0);
  };
  for (int k = 0; k < n; ++k) height.hessian_pairs.emplace_back(k, k);
  prog->AddNonlinearCost(height);
}

// A stance row in a knot's constraint: which of its sides are there and where the first goes.
struct KnotRow {
  std::size_t row = 0;
  std::array<bool, 2> on{};
  int out = 0;
};

// The selected acceleration rows (linear) and bound sides (one nonlinear constraint per knot,
// on that knot's block, each side a margin >= 0).
RowMap AddConstraints(const WindowData& d, const Selection& sel, const std::vector<optim::VariableBlock>& blocks,
                      optim::Program* prog) {
  const BodyPlannerSettings& set = d.planner->settings();
  const int n = d.n, rows_per = n - 2;
  RowMap map;
  std::vector<int>& accel_rows = map.accel;
  for (int r = 0; r < 3 * rows_per; ++r) {
    if (sel.accel[static_cast<std::size_t>(r)]) accel_rows.push_back(r);
  }
  if (!accel_rows.empty()) {
    const int m = static_cast<int>(accel_rows.size());
    std::vector<optim::LinearTerm> terms;
    for (int k = 0; k < n; ++k) terms.emplace_back(blocks[static_cast<std::size_t>(k)], Eigen::MatrixXd::Zero(m, 3));
    Eigen::VectorXd hi(m);
    for (int i = 0; i < m; ++i) {
      const int q = accel_rows[static_cast<std::size_t>(i)] / rows_per, k = accel_rows[static_cast<std::size_t>(i)] % rows_per;
      terms[static_cast<std::size_t>(k)].second(i, q) = 1.0;
      terms[static_cast<std::size_t>(k + 1)].second(i, q) = -2.0;
      terms[static_cast<std::size_t>(k + 2)].second(i, q) = 1.0;
      hi[i] = AccelLimit(set, q);
    }
    prog->AddLinearConstraint(terms, -hi, hi, "acceleration");
  }

  for (std::size_t first = 0; first < d.rows.size();) {
    std::size_t last = first;
    while (last < d.rows.size() && d.rows[last].knot == d.rows[first].knot) ++last;
    // This knot's stance rows with a selected side; each is evaluated once per point (one
    // HipHeight call gives both sides) and writes its selected sides in order.
    std::vector<KnotRow> knot_rows;
    int m = 0;
    for (std::size_t i = first; i < last; ++i) {
      const std::array<bool, 2>& on = sel.sides[i];
      if (!on[0] && !on[1]) continue;
      knot_rows.push_back({i, on, m});
      m += static_cast<int>(on[0]) + static_cast<int>(on[1]);
      for (int side = 0; side < 2; ++side) {
        if (on[static_cast<std::size_t>(side)]) map.sides.emplace_back(i, side);
      }
    }
    const int k = d.rows[first].knot;
    first = last;
    if (m == 0) continue;
    optim::NonlinearConstraint limits;
    limits.name = "hip_bounds" + std::to_string(k);
    limits.blocks = {blocks[static_cast<std::size_t>(k)]};
    limits.lower = Eigen::VectorXd::Zero(m);
    limits.upper = Eigen::VectorXd::Constant(m, optim::kInf);
    limits.value = [&d, knot_rows](const Eigen::VectorXd& x, Eigen::Ref<Eigen::VectorXd> c) {
      for (const KnotRow& kr : knot_rows) {
        const Eigen::Vector2d margins = d.Margins(d.rows[kr.row], x);
        int out = kr.out;
        for (int side = 0; side < 2; ++side) {
          if (kr.on[static_cast<std::size_t>(side)]) c[out++] = margins[side];
        }
      }
    };
    // d/dz is exact (+1 for h - lo, -1 for hi - h); pitch and shift by central differences.
    limits.jacobian = [&d, knot_rows, k](const Eigen::VectorXd& x, int, Eigen::Ref<Eigen::MatrixXd> jac) {
      const double z = x[Z(k)], p = x[P(k)], s = x[S(k)], e = kFiniteStep;
      for (const KnotRow& kr : knot_rows) {
        const StanceRow& r = d.rows[kr.row];
        const Eigen::Vector2d dp = (d.Margins(r, z, p + e, s) - d.Margins(r, z, p - e, s)) / (2.0 * e);
        const Eigen::Vector2d ds = (d.Margins(r, z, p, s + e) - d.Margins(r, z, p, s - e)) / (2.0 * e);
        int out = kr.out;
        for (int side = 0; side < 2; ++side) {
          if (kr.on[static_cast<std::size_t>(side)]) jac.row(out++) << (side == 0 ? 1.0 : -1.0), dp[side], ds[side];
        }
      }
    };
    // The margins' curvature in (pitch, shift) by second differences over the same stencil:
    // the hip's sin/cos (the hip height is linear in z) and the blended slope changes of the
    // tabulated bounds near a cell edge, which a Hessian without them would miss there.
    limits.hessian = [&d, knot_rows, k](const Eigen::VectorXd& x, const Eigen::Ref<const Eigen::VectorXd>& w, int, int,
                                        Eigen::Ref<Eigen::MatrixXd> h) {
      h.setZero();
      const double z = x[Z(k)], p = x[P(k)], s = x[S(k)], e = kFiniteStep;
      for (const KnotRow& kr : knot_rows) {
        // This row's sides weighted by their multipliers: one combined margin to differentiate.
        Eigen::Vector2d weight = Eigen::Vector2d::Zero();
        int out = kr.out;
        for (int side = 0; side < 2; ++side) {
          if (kr.on[static_cast<std::size_t>(side)]) weight[side] = w[out++];
        }
        if (weight.isZero()) continue;
        const StanceRow& r = d.rows[kr.row];
        const auto f = [&](double dp, double ds) { return weight.dot(d.Margins(r, z, p + dp, s + ds)); };
        const double c = f(0.0, 0.0);
        h(1, 1) += (f(e, 0.0) - 2.0 * c + f(-e, 0.0)) / (e * e);
        h(2, 2) += (f(0.0, e) - 2.0 * c + f(0.0, -e)) / (e * e);
        const double ps = (f(e, e) - f(e, -e) - f(-e, e) + f(-e, -e)) / (4.0 * e * e);
        h(2, 1) += ps;
        h(1, 2) += ps;
      }
    };
    prog->AddNonlinearConstraint(limits);
  }
  return map;
}

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

BodyState Lerp(const BodyState& a, const BodyState& b, double f) {
  const auto mix = [f](double u, double v) { return u + f * (v - u); };
  BodyState s;
  s.t = mix(a.t, b.t);
  s.x = mix(a.x, b.x);
  s.y = mix(a.y, b.y);
  s.z = mix(a.z, b.z);
  s.pitch = mix(a.pitch, b.pitch);
  s.yaw = mix(a.yaw, b.yaw);
  s.com_shift = mix(a.com_shift, b.com_shift);
  s.com_shift_y = mix(a.com_shift_y, b.com_shift_y);
  return s;
}

// Moves knot 0 of `knots` to `state` and fades the difference out over the next knots, (1 - k/m)^2
// for k < m, with m long enough that the fade's acceleration 2 |delta| / m^2 is half the limit:
// a guess whose knot 0 alone jumps breaks the acceleration limits at the start (the state a loop
// measures is rarely where the previous plan put it), and Ipopt then crawls out of that corner
// in short steps.
void BlendInState(const BodyState& state, const Eigen::Vector3d& accel_limits, std::vector<BodyState>* knots) {
  const int n = static_cast<int>(knots->size());
  BodyState& first = knots->front();
  const Eigen::Vector3d delta(state.z - first.z, state.pitch - first.pitch, state.com_shift - first.com_shift);
  const double t0 = first.t;
  first = state;
  first.t = t0;
  for (int q = 0; q < 3; ++q) {
    const double m = std::clamp(std::ceil(std::sqrt(4.0 * std::abs(delta[q]) / accel_limits[q])), 1.0, n - 1.0);
    for (int k = 1; k < m; ++k) {
      const double w = (1.0 - k / m) * (1.0 - k / m);
      BodyState& b = (*knots)[static_cast<std::size_t>(k)];
      (q == 0 ? b.z : q == 1 ? b.pitch : b.com_shift) += w * delta[q];
    }
  }
}

void CheckSolution(const BodyNlpSolution& s) {
  const std::size_t n = s.knots.size();
  if (n < 3) throw std::invalid_argument("BodyNlpSolution::knots: needs at least 3 knots");
  const auto sized = [](std::size_t got, std::size_t want, const char* field) {
    if (got != want) {
      throw std::invalid_argument(std::string("BodyNlpSolution::") + field + ": " + std::to_string(got) +
                                  " entries, the knots need " + std::to_string(want));
    }
  };
  sized(s.stance_foothold.size(), n * kBodyLegs, "stance_foothold");
  sized(s.stance_duals.size(), n * kBodyLegs, "stance_duals");
  sized(s.accel_duals.size(), 3 * (n - 2), "accel_duals");
  sized(s.bound_duals.size(), 3 * n, "bound_duals");
}

}  // namespace

BodyNlpSolution ShiftBodyNlpSolution(const BodyNlpSolution& previous, double t0, const BodyPlannerSettings& settings,
                                     const BodyState& state) {
  CheckSolution(previous);
  const double knot_dt = settings.knot_dt;
  const Eigen::Vector3d accel_limits(AccelLimit(settings, 0), AccelLimit(settings, 1), AccelLimit(settings, 2));
  // Half a microsecond of slack: a loop adding its period to t0 rounds.
  if (!(t0 >= previous.t0 - 5e-7)) throw std::invalid_argument("t0: before the previous solution's t0");
  const int n = static_cast<int>(previous.knots.size());
  const double shift = std::max(0.0, (t0 - previous.t0) / knot_dt);  // in previous knots
  BodyNlpSolution s;
  s.t0 = t0;
  s.knots.resize(static_cast<std::size_t>(n));
  s.stance_foothold.assign(static_cast<std::size_t>(n * kBodyLegs), -1);
  s.stance_duals.assign(static_cast<std::size_t>(n * kBodyLegs), {0.0, 0.0});
  s.accel_duals.assign(static_cast<std::size_t>(3 * (n - 2)), 0.0);
  s.bound_duals.assign(static_cast<std::size_t>(3 * n), 0.0);
  for (int k = 0; k < n; ++k) {
    // Knot k of the new window is at previous knot k + shift: the point interpolated there, or
    // beyond the end extrapolated from the last two knots (holding the last knot instead made a
    // velocity kink whose acceleration row Ipopt first had to leave: 3.75 iterations instead of 3.25
    // on average in the bench); the multipliers of the previous knot nearest to it.
    const double at = k + shift;
    const int segment = std::min(static_cast<int>(std::floor(at)), n - 2);
    BodyState& knot = s.knots[static_cast<std::size_t>(k)];
    knot = Lerp(previous.knots[static_cast<std::size_t>(segment)], previous.knots[static_cast<std::size_t>(segment + 1)],
                at - segment);
    knot.pitch = std::clamp(knot.pitch, -settings.max_pitch, settings.max_pitch);
    knot.com_shift = std::clamp(knot.com_shift, -settings.max_shift, settings.max_shift);
    knot.t = t0 + k * knot_dt;
    const int nearest = static_cast<int>(std::lround(at));
    if (nearest > n - 1) continue;  // a knot the previous window did not reach: multipliers 0
    const auto at_index = [](int i) { return static_cast<std::size_t>(i); };
    for (int l = 0; l < kBodyLegs; ++l) {
      s.stance_foothold[at_index(k * kBodyLegs + l)] = previous.stance_foothold[at_index(nearest * kBodyLegs + l)];
      s.stance_duals[at_index(k * kBodyLegs + l)] = previous.stance_duals[at_index(nearest * kBodyLegs + l)];
    }
    for (int i = 0; i < 3; ++i) s.bound_duals[at_index(3 * k + i)] = previous.bound_duals[at_index(3 * nearest + i)];
    if (k + 2 < n && nearest + 2 < n) {
      for (int q = 0; q < 3; ++q) {
        s.accel_duals[at_index(q * (n - 2) + k)] = previous.accel_duals[at_index(q * (n - 2) + nearest)];
      }
    }
  }
  BlendInState(state, accel_limits, &s.knots);
  return s;
}

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
  const BodyPlanCheck check = CheckBodyTrajectory(bounds, planner.schedule(), plan.body, settings.clearance_margin);
  if (!check.ok()) failure = "body NLP re-check: " + check.first_violation;
  plan.status = failure.empty() ? PlanStatus::kOk : PlanStatus::kInfeasible;
  plan.status_reason = failure;
  plan.timing_us.emplace_back("body_nlp", std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count());
  if (summary != nullptr) *summary = worst;
  return plan;
}

}  // namespace stairplan
