#include "stairplan/planning/body/body_qp.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "stairplan/planning/body/difference_matrices.h"

namespace stairplan {

namespace {

// Curvature of the relaxation's cost: the dual active-set solver needs a positive definite
// Hessian; against kRelaxPenalty it changes nothing.
constexpr double kRelaxCurvature = 1.0;
// Gravity for the support rows' pendulum [m/s^2].
constexpr double kZmpGravity = 9.81;

// Moves the states of a block of `per_knot` entries per knot `knots` knots earlier; the last
// `knots` knots keep theirs.
void ShiftKnots(std::vector<optim::ActiveSide>* states, int start, int size, int per_knot, int knots) {
  const int offset = per_knot * knots;
  for (int i = start; i < start + size - offset; ++i) (*states)[static_cast<std::size_t>(i)] = (*states)[static_cast<std::size_t>(i + offset)];
}

}  // namespace

BodyQp::BodyQp(const BodyPlannerSettings& settings, const std::array<double, kBodyLegs>& row_coefficients,
               bool stance_rows, double zmp_height, double shift_along_travel)
    : knots_(settings.knots),
      settings_(settings),
      c_(row_coefficients),
      lateral_apart_(settings.stability_margin < 0.0 && !stance_rows),
      accel_curvature_(2.0 * settings.acceleration_weight /
                       (settings.knot_dt * settings.knot_dt * settings.knot_dt * settings.knot_dt)) {
  settings_.Validate();
  if (!(zmp_height >= 0.0 && zmp_height < 10.0)) throw std::invalid_argument("BodyQp: zmp_height must be in [0, 10) m");
  zmp_weight_ = zmp_height / (kZmpGravity * settings_.knot_dt * settings_.knot_dt);
  if (shift_along_travel != 1.0 && shift_along_travel != -1.0) {
    throw std::invalid_argument("BodyQp: shift_along_travel must be 1 or -1");
  }
  const int n = knots_;
  for (int l = 0; l < kBodyLegs; ++l) {
    int g = 0;
    while (g < groups_ && std::abs(group_c_[static_cast<std::size_t>(g)] - c_[static_cast<std::size_t>(l)]) > kRowMergeTolerance) ++g;
    if (g == groups_) group_c_[static_cast<std::size_t>(groups_++)] = c_[static_cast<std::size_t>(l)];
    group_of_[static_cast<std::size_t>(l)] = g;
  }
  for (int g = 0; g < groups_; ++g) {
    double sum = 0.0;
    int count = 0;
    for (int l = 0; l < kBodyLegs; ++l) {
      if (group_of_[static_cast<std::size_t>(l)] == g) sum += c_[static_cast<std::size_t>(l)], ++count;
    }
    group_c_[static_cast<std::size_t>(g)] = sum / count;
  }
  for (int l = 0; l < kBodyLegs; ++l) c_[static_cast<std::size_t>(l)] = group_c_[static_cast<std::size_t>(group_of_[static_cast<std::size_t>(l)])];
  const double dt = settings_.knot_dt;
  z_ = program_.AddVariables("height", n);
  pitch_ = program_.AddVariables("pitch", n);
  shift_ = program_.AddVariables("com_shift", n);
  optim::Program& lateral_program = lateral_apart_ ? lateral_program_ : program_;
  lateral_ = lateral_program.AddVariables("com_shift_y", n);
  if (stance_rows) {
    relax_ = program_.AddVariables("relax", n);
    program_.SetVariableBounds(relax_, Eigen::VectorXd::Zero(n), Eigen::VectorXd::Ones(n));
  }

  // Costs (0.5 x'Hx + g'x: a weight w on (a'x - r)^2 adds 2w aa' to H).
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(n, n);
  double sum_c = 0.0, sum_c2 = 0.0;
  for (double c : c_) sum_c += c, sum_c2 += c * c;
  const double wh = settings_.height_weight;
  const Eigen::MatrixXd d1 = FirstDifferences(n), d2 = SecondDifferences(n);
  Eigen::MatrixXd smooth = 2.0 * settings_.velocity_weight / (dt * dt) * d1.transpose() * d1 +
                           accel_curvature_ * d2.transpose() * d2;
  smooth(1, 1) += accel_curvature_;  // knot 0's term (`straight`)
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  program_.AddQuadraticCost(z_, 2.0 * wh * kBodyLegs * identity + smooth, zero);
  program_.AddQuadraticCost(pitch_, (2.0 * wh * sum_c2 + 2.0 * settings_.pitch_weight) * identity + smooth, zero);
  program_.AddCrossQuadraticCost(z_, pitch_, 2.0 * wh * sum_c * identity);
  program_.AddQuadraticCost(shift_, 2.0 * settings_.shift_weight * identity + smooth, zero);
  lateral_program.AddQuadraticCost(lateral_, 2.0 * settings_.lateral_weight * identity + smooth, zero);
  if (stance_rows) program_.AddQuadraticCost(relax_, 2.0 * kRelaxCurvature * identity, Eigen::VectorXd::Constant(n, kRelaxPenalty));

  // Hip rows: z_k + c_g pitch_k, row k * groups + g.
  Eigen::MatrixXd a_z = Eigen::MatrixXd::Zero(groups_ * n, n), a_p = a_z;
  for (int k = 0; k < n; ++k) {
    for (int g = 0; g < groups_; ++g) {
      a_z(k * groups_ + g, k) = 1.0;
      a_p(k * groups_ + g, k) = group_c_[static_cast<std::size_t>(g)];
    }
  }
  const Eigen::VectorXd free_lo = Eigen::VectorXd::Constant(groups_ * n, -optim::kInf);
  const Eigen::VectorXd free_hi = Eigen::VectorXd::Constant(groups_ * n, optim::kInf);
  hip_rows_ = program_.AddLinearConstraint({{z_, a_z}, {pitch_, a_p}}, free_lo, free_hi, "hip_height");

  // Acceleration limits (the sideways shift's with its own variables).
  const Eigen::MatrixXd zeros = Eigen::MatrixXd::Zero(n - 2, n);
  Eigen::MatrixXd accel_z(3 * (n - 2), n), accel_p(3 * (n - 2), n), accel_s(3 * (n - 2), n);
  accel_z << d2, zeros, zeros;
  accel_p << zeros, d2, zeros;
  accel_s << zeros, zeros, d2;
  Eigen::VectorXd accel_hi(3 * (n - 2));
  accel_hi << Eigen::VectorXd::Constant(n - 2, settings_.max_height_accel * dt * dt),
      Eigen::VectorXd::Constant(n - 2, settings_.max_pitch_accel * dt * dt),
      Eigen::VectorXd::Constant(n - 2, settings_.max_shift_accel * dt * dt);
  accel_rows_ = program_.AddLinearConstraint({{z_, accel_z}, {pitch_, accel_p}, {shift_, accel_s}}, -accel_hi, accel_hi,
                                             "acceleration");
  const Eigen::VectorXd lateral_accel = Eigen::VectorXd::Constant(n - 2, settings_.max_lateral_accel * dt * dt);
  lateral_accel_rows_ =
      lateral_program.AddLinearConstraint({{lateral_, d2}}, -lateral_accel, lateral_accel, "lateral_acceleration");
  // With stance rows the pitch and the weight shifts come to rest at the horizon's end: a plan
  // ending in motion toward a limit leaves the next cycle, whose last knot lies beyond, no way to
  // stop within the acceleration limits (the plan shifted by a cycle is then outside the QP's
  // feasible set). Without them (the default) the NLP refinement's test found Ipopt failing from
  // such plans.
  if (stance_rows) {
    Eigen::MatrixXd last = Eigen::MatrixXd::Zero(1, n);
    last(0, n - 2) = -1.0;
    last(0, n - 1) = 1.0;
    const Eigen::VectorXd rest = Eigen::VectorXd::Zero(1);
    program_.AddLinearConstraint({{pitch_, last}}, rest, rest, "pitch_at_rest");
    program_.AddLinearConstraint({{shift_, last}}, rest, rest, "shift_at_rest");
    program_.AddLinearConstraint({{lateral_, last}}, rest, rest, "lateral_at_rest");
  }

  // Progress rows (with stance rows): the body moves against the travel only by what the retreat
  // variables pay for, at a price far below the relaxation's (the support and leg rows come first)
  // and far above what moving back could gain the other costs.
  if (stance_rows) {
    retreat_ = program_.AddVariables("retreat", n - 1);
    program_.SetVariableBounds(retreat_, Eigen::VectorXd::Zero(n - 1), Eigen::VectorXd::Constant(n - 1, optim::kInf));
    program_.AddQuadraticCost(retreat_, 2.0 * kRelaxCurvature * Eigen::MatrixXd::Identity(n - 1, n - 1),
                              Eigen::VectorXd::Constant(n - 1, kRetreatPenalty));
    give_ = program_.AddVariables("margin_given", n);
    max_give_ = std::max(settings_.stability_margin - settings_.min_stability_margin, 0.0);
    program_.SetVariableBounds(give_, Eigen::VectorXd::Zero(n), Eigen::VectorXd::Constant(n, max_give_));
    program_.AddQuadraticCost(give_, 2.0 * kRelaxCurvature * identity,
                              Eigen::VectorXd::Constant(n, kMarginGivePenalty));
    if (zmp_weight_ > 0.0) {
      excursion_ = program_.AddVariables("zmp_excursion", n);
      program_.SetVariableBounds(excursion_, Eigen::VectorXd::Zero(n), Eigen::VectorXd::Constant(n, optim::kInf));
      program_.AddQuadraticCost(excursion_, 2.0 * kRelaxCurvature * identity,
                                Eigen::VectorXd::Constant(n, kZmpExcursionPenalty));
    }
    const Eigen::VectorXd free = Eigen::VectorXd::Constant(n - 1, optim::kInf);
    progress_rows_ = program_.AddLinearConstraint({{shift_, shift_along_travel * d1}, {retreat_, Eigen::MatrixXd::Identity(n - 1, n - 1)}},
                                                  -free, free, "progress");
  }
  progress_lo.setConstant(n - 1, -optim::kInf);
  progress_hi_.setConstant(n - 1, optim::kInf);

  // Support rows: free until the planner gives them feet (none when the lateral QP is apart).
  const int support_count = lateral_apart_ ? 0 : kSupportRows * n;
  const Eigen::MatrixXd no_coefficients = Eigen::MatrixXd::Zero(support_count, n);
  const Eigen::VectorXd support_free = Eigen::VectorXd::Constant(support_count, optim::kInf);
  // The ZMP's rows (with leg rows and a pendulum height) neither give margin nor relax: the ZMP
  // leaves the polygon by the excursion, and the margin is the COM's.
  const bool zmp = stance_rows && zmp_weight_ > 0.0 && !lateral_apart_;
  for (SupportFamily* family : {&com_support_, &zmp_support_}) {
    const bool is_zmp = family == &zmp_support_;
    family->zmp = is_zmp;
    const char* name = is_zmp ? "zmp_support" : "support";
    if (lateral_apart_ || (is_zmp && !zmp)) {
      family->rows = {name, program_.num_rows(), 0};
    } else {
      std::vector<optim::LinearTerm> terms{{shift_, no_coefficients}, {lateral_, no_coefficients}};
      if (stance_rows && !is_zmp) {
        terms.push_back({relax_, no_coefficients});
        terms.push_back({give_, no_coefficients});
      }
      if (is_zmp) terms.push_back({excursion_, no_coefficients});
      family->rows = program_.AddLinearConstraint(terms, -support_free, support_free, name);
    }
    for (Eigen::VectorXd* v : {&family->pushed_cx, &family->pushed_cy, &family->pushed_sigma, &family->pushed_give}) {
      v->setZero(kSupportRows * n);
    }
  }
  support_cx.setZero(kSupportRows * n);
  support_cy.setZero(kSupportRows * n);
  support_sigma.setZero(kSupportRows * n);
  support_lo.setConstant(kSupportRows * n, -optim::kInf);
  support_hi.setConstant(kSupportRows * n, optim::kInf);
  zmp_lo = support_lo;
  zmp_hi = support_hi;
  single_row_ = {com_support_.rows.name, com_support_.rows.start, 1};

  // Stance and clearance rows: free until the planner linearises a stance leg into them.
  const int legs_rows = stance_rows ? kBodyLegs * n : 0;
  AddKnotRows("stance", kStanceRows * legs_rows, kStanceRows * kBodyLegs, &stance, &stance_);
  AddKnotRows("clearance", stance_rows ? kClearanceRows * n : 0, kClearanceRows, &clearance, &clearance_);
  AddKnotRows("passing_clearance", stance_rows ? kClearanceRows * n : 0, kClearanceRows, &passing, &passing_, true);

  for (Eigen::VectorXd* v : {&z_lo, &pitch_lo, &shift_lo, &lateral_lo}) v->setConstant(n, -optim::kInf);
  for (Eigen::VectorXd* v : {&z_hi, &pitch_hi, &shift_hi, &lateral_hi}) v->setConstant(n, optim::kInf);
  hip_lo = free_lo;
  hip_hi = free_hi;
  height_ref.setZero(kBodyLegs * n);
  pitch_ref.setZero(n);
  shift_ref.setZero(n);
  lateral_ref.setZero(n);
  g_z_.setZero(n);
  g_pitch_.setZero(n);
  g_shift_.setZero(n);
  g_lateral_.setZero(n);
}

std::array<double, 3> BodyQp::ZmpStencil(int k) const {
  const double a = zmp_weight_;
  if (k == knots_ - 1) return {-a, 1.0 + a, 0.0};
  return {-a, 1.0 + 2.0 * a, -a};
}

std::array<int, 2> BodyQp::SupportPair(int r) {
  static constexpr std::array<std::array<int, 2>, kSupportRows> kPairs{{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}};
  return kPairs[static_cast<std::size_t>(r)];
}

void BodyQp::PushInputs() {
  const double wh = settings_.height_weight;
  for (int k = 0; k < knots_; ++k) {
    double gz = 0.0, gp = 0.0;
    for (int l = 0; l < kBodyLegs; ++l) {
      const double r = height_ref[k * kBodyLegs + l];
      gz -= 2.0 * wh * r;
      gp -= 2.0 * wh * c_[static_cast<std::size_t>(l)] * r;
    }
    g_z_[k] = gz;
    g_pitch_[k] = gp - 2.0 * settings_.pitch_weight * pitch_ref[k];
    g_shift_[k] = -2.0 * settings_.shift_weight * shift_ref[k];
    g_lateral_[k] = -2.0 * settings_.lateral_weight * lateral_ref[k];
  }
  // Knot 0's acceleration term, w (x_1 - straight)^2 / dt^4.
  g_z_[1] -= accel_curvature_ * straight[0];
  g_pitch_[1] -= accel_curvature_ * straight[1];
  g_shift_[1] -= accel_curvature_ * straight[2];
  g_lateral_[1] -= accel_curvature_ * straight[3];
  program_.SetLinearCost(z_, g_z_);
  program_.SetLinearCost(pitch_, g_pitch_);
  program_.SetLinearCost(shift_, g_shift_);
  optim::Program& lateral_program = lateral_apart_ ? lateral_program_ : program_;
  lateral_program.SetLinearCost(lateral_, g_lateral_);
  program_.SetVariableBounds(z_, z_lo, z_hi);
  program_.SetVariableBounds(pitch_, pitch_lo, pitch_hi);
  program_.SetVariableBounds(shift_, shift_lo, shift_hi);
  lateral_program.SetVariableBounds(lateral_, lateral_lo, lateral_hi);
  program_.SetConstraintBounds(hip_rows_, hip_lo, hip_hi);
  if (lateral_apart_) return;  // no support or stance rows
  PushSupportRows();
  PushProgressRows();
  PushKnotRows(stance, &stance_);
  PushKnotRows(clearance, &clearance_);
  PushKnotRows(passing, &passing_);
}

void BodyQp::AddKnotRows(const char* name, int count, int per_knot, KnotRows* inputs, PushedRows* rows,
                         bool spans_next) {
  const int n = knots_;
  if (count > 0) {
    const Eigen::MatrixXd none = Eigen::MatrixXd::Zero(count, n);
    const Eigen::VectorXd free = Eigen::VectorXd::Constant(count, optim::kInf);
    rows->rows = program_.AddLinearConstraint(
        {{z_, none}, {pitch_, none}, {shift_, none}, {lateral_, none}, {relax_, none}}, -free, free, name);
  } else {
    rows->rows = {name, program_.num_rows(), 0};
  }
  rows->per_knot = per_knot;
  rows->spans_next = spans_next;
  rows->pushed.setZero(count, 5);
  inputs->a.setZero(count, 4);
  inputs->lo.setConstant(count, -optim::kInf);
  inputs->hi.setConstant(count, optim::kInf);
  inputs->sigma.setZero(count);
}

void BodyQp::KnotRows::RelaxAt(int first, int count, const Eigen::Vector4d& v) {
  for (int r = first; r < first + count; ++r) {
    const double value = a.row(r).dot(v);
    sigma[r] = lo[r] - value > 0.0 ? lo[r] - value : hi[r] - value < 0.0 ? hi[r] - value : 0.0;
  }
}

void BodyQp::SetCoefficient(const optim::ConstraintRows& row, const optim::VariableBlock& block, int k, double value) {
  program_.SetConstraintCoefficient(row, 0, block, k, value);
}

void BodyQp::SetStencil(const optim::ConstraintRows& row, const optim::VariableBlock& block, int k, double value) {
  const std::array<double, 3> w = ZmpStencil(k);
  const int first = std::max(k - 1, 0), last = std::min(k + 1, knots_ - 1);
  for (int j = first; j <= last; ++j) {
    program_.SetConstraintCoefficient(row, 0, block, j, w[static_cast<std::size_t>(j - k + 1)] * value);
  }
}

void BodyQp::PushSupportRows() {
  PushSupportFamily(&com_support_);
  PushSupportFamily(&zmp_support_);
}

void BodyQp::PushSupportFamily(SupportFamily* family) {
  if (family->rows.size == 0) return;
  // Only rows whose feet changed get new coefficients: the solver keeps its factorisation when
  // they are inactive (the planner changes a pair's feet only while its row is free).
  // The COM's rows give margin (give_) and relax; the ZMP's leave the polygon by the excursion.
  const Eigen::VectorXd& lo = family->zmp ? zmp_lo : support_lo;
  const Eigen::VectorXd& hi = family->zmp ? zmp_hi : support_hi;
  const Eigen::VectorXd* sigma = family->zmp ? nullptr : &support_sigma;
  const optim::VariableBlock& widen = family->zmp ? excursion_ : give_;
  const bool gives = widen.size > 0;
  const bool relaxes = relax_.size > 0 && sigma != nullptr;
  for (int row = 0; row < static_cast<int>(support_cx.size()); ++row) {
    const bool sigma_changed = relaxes && (*sigma)[row] != family->pushed_sigma[row];
    // The margin given up widens the row on its bounded side (a free row keeps what it had).
    const double give = hi[row] < optim::kInf ? -1.0 : lo[row] > -optim::kInf ? 1.0 : family->pushed_give[row];
    const bool give_changed = gives && give != family->pushed_give[row];
    if (support_cx[row] == family->pushed_cx[row] && support_cy[row] == family->pushed_cy[row] && !sigma_changed &&
        !give_changed) {
      continue;
    }
    const int k = row / kSupportRows;
    single_row_.start = family->rows.start + row;
    if (family->zmp) {
      SetStencil(single_row_, shift_, k, support_cx[row]);
      SetStencil(single_row_, lateral_, k, support_cy[row]);
    } else {
      SetCoefficient(single_row_, shift_, k, support_cx[row]);
      SetCoefficient(single_row_, lateral_, k, support_cy[row]);
    }
    if (sigma_changed) SetCoefficient(single_row_, relax_, k, (*sigma)[row]);
    if (give_changed) SetCoefficient(single_row_, widen, k, give);
    family->pushed_cx[row] = support_cx[row];
    family->pushed_cy[row] = support_cy[row];
    if (sigma_changed) family->pushed_sigma[row] = (*sigma)[row];
    family->pushed_give[row] = give;
  }
  program_.SetConstraintBounds(family->rows, lo, hi);
}

void BodyQp::PushProgressRows() {
  if (progress_rows_.size > 0) program_.SetConstraintBounds(progress_rows_, progress_lo, progress_hi_);
}

void BodyQp::PushKnotRows(const KnotRows& inputs, PushedRows* rows) {
  if (rows->rows.size == 0) return;
  // Free rows keep whatever coefficients they had: pushing them would only cost time.
  const std::array<const optim::VariableBlock*, 5> blocks{&z_, &pitch_, &shift_, &lateral_, &relax_};
  // A row's changed coefficients go in at once: 4 variables at one or two knots, and relax.
  std::array<optim::Program::Coefficient, 9> changed;
  for (int row = 0; row < rows->rows.size; ++row) {
    if (inputs.lo[row] == -optim::kInf && inputs.hi[row] == optim::kInf) continue;
    const int k = row / rows->per_knot;
    int count = 0;
    for (int v = 0; v < 5; ++v) {
      const double value = v < 4 ? inputs.a(row, v) : inputs.sigma[row];
      if (value == rows->pushed(row, v)) continue;
      const int column = blocks[static_cast<std::size_t>(v)]->start + k;
      if (rows->spans_next && v < 4) {
        changed[static_cast<std::size_t>(count++)] = {column, 0.5 * value};
        changed[static_cast<std::size_t>(count++)] = {column + 1, 0.5 * value};
      } else {
        changed[static_cast<std::size_t>(count++)] = {column, value};
      }
      rows->pushed(row, v) = value;
    }
    program_.SetRowCoefficients(rows->rows, row, changed.data(), count);
  }
  program_.SetConstraintBounds(rows->rows, inputs.lo, inputs.hi);
}

void BodyQp::Solve(double time_limit_s, optim::SolveResult* result) {
  PushInputs();
  solver_.settings().time_limit_s = time_limit_s > 0.0 ? time_limit_s : 1e-9;
  solver_.Solve(program_, result);
  if (!lateral_apart_) return;
  // The sideways shift's own QP, in what is left of the time; its outcome joins the result's.
  const double left_s = time_limit_s - 1e-6 * result->info.solve_time_us;
  lateral_solver_.settings().time_limit_s = left_s > 0.0 ? left_s : 1e-9;
  lateral_solver_.Solve(lateral_program_, &lateral_result_);
  result->info.iterations += lateral_result_.info.iterations;
  if (result->solved() && !lateral_result_.solved()) result->status = lateral_result_.status;
}

void BodyQp::ShiftWarmStart(const optim::ActiveSet& last, int knots) {
  const int n = knots_;
  knots = std::min(knots, n - 1);
  if (knots <= 0) return;
  if (last.rows.size() != static_cast<std::size_t>(program_.num_rows()) ||
      last.bounds.size() != static_cast<std::size_t>(program_.num_variables())) {
    return;
  }
  shifted_ = last;
  // The sideways shift's own QP, when apart, keeps its solver's last active set.
  if (!lateral_apart_) {
    ShiftKnots(&shifted_.bounds, lateral_.start, lateral_.size, 1, knots);
    ShiftKnots(&shifted_.rows, lateral_accel_rows_.start, lateral_accel_rows_.size, 1, knots);
  }
  for (const optim::VariableBlock* block : {&z_, &pitch_, &shift_, &relax_, &retreat_, &give_, &excursion_}) {
    ShiftKnots(&shifted_.bounds, block->start, block->size, 1, knots);
  }
  ShiftKnots(&shifted_.rows, hip_rows_.start, hip_rows_.size, groups_, knots);
  for (int f = 0; f < 3; ++f) ShiftKnots(&shifted_.rows, accel_rows_.start + f * (n - 2), n - 2, 1, knots);
  ShiftKnots(&shifted_.rows, progress_rows_.start, progress_rows_.size, 1, knots);
  ShiftKnots(&shifted_.rows, com_support_.rows.start, com_support_.rows.size, kSupportRows, knots);
  ShiftKnots(&shifted_.rows, zmp_support_.rows.start, zmp_support_.rows.size, kSupportRows, knots);
  ShiftKnots(&shifted_.rows, stance_.rows.start, stance_.rows.size, stance_.per_knot, knots);
  ShiftKnots(&shifted_.rows, clearance_.rows.start, clearance_.rows.size, clearance_.per_knot, knots);
  ShiftKnots(&shifted_.rows, passing_.rows.start, passing_.rows.size, passing_.per_knot, knots);
  solver_.SetWarmStart(shifted_);
}

Eigen::VectorBlock<const Eigen::VectorXd> BodyQp::LateralOf(const optim::SolveResult& result) const {
  const Eigen::VectorXd& x = lateral_apart_ ? lateral_result_.x : result.x;
  return x.segment(lateral_.start, knots_);
}

}  // namespace stairplan
