#include "stairplan/planning/validation/contact_wrench_qp.h"

#include <cmath>
#include <stdexcept>

#include <Eigen/Geometry>

#include "stairplan/geometry/cross_matrix.h"
#include "stairplan/geometry/field_error.h"

namespace stairplan {
namespace {

constexpr double kGravity = 9.81;              // [m/s^2]
constexpr double kForceRegularization = 1e-7;  // picks the least forces among equal residuals
constexpr double kPi = 3.14159265358979323846;

// A unit tangent of the surface: the world x axis (the stairs' run) projected onto it, or y where
// the normal is along x.
Eigen::Vector3d FirstTangent(const Eigen::Vector3d& n) {
  Eigen::Vector3d t = Eigen::Vector3d::UnitX() - n.x() * n;
  if (t.norm() < 1e-6) t = Eigen::Vector3d::UnitY() - n.y() * n;
  return t.normalized();
}

}  // namespace

void ContactWrenchSettings::Validate() const {
  RequireInRange("friction", friction, 0.0, 10.0);
  if (friction_faces < 4 || friction_faces > 64) throw FieldError("friction_faces", "must be in [4, 64]");
  RequireInRange("residual_tolerance", residual_tolerance, 1e-9, 1.0);
  RequireInRange("max_line_tilt", max_line_tilt, 0.0, 1.0);
}

const char* ToString(DynamicsCheckMode mode) {
  switch (mode) {
    case DynamicsCheckMode::kOff: return "off";
    case DynamicsCheckMode::kReport: return "report";
    case DynamicsCheckMode::kJudge: return "judge";
  }
  return "off";
}

const char* ToString(WrenchLimit limit) {
  switch (limit) {
    case WrenchLimit::kNone: return "none";
    case WrenchLimit::kFrictionCone: return "friction_cone";
    case WrenchLimit::kTorqueLimit: return "torque_limit";
    case WrenchLimit::kWrenchUnattainable: return "wrench_unattainable";
  }
  return "none";
}

// Variables: the four feet's forces (12) and the scaled wrench residual (6). Rows: wrench map * f -
// diag(1, lever) * residual = demand (equalities), `faces` pyramid rows per foot, three torque
// rows per leg. Cost: 0.5 |residual|^2 + a little |f|^2.
ContactWrenchQp::ContactWrenchQp(double mass, double lever, const ContactWrenchSettings& settings)
    : settings_(settings), mass_(mass), lever_(lever) {
  settings_.Validate();
  RequireInRange("mass", mass, 1e-6, 1e6);
  RequireInRange("lever", lever, 1e-3, 100.0);
  tolerance_ = settings_.residual_tolerance * mass_ * kGravity;
  const int faces = settings_.friction_faces;
  forces_ = program_.AddVariables("foot_forces", 12);
  residual_ = program_.AddVariables("wrench_residual", 6);
  program_.AddQuadraticCost(forces_, kForceRegularization * Eigen::MatrixXd::Identity(12, 12), Eigen::VectorXd::Zero(12));
  program_.AddQuadraticCost(residual_, Eigen::MatrixXd::Identity(6, 6), Eigen::VectorXd::Zero(6));
  wrench_map_ = Eigen::MatrixXd::Zero(6, 12);
  for (int i = 0; i < 4; ++i) wrench_map_.block<3, 3>(0, 3 * i).setIdentity();
  Eigen::VectorXd scale(6);
  scale << 1, 1, 1, lever_, lever_, lever_;
  wrench_ = Eigen::VectorXd::Zero(6);
  wrench_rows_ = program_.AddLinearConstraint({{forces_, wrench_map_}, {residual_, -Eigen::MatrixXd(scale.asDiagonal())}},
                                              wrench_, wrench_, "wrench");
  cone_map_ = Eigen::MatrixXd::Zero(4 * faces, 12);
  cone_lower_ = Eigen::VectorXd::Constant(4 * faces, -optim::kInf);
  cone_upper_ = Eigen::VectorXd::Constant(4 * faces, optim::kInf);
  cone_rows_ = program_.AddLinearConstraint({{forces_, cone_map_}}, cone_lower_, cone_upper_, "friction_pyramids");
  torque_map_ = Eigen::MatrixXd::Zero(12, 12);
  torque_lower_ = Eigen::VectorXd::Constant(12, -optim::kInf);
  torque_upper_ = Eigen::VectorXd::Constant(12, optim::kInf);
  torque_rows_ = program_.AddLinearConstraint({{forces_, torque_map_}}, torque_lower_, torque_upper_, "joint_torques");
  force_lower_ = Eigen::VectorXd::Zero(12);
  force_upper_ = Eigen::VectorXd::Zero(12);
  for (Eigen::Vector3d& f : result_.forces_W) f.setZero();
}

// A stance foot: free force inside its pyramid (which also keeps the normal force >= 0) and its
// torque rows; a swing foot: zero force, its rows unbounded (bounded rows on a force fixed at
// zero would only add degenerate active constraints).
void ContactWrenchQp::SetFoot(int leg, const WrenchFoot& foot, const WrenchDemand& demand) {
  const int faces = settings_.friction_faces;
  const auto i = static_cast<Eigen::Index>(leg);
  if (!foot.position_W.allFinite() || !foot.normal_W.allFinite() || !foot.torque_map.allFinite() ||
      foot.effort.hasNaN() || (foot.effort.array() < 0.0).any()) {
    throw std::invalid_argument(std::string("ContactWrenchQp: foot ") + ToString(LegIdFromIndex(leg)) + " is not finite");
  }
  if (foot.stance && foot.normal_W.norm() < 1e-9) {
    throw std::invalid_argument(std::string("ContactWrenchQp: foot ") + ToString(LegIdFromIndex(leg)) + " has a zero normal");
  }
  wrench_map_.block<3, 3>(3, 3 * i) = CrossMatrix(foot.position_W - demand.com_W);  // moment about the COM: r x f
  const double free = foot.stance ? optim::kInf : 0.0;
  force_lower_.segment<3>(3 * i).setConstant(-free);
  force_upper_.segment<3>(3 * i).setConstant(free);
  const Eigen::Vector3d n = foot.stance ? Eigen::Vector3d(foot.normal_W.normalized()) : Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d t1 = FirstTangent(n), t2 = n.cross(t1);
  const double mu = settings_.friction * std::cos(kPi / faces);  // inscribed pyramid
  for (int k = 0; k < faces; ++k) {
    const double angle = 2.0 * kPi * k / faces;
    const Eigen::Vector3d face = std::cos(angle) * t1 + std::sin(angle) * t2 - mu * n;  // face . f <= 0
    cone_map_.block<1, 3>(i * faces + k, 3 * i) = face.transpose();
    cone_upper_(i * faces + k) = foot.stance ? 0.0 : optim::kInf;
  }
  torque_map_.block<3, 3>(3 * i, 3 * i) = foot.stance ? foot.torque_map : Eigen::Matrix3d::Zero();
  torque_lower_.segment<3>(3 * i) = foot.stance ? Eigen::Vector3d(-foot.effort) : Eigen::Vector3d::Constant(-optim::kInf);
  torque_upper_.segment<3>(3 * i) = foot.stance ? foot.effort : Eigen::Vector3d::Constant(optim::kInf);
}

const WrenchResult& ContactWrenchQp::Solve(const std::array<WrenchFoot, 4>& feet, const WrenchDemand& demand) {
  if (!demand.com_W.allFinite() || !demand.force_W.allFinite() || !demand.moment_W.allFinite()) {
    throw std::invalid_argument("ContactWrenchQp: the demanded wrench or the centre of mass is not finite");
  }
  for (int i = 0; i < 4; ++i) SetFoot(i, feet[static_cast<std::size_t>(i)], demand);
  program_.SetConstraintCoefficients(wrench_rows_, forces_, wrench_map_);
  wrench_ << demand.force_W, demand.moment_W;
  program_.SetConstraintBounds(wrench_rows_, wrench_, wrench_);
  program_.SetConstraintCoefficients(cone_rows_, forces_, cone_map_);
  program_.SetConstraintBounds(cone_rows_, cone_lower_, cone_upper_);
  program_.SetConstraintCoefficients(torque_rows_, forces_, torque_map_);
  program_.SetConstraintBounds(torque_rows_, torque_lower_, torque_upper_);
  program_.SetVariableBounds(forces_, force_lower_, force_upper_);
  solver_.Solve(program_, &solution_);
  result_.solved = solution_.solved();
  result_.limit = WrenchLimit::kNone;
  result_.leg = LegId::kNone;
  if (!result_.solved) {
    // No forces at all: the whole demand is the residual, and no single leg is to blame.
    for (Eigen::Vector3d& f : result_.forces_W) f.setZero();
    result_.residual = std::hypot(demand.force_W.norm(), demand.moment_W.norm() / lever_);
    result_.within_tolerance = false;
    result_.limit = WrenchLimit::kWrenchUnattainable;
    return result_;
  }
  for (int i = 0; i < 4; ++i) {
    result_.forces_W[static_cast<std::size_t>(i)] = forces_.Of(solution_.x).segment<3>(3 * i);
  }
  result_.residual = residual_.Of(solution_.x).norm();
  result_.within_tolerance = result_.residual <= tolerance_;
  if (!result_.within_tolerance) FindBindingLeg(feet);
  return result_;
}

void ContactWrenchQp::FindBindingLeg(const std::array<WrenchFoot, 4>& feet) {
  const int faces = settings_.friction_faces;
  double largest = 0.0;
  for (int i = 0; i < 4; ++i) {
    if (!feet[static_cast<std::size_t>(i)].stance) continue;
    for (int k = 0; k < faces + 3; ++k) {
      const bool cone = k < faces;
      const int row = cone ? cone_rows_.start + i * faces + k : torque_rows_.start + 3 * i + (k - faces);
      const double dual = std::abs(solution_.row_duals(row));
      if (dual <= largest) continue;
      largest = dual;
      result_.leg = LegIdFromIndex(i);
      result_.limit = cone ? WrenchLimit::kFrictionCone : WrenchLimit::kTorqueLimit;
    }
  }
  const bool unloaded = result_.leg != LegId::kNone &&
                        result_.forces_W[static_cast<std::size_t>(result_.leg)].norm() < 1e-6 * mass_ * kGravity;
  if (result_.leg == LegId::kNone || unloaded) result_.limit = WrenchLimit::kWrenchUnattainable;
}

}  // namespace stairplan
