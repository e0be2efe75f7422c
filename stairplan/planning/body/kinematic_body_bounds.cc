#include "stairplan/planning/body/kinematic_body_bounds.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "stairplan/collision/clearance.h"
#include "stairplan/collision/stance_check.h"

namespace stairplan {
namespace {

// The clearance bound is computed at the nodes with this much extra distance, so that between
// nodes (where it is interpolated) the guaranteed clearance_margin still holds.
constexpr double kClearanceSlack = 0.001;
// Bisection tolerance of the node bounds [m].
constexpr double kHeightTolerance = 5e-4;

}  // namespace

KinematicBodyBounds::KinematicBodyBounds(const RobotModel& robot, const Staircase& stairs, Facing facing,
                                         const BodyPlannerSettings& settings)
    : KinematicBodyBounds(RobotKinematics(robot), stairs, facing, settings) {}

KinematicBodyBounds::KinematicBodyBounds(const RobotKinematics& kinematics, const Staircase& stairs, Facing facing,
                                         const BodyPlannerSettings& settings)
    : settings_(settings) {
  settings_.Validate();
  kinematics_ = std::make_unique<RobotKinematics>(kinematics);
  collision_ = std::make_unique<RobotCollisionModel>(*kinematics_);
  stairs_ = std::make_unique<StairCollisionModel>(stairs);
  ws_ = std::make_unique<RobotWorkspace>(*kinematics_);
  yaw_ = facing == Facing::kForward ? 0.0 : M_PI;
  heading_ = facing == Facing::kForward ? 1.0 : -1.0;
  double reach = 0.0;
  for (int l = 0; l < kinematics_->leg_count(); ++l) {
    const LegModel& m = kinematics_->leg(l).model();
    lateral_.push_back(m.hip_B.y() - m.foot_zero_B.y());
    reach = std::max(reach, kinematics_->leg(l).reach().hi);
  }
  h_max_ = reach + 0.02;
  double mean_reach = 0.0, radius = 0.0;
  for (int l = 0; l < kinematics_->leg_count(); ++l) {
    mean_reach += kinematics_->leg(l).reach().hi / kinematics_->leg_count();
    radius += kinematics_->leg(l).model().foot_radius / kinematics_->leg_count();
  }
  nominal_hip_height_ = radius + settings_.hip_height_fraction * mean_reach;
  const double dx_span = reach + settings_.grid_dx;
  nx_ = 2 * static_cast<int>(std::ceil(dx_span / settings_.grid_dx)) + 1;
  x0_ = -0.5 * (nx_ - 1) * settings_.grid_dx;
  const double p_span = settings_.max_pitch + settings_.trust_pitch + settings_.grid_pitch;
  np_ = 2 * static_cast<int>(std::ceil(p_span / settings_.grid_pitch)) + 1;
  p0_ = -0.5 * (np_ - 1) * settings_.grid_pitch;
  reach_.assign(static_cast<std::size_t>(kinematics_->leg_count()),
                std::vector<ReachNode>(static_cast<std::size_t>(nx_ * np_)));
}

void KinematicBodyBounds::SetFootholds(const std::vector<Foothold>& footholds) {
  for (std::size_t f = 0; f < footholds.size(); ++f) {
    if (footholds[f].leg < 0 || footholds[f].leg >= kinematics_->leg_count() || !footholds[f].contact_W.allFinite()) {
      throw std::invalid_argument("KinematicBodyBounds::SetFootholds: footholds[" + std::to_string(f) +
                                  "] has an unknown leg or a non-finite contact");
    }
  }
  footholds_ = footholds;
  clear_.assign(footholds_.size(), std::vector<ClearNode>(static_cast<std::size_t>(nx_ * np_)));
}

BodyPose KinematicBodyBounds::PoseFor(int leg, const Eigen::Vector3d& contact_W, double dx, double h,
                                      double pitch) const {
  BodyPose pose;
  pose.pitch = pitch;
  pose.yaw = yaw_;
  const Eigen::Vector3d hip_W =
      contact_W + Eigen::Vector3d(heading_ * dx, heading_ * lateral_[static_cast<std::size_t>(leg)], h);
  pose.position_W = hip_W - pose.ToIsometry().linear() * kinematics_->leg(leg).hip_B();
  return pose;
}

IkResult KinematicBodyBounds::StanceIk(int leg, const Eigen::Vector3d& contact_W, const BodyPose& body) {
  const LegKinematics& kin = kinematics_->leg(leg);
  LegWorkspace& ws = ws_->leg(leg);
  const Eigen::Isometry3d body_W = body.ToIsometry();
  const Eigen::Isometry3d W_body = body_W.inverse();
  // As CheckStance: the sphere's offset from the foot origin turns with the foot, so re-aim.
  Eigen::Matrix3d foot_rotation_W = body_W.linear();
  IkResult ik = kin.SolveFootIk(W_body * FootOriginForContact(kin.model(), contact_W, foot_rotation_W), ws);
  if (!kin.model().foot_sphere_center.isZero()) {
    for (int pass = 0; pass < 3 && ik.ok(); ++pass) {
      foot_rotation_W = body_W.linear() * kin.FootPose(ik.q, ws).linear();
      ik = kin.SolveFootIk(W_body * FootOriginForContact(kin.model(), contact_W, foot_rotation_W), ik.q, ws);
    }
  }
  return ik;
}

StanceLegCheck KinematicBodyBounds::CheckLeg(int leg, const Eigen::Vector3d& contact_W, const BodyPose& body) {
  StanceLegCheck check;
  check.ik = StanceIk(leg, contact_W, body);
  check.clearance = check.ik.ok()
                        ? LegStairClearance(*kinematics_, *collision_, *stairs_, leg, check.ik.q, body, *ws_).distance
                        : -std::numeric_limits<double>::infinity();
  return check;
}

StanceResult KinematicBodyBounds::CheckFeet(const BodyPose& body, const std::array<Eigen::Vector3d, 4>& contacts_W,
                                            double min_clearance, double prune_above) {
  StanceSettings stance;
  stance.min_clearance = min_clearance;
  stance.clearance.prune_above = prune_above;
  return CheckStance(*kinematics_, *collision_, *stairs_, body, contacts_W, *ws_, stance);
}

const KinematicBodyBounds::ReachNode& KinematicBodyBounds::FillReach(ReachNode& node, int leg, int i, int j) {
  node.done = true;
  ++reach_computed_;
  const double dx = x0_ + i * settings_.grid_dx, pitch = p0_ + j * settings_.grid_pitch;
  const Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // IK does not depend on where the foot is
  const LegKinematics& kin = kinematics_->leg(leg);
  const auto reachable = [&](double h) {
    const BodyPose pose = PoseFor(leg, origin, dx, h, pitch);
    const Eigen::Isometry3d body_W = pose.ToIsometry();
    return kin.SolveFootIk(body_W.inverse() * FootOriginForContact(kin.model(), origin, body_W.linear()), ws_->leg(leg)).ok();
  };
  // The longest run of reachable heights on the scan, then both ends refined by bisection.
  const double step = settings_.grid_height;
  double run_lo = 0.0, run_hi = -1.0, best_lo = 0.0, best_hi = -1.0;
  bool in_run = false;
  for (double h = step; h <= h_max_ + 1e-12; h += step) {
    if (reachable(h)) {
      if (!in_run) run_lo = h;
      run_hi = h;
      in_run = true;
      if (run_hi - run_lo > best_hi - best_lo) best_lo = run_lo, best_hi = run_hi;
    } else {
      in_run = false;
    }
  }
  if (best_hi < best_lo) return node;  // stays empty
  double out = best_lo - step, in = best_lo;
  while (in - out > kHeightTolerance) {
    const double mid = 0.5 * (in + out);
    (reachable(mid) ? in : out) = mid;
  }
  const double lo = in;
  out = best_hi + step;
  in = best_hi;
  while (out - in > kHeightTolerance) {
    const double mid = 0.5 * (in + out);
    (reachable(mid) ? in : out) = mid;
  }
  node.lo = static_cast<float>(lo + settings_.reach_margin);
  node.hi = static_cast<float>(in - settings_.reach_margin);
  return node;
}

float KinematicBodyBounds::FillClearLow(ClearNode& node, int foothold, int i, int j) {
  node.done = true;
  ++clearance_computed_;
  const Foothold& f = footholds_[static_cast<std::size_t>(foothold)];
  const ReachNode& r = Reach(f.leg, i, j);
  node.lo = std::numeric_limits<float>::infinity();
  if (!(r.lo <= r.hi)) return node.lo;
  const double dx = x0_ + i * settings_.grid_dx, pitch = p0_ + j * settings_.grid_pitch;
  const double need = settings_.clearance_margin + kClearanceSlack;
  // CheckLeg(...).ok(need) with FCL measuring only the shape pairs that may be nearer than
  // `need`: the node asks yes or no, and pairs surely farther cannot change the answer.
  ClearanceOptions options;
  options.prune_above = need;
  const auto clear = [&](double h) {
    const BodyPose body = PoseFor(f.leg, f.contact_W, dx, h, pitch);
    const IkResult ik = StanceIk(f.leg, f.contact_W, body);
    return ik.ok() && LegStairClearance(*kinematics_, *collision_, *stairs_, f.leg, ik.q, body, *ws_, options).distance >= need;
  };
  // Clearance grows as the body rises (the leg straightens away from risers and nosings): the
  // lowest clear height above the reach's lower end.
  const double step = settings_.grid_height;
  double below = r.lo - step;
  for (double h = r.lo; h <= r.hi + 1e-12; h += step) {
    if (clear(h)) {
      double in = h, out = std::max(below, static_cast<double>(r.lo) - 1e-9);
      if (h == static_cast<double>(r.lo)) {
        node.lo = r.lo;
        return node.lo;
      }
      while (in - out > kHeightTolerance) {
        const double mid = 0.5 * (in + out);
        (clear(mid) ? in : out) = mid;
      }
      node.lo = static_cast<float>(in);
      return node.lo;
    }
    below = h;
  }
  if (clear(r.hi)) node.lo = r.hi;
  return node.lo;
}

HeightRange KinematicBodyBounds::HipHeight(const HipBox& box) {
  if (box.foothold < 0 || box.foothold >= static_cast<int>(footholds_.size())) return {1.0, 0.0};
  return Interpolate(box, true);
}

HeightRange KinematicBodyBounds::ReachHeight(const HipBox& box) { return Interpolate(box, false); }

HeightRange KinematicBodyBounds::Interpolate(const HipBox& box, bool with_clearance) {
  if (box.leg < 0 || box.leg >= kinematics_->leg_count() || !(box.dx_lo <= box.dx_hi) || !(box.pitch_lo <= box.pitch_hi)) {
    return {1.0, 0.0};
  }
  // Bilinear interpolation of the node bounds at the box's corners, the worst corner kept: it is
  // continuous as the box moves (no jumps when a box crosses a node), and the box is smaller
  // than a grid cell, so its corners bracket it.
  HeightRange range{-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  // The box is smaller than a grid cell, so its corners mostly share one cell: its nodes are
  // looked up once (each look-up walks the caches) and kept while the next corner's cell is the same.
  int cell_i = -1, cell_j = -1;
  std::array<double, 4> cell_lo{}, cell_hi{};  // the cell's nodes, index di * 2 + dj
  for (const double dx : {box.dx_lo, box.dx_hi}) {
    for (const double pitch : {box.pitch_lo, box.pitch_hi}) {
      const double u = (dx - x0_) / settings_.grid_dx, v = (pitch - p0_) / settings_.grid_pitch;
      const int i = static_cast<int>(std::floor(u)), j = static_cast<int>(std::floor(v));
      if (i < 0 || j < 0 || i + 1 >= nx_ || j + 1 >= np_) return {1.0, 0.0};  // beyond the grid
      if (i != cell_i || j != cell_j) {
        for (int c = 0; c < 4; ++c) {
          const int di = c / 2, dj = c % 2;
          const ReachNode& r = Reach(box.leg, i + di, j + dj);
          const double clear_lo = with_clearance ? static_cast<double>(ClearLow(box.foothold, i + di, j + dj)) : r.lo;
          const double node_lo = std::max(static_cast<double>(r.lo), clear_lo);
          if (!(node_lo <= r.hi)) return {1.0, 0.0};  // a corner node has no valid height
          cell_lo[static_cast<std::size_t>(c)] = node_lo;
          cell_hi[static_cast<std::size_t>(c)] = r.hi;
        }
        cell_i = i;
        cell_j = j;
      }
      const double a = u - i, b = v - j;
      double lo = 0.0, hi = 0.0;
      for (int c = 0; c < 4; ++c) {
        const int di = c / 2, dj = c % 2;
        const double w = (di ? a : 1.0 - a) * (dj ? b : 1.0 - b);
        lo += w * cell_lo[static_cast<std::size_t>(c)];
        hi += w * cell_hi[static_cast<std::size_t>(c)];
      }
      range.lo = std::max(range.lo, lo);
      range.hi = std::min(range.hi, hi);
    }
  }
  return range;
}

}  // namespace stairplan
