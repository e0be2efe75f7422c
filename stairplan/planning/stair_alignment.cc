#include "stairplan/planning/stair_alignment.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "stairplan/planning/com_model.h"

namespace stairplan {
namespace {

// How far the feet, under the hips in the body frame (`under_hips`, their centre `centre`), shift
// so that their centre is under the centre of mass of the robot standing on them on flat ground,
// the legs through IK, the hips at `hip_height_fraction` of the reach (as the body path stands it).
Eigen::Vector2d StandingShift(const RobotKinematics& kinematics, const std::vector<Eigen::Vector2d>& under_hips,
                              const Eigen::Vector2d& centre, double hip_height_fraction) {
  const RobotModel& robot = kinematics.robot();
  const ComModel com_model(kinematics);
  RobotWorkspace ws(kinematics);
  double reach = 0.0, hip_z = 0.0;
  for (const LegKinematics& leg : kinematics.legs()) {
    reach += leg.reach().hi / static_cast<double>(kinematics.legs().size());
    hip_z += leg.hip_B().z() / static_cast<double>(kinematics.legs().size());
  }
  BodyPose body;
  body.position_W.z() = hip_height_fraction * reach - hip_z;  // the feet's origins at z = 0
  Eigen::Vector2d shift = ApproximateComOffset(robot).head<2>() - centre;
  // A few fixed-point passes: the legs' pose, and so the COM, follows the feet (millimetres after two).
  for (int pass = 0; pass < 3; ++pass) {
    std::array<Eigen::Vector3d, 4> q{};
    for (std::size_t i = 0; i < robot.legs().size() && i < q.size(); ++i) {
      const int l = kinematics.LegIndex(robot.legs()[i].name);
      const Eigen::Vector2d foot = under_hips[i] + shift;
      q[static_cast<std::size_t>(l)] = kinematics.SolveFootIkWorld(l, Eigen::Vector3d(foot.x(), foot.y(), 0.0), body, ws).q;
    }
    shift += com_model.Com(body, q, ws).head<2>() - (centre + shift);
  }
  return shift;
}

}  // namespace

AlignmentStance ComputeAlignmentStance(const RobotKinematics& kinematics, const Staircase& stairs, const ConstrainedMap& map,
                                       Facing facing, double hip_height_fraction, double lead_gap) {
  const RobotModel& robot = kinematics.robot();
  AlignmentStance a;
  if (map.size() < 1 || map.stair(0).step_region.empty()) {
    a.reason = "the first surface has no step region to stand on";
    return a;
  }
  a.facing = facing;
  a.yaw = facing == Facing::kForward ? 0.0 : M_PI;
  const Eigen::Rotation2Dd turn(a.yaw);
  // Feet under the hips, then shifted so that their centre is under the centre of mass.
  std::vector<Eigen::Vector2d> offsets;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const LegModel& leg : robot.legs()) {
    offsets.emplace_back(leg.hip_B.x(), leg.foot_zero_B.y());
    centre += offsets.back() / static_cast<double>(robot.legs().size());
  }
  const Eigen::Vector2d shift = StandingShift(kinematics, offsets, centre, hip_height_fraction);
  double lead = -std::numeric_limits<double>::infinity();
  for (Eigen::Vector2d& o : offsets) {
    o = turn * (o + shift);
    lead = std::max(lead, o.x());
  }
  const Extent region = map.stair(0).step_region.XExtent();
  const double x = region.hi - lead_gap - lead;
  a.position = Eigen::Vector3d(x, 0.0, stairs.surfaces().front().z);
  for (const Eigen::Vector2d& o : offsets) {
    const Eigen::Vector2d foot(x + o.x(), o.y());
    if (foot.x() < region.lo - 1e-9) {
      a.reason = "landing_before is too short for the robot's stance before the flight";
      a.feet.clear();
      return a;
    }
    a.feet.emplace_back(foot.x(), foot.y(), stairs.HeightAt(foot.x(), foot.y()));
  }
  a.riser_distance = stairs.edges().empty() ? -x : stairs.edges().front().x_riser - x;
  a.standoff = stairs.edges().empty() ? -x : stairs.edges().front().x_nose - x;
  a.found = true;
  return a;
}

}  // namespace stairplan
