// The body planner's QP (US 2020/0324412 A1 ("Robotically negotiating stairs") [0050]-[0052]): per
// knot the body height z, the pitch and the forward and sideways shifts of the centre of mass.
// Built once; every cycle the bounds and linear terms change, and the few support rows whose feet
// changed get new coefficients (inactive rows: ActiveSetQpSolver keeps its factorisation), so it
// re-solves warm without allocating.
//
//   min  sum_k [ sum_legs w_h (z_k + c_l pitch_k - height_ref_kl)^2       hip height above the feet
//              + w_p (pitch_k - pitch_ref_k)^2 + w_s (shift_k - shift_ref_k)^2 ]
//        + velocity and acceleration terms (finite differences over the knots)
//   s.t. hip_lo_kg <= z_k + c_g pitch_k <= hip_hi_kg    one row per knot and hip group
//        (legs whose hips share c, e.g. the front pair, share a row: half the rows to scan;
//        the solver copes with identical rows, tests/optim/active_set_degenerate_test.cc)
//        |second differences| <= max accel * dt^2        height, pitch, shift, lateral
//        with stance rows: pitch, shift and lateral at rest over the last two knots (the next
//        cycle can always stop), and progress rows (the body moves against the travel only as
//        far as the penalised retreat_k lets it: shift_{k+1} - shift_k + retreat_k >= minus the
//        neutral body's advance)
//        support_lo_kr <= cx_kr shift_k + cy_kr lateral_k (+ e_kr relax_k -+ give_k) <= support_hi_kr
//                                 one row per knot and pair r of legs (6): the COM on the inner
//                                 side of the support polygon's edge between the two feet, by the
//                                 stability margin less give_k (with stance rows: the margin the
//                                 knot gives up, at most stability_margin - min_stability_margin,
//                                 at kMarginGivePenalty per metre)
//        zmp_lo_kr <= sum_j w_kj (cx_kr shift_j + cy_kr lateral_j) -+ excursion_k <= zmp_hi_kr
//                                 with stance rows and a pendulum height h: the same edges for
//                                 the linear inverted pendulum's ZMP, COM - h/g COM'', over knots
//                                 k-1, k, k+1 (w = ZmpStencil(k)); knot 0's row too, which bounds
//                                 knot 1 against the body executed a cycle ago. No margin; the
//                                 ZMP leaves the polygon by excursion_k at kZmpExcursionPenalty
//                                 per metre, so that a crawl's quasi-static plan stays feasible;
//                                 where two feet stand (a trot's diagonal), four of the knot's
//                                 rows hold the ZMP on the segment between them instead
//        stance_lo_klj <= a_klj . (z_k, pitch_k, shift_k, lateral_k) + e_klj relax_k <= stance_hi_klj
//                                 per knot, stance leg l and row j (4): its three joints within
//                                 their limits and its extension within the knee's range,
//                                 linearised through the leg's KDL Jacobian (stance_leg_rows.h)
//        clearance_lo_kl <= b_kl . (z_k, pitch_k, shift_k, lateral_k) + e_kl relax_k
//                                 per knot and leg, and of the body: its links clear of the
//                                 stairs (FCL); the same half a knot later over the mean of knots
//                                 k and k + 1 (passing: a link sweeping past a nosing comes nearer
//                                 between two knots than at either)
//        variable bounds (limits intersected with the cycle's trust region; knot 0 pinned)
//
// With stance rows, relax_k in [0, 1] is one elastic variable per knot, the share of the linearisation point's
// violations (e: the violated bound minus the row's value there, 0 for rows it satisfies) the plan
// may keep at that knot, with an exact penalty (kRelaxPenalty). At relax_k = 1 the point itself
// satisfies every row, so the QP is feasible whatever the previous plan broke (a swing that came
// into the horizon, a linearisation that moved), and rows the point satisfies stay hard.
//
// Without stability and stance rows (stability_margin < 0, stance rows off) nothing couples the sideways shift to the rest, so it is its own small QP with its
// own solver (lateral_program()): the per-cycle solver's cost grows with n^2 per active-set change.
//
// c_l = -hip_x_l cos(pitch_nominal) is the hip's height change per unit pitch at the flight's
// nominal pitch. It is fixed so the matrix never changes; the planner evaluates the exact hip
// height at the linearisation point and makes each row's bounds hold over the trust region.
#pragma once

#include <array>

#include <Eigen/Core>

#include "stairplan/planning/body/body_planner_settings.h"
#include "stairplan/optim/active_set_qp_solver.h"
#include "stairplan/optim/program.h"

namespace stairplan {

/// Number of legs the body planner plans for (quadrupeds).
constexpr int kBodyLegs = 4;

/// The body planner's QP over the horizon's knots, built once and re-solved warm every cycle (see
/// the file's top comment).
class BodyQp {
 public:
  /// `row_coefficients`: c_l per leg; legs within kRowMergeTolerance share a row (and the mean
  /// coefficient). Throws std::invalid_argument naming the field for bad settings.
  /// `stance_rows`: with the stance legs' kinematic rows (the planner has the robot's kinematics).
  /// `zmp_height` > 0 (with stance rows): ZMP rows beside the COM's, for a pendulum that high [m].
  /// `shift_along_travel`: +1 where a growing shift moves the body along its travel (it faces
  /// where it goes), -1 where against it (it walks backwards); the progress rows' sign.
  BodyQp(const BodyPlannerSettings& settings, const std::array<double, kBodyLegs>& row_coefficients,
         bool stance_rows = false, double zmp_height = 0.0, double shift_along_travel = 1.0);

  /// Coefficients closer than this share one row [m/rad].
  static constexpr double kRowMergeTolerance = 1e-3;

  /// Number of knots over the horizon.
  int knots() const { return knots_; }
  ///@{
  /// Rows per knot (hip groups) and each leg's group.
  int groups() const { return groups_; }
  int group_of(int leg) const { return group_of_[static_cast<std::size_t>(leg)]; }
  ///@}
  /// The row coefficient used for leg `leg` (its group's).
  double row_coefficient(int leg) const { return group_c_[static_cast<std::size_t>(group_of(leg))]; }

  /// Support rows per knot: one per pair of legs (i < j), in the order of SupportPair().
  static constexpr int kSupportRows = 6;
  /// The legs (i < j) of support row `r` (0 .. kSupportRows - 1).
  static std::array<int, 2> SupportPair(int r);
  /// Weights of knots k-1, k and k+1 in knot k's ZMP rows (see the top comment): the ZMP's
  /// second difference, the last knot's at rest beyond the horizon (its shift at rest too).
  /// Knot 0's row has the first two (knot -1, executed a cycle ago, is the planner's constant).
  std::array<double, 3> ZmpStencil(int k) const;
  /// h / (g dt^2): the weight of a knot's neighbours in the ZMP (0: no ZMP rows).
  double zmp_weight() const { return zmp_weight_; }
  /// The most stability margin a knot may give up (with stance rows) [m].
  double max_give() const { return max_give_; }
  /// Stance rows per leg and knot: three joints, the extension and the first axis's distance
  /// (StanceLegRows::kRows).
  static constexpr int kStanceRows = 5;
  /// Index of stance row `j` of leg `leg` at knot `k`.
  static int StanceRow(int k, int leg, int j) { return (k * kBodyLegs + leg) * kStanceRows + j; }
  /// Clearance rows per knot: one per leg and one of the body.
  static constexpr int kClearanceRows = kBodyLegs + 1;
  /// Index of the clearance row of leg `leg` at knot `k` (leg kBodyLegs: the body's).
  static int ClearanceRow(int k, int leg) { return k * kClearanceRows + leg; }
  /// Cost of keeping all of one knot's violations (relax 1): far above what any row is worth to
  /// the other costs, so the penalty is exact.
  static constexpr double kRelaxPenalty = 1e6;
  /// Cost of one metre of the body's motion against the travel (with stance rows): ten times the
  /// margin's and the ZMP's, so that crossing a support diagonal sideways, with margin given up
  /// or the ZMP out for a moment, beats crossing it backwards; a tenth of the relaxation's.
  static constexpr double kRetreatPenalty = 1e5;
  /// Cost of one metre of stability margin given up (with stance rows): far above what the other
  /// costs could gain by it and far below the relaxation.
  static constexpr double kMarginGivePenalty = 1e4;
  /// Cost of one metre of the ZMP outside the support polygon (with stance rows and a pendulum
  /// height): the pendulum shapes the motion, the relaxation answers to the COM's rows.
  static constexpr double kZmpExcursionPenalty = 1e4;

  // ---- per-cycle inputs, filled in place by the planner (sizes fixed at construction) ----
  ///@{
  Eigen::VectorXd z_lo, z_hi, pitch_lo, pitch_hi, shift_lo, shift_hi, lateral_lo, lateral_hi;  ///< knots
  ///@}
  ///@{
  Eigen::VectorXd hip_lo, hip_hi;      ///< knots * groups(), row k * groups() + group; +-inf: none
  ///@}
  /// Knot 1 on the straight line from the body executed a cycle ago through knot 0, per variable
  /// (z, pitch, shift, lateral): the acceleration cost's term centred at knot 0, the one the
  /// robot executes, prices knot 1's distance from it like every other knot's second difference.
  std::array<double, 4> straight = {0.0, 0.0, 0.0, 0.0};
  Eigen::VectorXd height_ref;          ///< knots * 4: wanted value of z + c_l pitch
  ///@{
  Eigen::VectorXd pitch_ref, shift_ref, lateral_ref;  ///< knots
  ///@}
  ///@{
  /// Support rows, k * kSupportRows + r: coefficients of shift_k and lateral_k and the bounds
  /// (+-inf: none). Coefficients are pushed only where they changed.
  Eigen::VectorXd support_cx, support_cy, support_lo, support_hi;
  ///@}
  /// With stance rows, the support rows' relaxation coefficients (as KnotRows::sigma); unused without.
  Eigen::VectorXd support_sigma;
  ///@{
  /// With stance rows and a pendulum height, the bounds of the ZMP's support rows: the COM's
  /// coefficients over ZmpStencil(), no margin; the ZMP leaves the polygon only by the excursion
  /// (kZmpExcursionPenalty per metre). Unused without.
  Eigen::VectorXd zmp_lo, zmp_hi;
  ///@}
  /// With stance rows, progress row k: s (shift_{k+1} - shift_k) + retreat_k >= progress_lo_k,
  /// s the constructor's shift_along_travel (knots - 1 rows; the planner puts minus the neutral
  /// body's advance along the travel there, so that the body moves against the travel only by the
  /// retreat, which costs kRetreatPenalty per metre). Unused without.
  Eigen::VectorXd progress_lo;
  /// Rows of one family over one knot's (z, pitch, shift, lateral) each, softened by its relaxation.
  struct KnotRows {
    Eigen::MatrixXd a;       ///< coefficients, one row per constraint (4 columns)
    ///@{
    Eigen::VectorXd lo, hi;  ///< bounds (+-inf: none; the coefficients of a free row are ignored)
    ///@}
    /// Relaxation coefficients: the violated bound minus the row's value at the linearisation
    /// point (0 where it holds there, and for a free row).
    Eigen::VectorXd sigma;
    /// Sets the relaxation coefficients of rows first .. first + count - 1 to what the point `v`
    /// breaks: with relax 1 `v` satisfies them.
    void RelaxAt(int first, int count, const Eigen::Vector4d& v);
  };
  /// The stance legs' joint and extension rows, StanceRow(k, leg, j).
  KnotRows stance;
  /// The legs' and the body's clearance to the stairs, ClearanceRow(k, leg) (lower bounds only).
  KnotRows clearance;
  /// The same half a knot after knot k, ClearanceRow(k, leg), over the mean of knots k and k + 1
  /// (the body there, moving straight between them): a link sweeping past a nosing comes nearer
  /// between two knots than at either.
  KnotRows passing;

  /// Pushes the inputs into the program(s) and solves warm; `time_limit_s` may be +inf.
  /// Allocation-free after the first call. Without support rows the sideways shift is its own
  /// QP (lateral_apart()): `result` then holds the rest, and its status and iterations both's.
  void Solve(double time_limit_s, optim::SolveResult* result);
  /// The next Solve() starts from `last`, an earlier solve's active set, moved `knots` knots
  /// earlier: the horizon has advanced that far since, so what was active at knot k + knots is
  /// what is likely active at knot k now (the last `knots` knots keep their own). Unshifted, a
  /// stretch of active rows one knot off is dropped and added back row by row. `last` is of
  /// program(); the sideways shift's own QP (lateral_apart()) starts where it ended.
  void ShiftWarmStart(const optim::ActiveSet& last, int knots);
  /// The next solve starts cold.
  void ResetWarmStart() {
    solver_.ResetWarmStart();
    lateral_solver_.ResetWarmStart();
  }
  /// The knots' sideways shift in `result` of Solve().
  Eigen::VectorBlock<const Eigen::VectorXd> LateralOf(const optim::SolveResult& result) const;

  /// True when no support row couples the sideways shift to the rest (stability_margin < 0):
  /// it is then a separate QP, lateral_program(), and program() holds the rest.
  bool lateral_apart() const { return lateral_apart_; }
  /// The QP over height, pitch and forward shift (and the sideways shift unless lateral_apart()).
  const optim::Program& program() const { return program_; }
  /// The sideways shift's own QP when lateral_apart(), else program().
  const optim::Program& lateral_program() const { return lateral_apart_ ? lateral_program_ : program_; }
  /// Body heights, one per knot, in program().
  const optim::VariableBlock& z() const { return z_; }
  /// Pitches, one per knot, in program().
  const optim::VariableBlock& pitch() const { return pitch_; }
  /// Forward shifts of the centre of mass, one per knot, in program().
  const optim::VariableBlock& shift() const { return shift_; }
  /// In lateral_program().
  const optim::VariableBlock& lateral() const { return lateral_; }
  /// The support rows (the COM inside the support polygon), in program().
  const optim::ConstraintRows& support_rows() const { return com_support_.rows; }
  /// The ZMP's support rows, in program() (empty without stance rows or a pendulum height).
  const optim::ConstraintRows& zmp_rows() const { return zmp_support_.rows; }
  /// The hip-height rows, in program().
  const optim::ConstraintRows& hip_rows() const { return hip_rows_; }
  /// The stance legs' joint and extension rows, in program() (empty without stance rows).
  const optim::ConstraintRows& stance_rows() const { return stance_.rows; }
  /// The stance legs' clearance rows, in program() (empty without stance rows).
  const optim::ConstraintRows& clearance_rows() const { return clearance_.rows; }
  /// True when the program has the stance legs' rows (joints, extension, clearance).
  bool has_stance_rows() const { return stance_.rows.size > 0; }
  /// The relaxation variables, one per knot, in program() (empty without stance rows).
  const optim::VariableBlock& relax() const { return relax_; }
  /// The stability margin each knot gives up, in program() (empty without stance rows).
  const optim::VariableBlock& give() const { return give_; }
  /// How far each knot's ZMP leaves the polygon, in program() (empty without ZMP rows).
  const optim::VariableBlock& excursion() const { return excursion_; }
  /// Writes the linear cost of the current inputs into the program (done by Solve too); lets
  /// other solvers (Ipopt, for comparison) solve the same QP.
  void PushInputs();

 private:
  int knots_ = 0;
  BodyPlannerSettings settings_;
  std::array<double, kBodyLegs> c_{};
  int groups_ = 0;
  std::array<int, kBodyLegs> group_of_{};
  std::array<double, kBodyLegs> group_c_{};
  bool lateral_apart_ = false;
  // 2 w / dt^4: the curvature the acceleration cost gives each second difference.
  double accel_curvature_ = 0.0;
  double zmp_weight_ = 0.0;  // h / (g dt^2): the ZMP's weight on a knot's neighbours
  optim::Program program_;
  optim::Program lateral_program_;  // the sideways shift when apart (else empty)
  optim::ActiveSetQpSolver lateral_solver_;
  optim::SolveResult lateral_result_;
  optim::VariableBlock z_, pitch_, shift_, lateral_, relax_, retreat_, give_, excursion_;
  optim::ConstraintRows hip_rows_, accel_rows_, lateral_accel_rows_;
  optim::ActiveSet shifted_;  // ShiftWarmStart's, sized once
  // One family of support rows in the program: the COM's (one knot each) or the ZMP's (over
  // ZmpStencil), and the coefficients pushed into them.
  struct SupportFamily {
    optim::ConstraintRows rows;
    bool zmp = false;
    Eigen::VectorXd pushed_cx, pushed_cy, pushed_sigma, pushed_give;
  };
  SupportFamily com_support_, zmp_support_;
  // A KnotRows family's rows in the program and the coefficients pushed into them.
  struct PushedRows {
    optim::ConstraintRows rows;
    int per_knot = 0;
    bool spans_next = false;  // over the mean of knots k and k + 1
    Eigen::MatrixXd pushed;  // a and sigma
  };
  PushedRows stance_, clearance_, passing_;
  double max_give_ = 0.0;
  optim::ActiveSetQpSolver solver_;
  Eigen::VectorXd g_z_, g_pitch_, g_shift_, g_lateral_;
  optim::ConstraintRows progress_rows_;
  Eigen::VectorXd progress_hi_;  // +inf
  optim::ConstraintRows single_row_;       // one support row (its start moves; no string copies)
  void PushSupportRows();
  // Pushes the COM's family (support_lo/hi/sigma) or the ZMP's (zmp_lo/hi, no relaxation).
  void PushSupportFamily(SupportFamily* family);
  void PushProgressRows();
  // Adds `count` free rows over one knot's variables each; the inputs sized to match.
  void AddKnotRows(const char* name, int count, int per_knot, KnotRows* inputs, PushedRows* rows,
                   bool spans_next = false);
  void PushKnotRows(const KnotRows& inputs, PushedRows* rows);
  // Writes `value` as knot k's coefficient of `block` into `row` (one row).
  void SetCoefficient(const optim::ConstraintRows& row, const optim::VariableBlock& block, int k, double value);
  // Sets `row`'s coefficients of `block` at knots k-1..k+1 to ZmpStencil(k) times `value`.
  void SetStencil(const optim::ConstraintRows& row, const optim::VariableBlock& block, int k, double value);
};

}  // namespace stairplan
