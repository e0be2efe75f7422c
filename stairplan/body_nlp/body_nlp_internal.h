// What the body NLP's files share and its users never see: the window's data (per knot, the
// stance rows and their exact margins), which constraints a screening round holds, the
// multipliers kept by what they constrain, and the functions that pass them between the files
// (body_nlp_window.cc, body_nlp_program.cc, body_nlp_duals.cc, body_nlp_solve.cc). Not part of
// the public API in body_nlp.h.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "stairplan/body_nlp/body_nlp.h"
#include "stairplan/solvers/ipopt_solver.h"
#include "stairplan/optim/program.h"
#include "stairplan/optim/solve_result.h"

namespace stairplan {
namespace body_nlp_detail {

struct StanceRow {
  int knot = 0, leg = 0, foothold = 0;
  double contact_x = 0.0, contact_z = 0.0;
};

// Variables: one block per knot, [z, pitch, shift]; each knot's constraints then touch only
// its own block, so the solvers see a sparse Jacobian instead of a dense one.
inline int Z(int k) { return 3 * k; }
inline int P(int k) { return 3 * k + 1; }
inline int S(int k) { return 3 * k + 2; }

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

// The multipliers of a window's constraints by what they constrain (its stance rows' two sides,
// the acceleration rows, the variables) rather than by program row, since each round selects
// other rows and the next cycle's window, shifted in time, has other knots. Signs as in
// optim::SolveResult; a constraint a round left out has 0 (it was inactive there).
struct WindowDuals {
  std::vector<std::array<double, 2>> sides;  // per stance row: lowest- and highest-hip side
  std::vector<double> accel;                 // per acceleration row q * (n - 2) + k
  Eigen::VectorXd bounds;                    // per variable
};

// Where a round's program holds the selected constraints: the acceleration row of each linear
// row and the (stance row, side) of each nonlinear row, in the program's order.
struct RowMap {
  std::vector<int> accel;
  std::vector<std::pair<std::size_t, int>> sides;
};

// body_nlp_window.cc: the window's data and the constraint screening.
WindowData Prepare(BodyPlanner& planner, double t0, int n);
// The acceleration limit of quantity q (0 height, 1 pitch, 2 shift) [per knot^2].
double AccelLimit(const BodyPlannerSettings& set, int q);
int Screen(const WindowData& d, const Eigen::VectorXd& x, double margin, double fraction, Selection* sel);

// body_nlp_program.cc: the costs and constraints of a round's program.
void AddCosts(const WindowData& d, const std::vector<optim::VariableBlock>& blocks, optim::Program* prog);
RowMap AddConstraints(const WindowData& d, const Selection& sel, const std::vector<optim::VariableBlock>& blocks,
                      optim::Program* prog);

// body_nlp_duals.cc: the multipliers between program rows, windows and solutions.
WindowDuals ZeroDuals(const WindowData& d);
optim::IpoptDualGuess ToProgram(const WindowDuals& w, const RowMap& map);
bool FromProgram(const WindowData& d, const optim::SolveResult& r, const RowMap& map, WindowDuals* w);
WindowDuals FromSolution(const WindowData& d, const BodyNlpSolution& s);
void ToSolution(const WindowData& d, const WindowDuals& w, BodyNlpSolution* s);

// body_nlp_solve.cc: one window's NLP, solved in screening rounds (`warm`: the multipliers to
// start from, or nullptr).
BodyNlpWindow SolveWindow(BodyPlanner& planner, const BodyNlpSettings& ns, double t0,
                          const std::vector<BodyState>& guess, const BodyNlpSolution* warm,
                          BodyNlpSolution* solution);

}  // namespace body_nlp_detail
}  // namespace stairplan
