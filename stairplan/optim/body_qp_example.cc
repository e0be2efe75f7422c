// The body-planner-shaped example QP: tracking costs with smoothing, banded kinematic rows.
#include "stairplan/optim/body_qp_example.h"

#include <cmath>

namespace stairplan::optim {
namespace {

constexpr double kDt = 0.05;          // knot spacing [s]
constexpr double kHalfLength = 0.3;   // hip to body centre [m]
constexpr double kRise = 0.17, kRun = 0.27, kSpeed = 0.25;

// Terrain height under a point x along the stairs.
double Ground(double x) { return x <= 0.0 ? 0.0 : kRise * std::floor(x / kRun + 1.0); }

}  // namespace

BodyQpExample MakeBodyQpExample(int knots) {
  BodyQpExample e;
  e.knots = knots;
  Program& p = e.program;
  e.height = p.AddVariables("height", knots);
  e.pitch = p.AddVariables("pitch", knots);
  e.shift = p.AddVariables("shift", knots);
  // Smoothness: second differences of height and pitch; tracking weights on top.
  Eigen::MatrixXd D2 = Eigen::MatrixXd::Zero(knots - 2, knots);
  for (int k = 0; k + 2 < knots; ++k) D2.row(k).segment(k, 3) << 1.0, -2.0, 1.0;
  const Eigen::MatrixXd smooth = D2.transpose() * D2 / (kDt * kDt);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(knots);
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(knots, knots);
  p.AddQuadraticCost(e.height, 100.0 * I + 0.01 * smooth, zero);
  p.AddQuadraticCost(e.pitch, 10.0 * I + 0.01 * smooth, zero);
  p.AddQuadraticCost(e.shift, 1.0 * I, zero);
  p.AddCrossQuadraticCost(e.height, e.shift, 0.1 * I);
  // Hip heights: z -+ L sin(pitch) ~ z -+ L pitch, within kinematic bands (set per cycle).
  Eigen::MatrixXd pitch_terms(2 * knots, knots), height_terms(2 * knots, knots);
  pitch_terms.setZero();
  height_terms.setZero();
  for (int k = 0; k < knots; ++k) {
    height_terms(2 * k, k) = 1.0;
    pitch_terms(2 * k, k) = kHalfLength;
    height_terms(2 * k + 1, k) = 1.0;
    pitch_terms(2 * k + 1, k) = -kHalfLength;
  }
  const Eigen::VectorXd wide = Eigen::VectorXd::Constant(2 * knots, 10.0);
  e.hip_heights = p.AddLinearConstraint({{e.height, height_terms}, {e.pitch, pitch_terms}}, -wide, wide, "hip_heights");
  // Rate limits between consecutive knots.
  Eigen::MatrixXd rate_h = Eigen::MatrixXd::Zero(2 * (knots - 1), knots);
  Eigen::MatrixXd rate_p = Eigen::MatrixXd::Zero(2 * (knots - 1), knots);
  for (int k = 0; k + 1 < knots; ++k) {
    rate_h(k, k) = -1.0;
    rate_h(k, k + 1) = 1.0;
    rate_p(knots - 1 + k, k) = -1.0;
    rate_p(knots - 1 + k, k + 1) = 1.0;
  }
  Eigen::VectorXd rate_limit(2 * (knots - 1));
  rate_limit.head(knots - 1).setConstant(0.4 * kDt);
  rate_limit.tail(knots - 1).setConstant(1.0 * kDt);
  e.rates = p.AddLinearConstraint({{e.height, rate_h}, {e.pitch, rate_p}}, -rate_limit, rate_limit, "rates");
  UpdateBodyQpExample(0, &e);
  return e;
}

void UpdateBodyQpExample(int cycle, BodyQpExample* e) {
  Program& p = e->program;
  const int n = e->knots;
  const double x0 = -0.3 + 0.003 * cycle;  // body position at this cycle
  for (int k = 0; k < n; ++k) {
    const double x = x0 + kSpeed * kDt * k;
    const double front = Ground(x + kHalfLength), rear = Ground(x - kHalfLength);
    const double z_ref = 0.5 * (front + rear) + 0.45;
    // Per-knot entries are written in place (unchecked access; Solve() validates the data).
    p.MutableLinearCost()[e->height.start + k] = -100.0 * z_ref;
    p.MutableLinearCost()[e->pitch.start + k] = -10.0 * std::atan2(front - rear, 2 * kHalfLength);
    p.MutableLinearCost()[e->shift.start + k] = -0.2 * std::sin(0.3 * (cycle + k));
    p.MutableRowLower()[e->hip_heights.start + 2 * k] = front + 0.30;
    p.MutableRowUpper()[e->hip_heights.start + 2 * k] = front + 0.52;
    p.MutableRowLower()[e->hip_heights.start + 2 * k + 1] = rear + 0.30;
    p.MutableRowUpper()[e->hip_heights.start + 2 * k + 1] = rear + 0.52;
    p.MutableVariableLower()[e->height.start + k] = rear + 0.25;
    p.MutableVariableUpper()[e->height.start + k] = front + 0.60;
    p.MutableVariableLower()[e->pitch.start + k] = -0.6;
    p.MutableVariableUpper()[e->pitch.start + k] = 0.6;
    p.MutableVariableLower()[e->shift.start + k] = -0.08;
    p.MutableVariableUpper()[e->shift.start + k] = 0.08;
  }
}

}  // namespace stairplan::optim
