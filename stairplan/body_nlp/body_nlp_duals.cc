// The body NLP's multipliers, kept by what they constrain (WindowDuals): to and from a round's
// program rows, and to and from a BodyNlpSolution's per-knot layout, so that a warm start finds
// them across screening rounds and across windows.
#include <cstddef>

#include "stairplan/body_nlp/body_nlp_internal.h"

namespace stairplan {
namespace body_nlp_detail {

WindowDuals ZeroDuals(const WindowData& d) {
  WindowDuals w;
  w.sides.assign(d.rows.size(), {0.0, 0.0});
  w.accel.assign(static_cast<std::size_t>(3 * (d.n - 2)), 0.0);
  w.bounds = Eigen::VectorXd::Zero(3 * d.n);
  return w;
}

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

}  // namespace body_nlp_detail
}  // namespace stairplan
