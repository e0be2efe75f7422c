// The body NLP's program: the costs (references, smoothness, the exact hip heights with their
// Hessian) and the constraints (acceleration rows, the exact hip-height bounds with
// finite-difference derivatives) that a screening round's optim::Program holds.
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "stairplan/body_nlp/body_nlp_internal.h"
#include "stairplan/planning/body/difference_matrices.h"

namespace stairplan {
namespace body_nlp_detail {
namespace {

// Central-difference step of the tabulated bounds' derivatives [m or rad]. The bounds are
// bilinear per grid cell (0.03 m x 0.1 rad) and their slopes jump at cell edges; a step of a few
// percent of a cell blends the two slopes near an edge, so the derivatives the solvers see are
// continuous and a solution sitting on an edge converges instead of cycling across it (with
// 1e-5 Ipopt cycled there until its iteration limit). The values stay exact.
constexpr double kFiniteStep = 2e-3;

// A stance row in a knot's constraint: which of its sides are there and where the first goes.
struct KnotRow {
  std::size_t row = 0;
  std::array<bool, 2> on{};
  int out = 0;
};

}  // namespace

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

}  // namespace body_nlp_detail
}  // namespace stairplan
