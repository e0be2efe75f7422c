// The body planner's bounds from the robot: the reach of a foot in the air (a swinging leg's
// bound) checked against the leg's IK, and against a standing leg's bound on the same box.
#include <catch2/catch.hpp>

#include <cmath>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/planning/body/kinematic_body_bounds.h"

using namespace stairplan;

namespace {

// The body pose that puts leg `leg`'s hip at (dx forward, the leg's nominal sideways offset,
// h above) the point `foot_W`, pitched by `pitch`, facing forward.
BodyPose HipAbove(const KinematicBodyBounds& bounds, int leg, const Eigen::Vector3d& foot_W, double dx, double h,
                  double pitch) {
  const LegModel& m = bounds.kinematics().leg(leg).model();
  BodyPose pose;
  pose.pitch = pitch;
  const Eigen::Vector3d hip_W = foot_W + Eigen::Vector3d(dx, m.hip_B.y() - m.foot_zero_B.y(), h);
  pose.position_W = hip_W - pose.ToIsometry().linear() * m.hip_B;
  return pose;
}

}  // namespace

TEST_CASE("a foot in the air is reached at every hip height ReachHeight allows, and not far beyond it",
          "[body][bounds]") {
  const RobotModel& robot = BuiltinRobot();
  const Staircase stairs{StairSpec{}};
  KinematicBodyBounds bounds(robot, stairs, Facing::kForward);
  // One foothold per leg on the first landing, so the stance bound can be compared on the same box.
  std::vector<Foothold> footholds;
  for (int l = 0; l < 4; ++l) footholds.push_back({l, Eigen::Vector3d(-0.3, 0.0, 0.0), 0});
  bounds.SetFootholds(footholds);
  const double margin = BodyPlannerSettings{}.reach_margin;
  // A foot 0.4 m above the landing, far from every stair solid: only the leg's reach matters.
  const Eigen::Vector3d air(-0.3, 0.0, 0.4);
  int checked = 0;
  for (int l = 0; l < 4; ++l) {
    for (const double dx : {-0.15, 0.0, 0.12}) {
      for (const double pitch : {-0.4, 0.0, 0.3}) {
        const HipBox box{l, l, dx, dx, pitch, pitch};
        const HeightRange reach = bounds.ReachHeight(box);
        REQUIRE_FALSE(reach.empty());
        // A standing leg's range adds the clearance to the stairs: never wider than the reach.
        const HeightRange stance = bounds.HipHeight(box);
        if (!stance.empty()) {
          CHECK(stance.lo >= reach.lo - 1e-6);
          CHECK(stance.hi <= reach.hi + 1e-6);
        }
        INFO("leg " << l << " dx " << dx << " pitch " << pitch << ": [" << reach.lo << ", " << reach.hi << "]");
        for (const double u : {0.0, 0.5, 1.0}) {
          const double h = reach.lo + u * (reach.hi - reach.lo);
          CHECK(bounds.CheckLeg(l, air, HipAbove(bounds, l, air, dx, h, pitch)).ik.ok());
          ++checked;
        }
        // The margin is all that separates the bound from the leg's real reach (to the grid's
        // interpolation error): a few centimetres beyond it the foot is out of reach.
        CHECK_FALSE(bounds.CheckLeg(l, air, HipAbove(bounds, l, air, dx, reach.hi + margin + 0.03, pitch)).ik.ok());
      }
    }
  }
  CHECK(checked == 4 * 9 * 3);
}
