#include "stairplan/collision/robot_collision_regions.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "stairplan/collision/clearance.h"
#include "stairplan/collision/stance_check.h"

namespace stairplan {
namespace {

// The body's pitch along the flight: nose-up (negative) when the robot faces uphill.
double FlightPitch(const Staircase& stairs, double yaw) {
  const auto& edges = stairs.edges();
  const double mean_run = edges.size() >= 2 ? (edges.back().x_nose - edges.front().x_nose) / (edges.size() - 1.0)
                                            : stairs.spec().run;
  const double slope = (stairs.surfaces().back().z - stairs.surfaces().front().z) / (stairs.steps() * mean_run);
  return -std::atan(slope * std::cos(yaw));
}

}  // namespace

void RobotRegionSettings::Validate() const {
  if (!std::isfinite(sample_step) || sample_step <= 0.0 || sample_step > 0.1) {
    throw std::invalid_argument("RobotRegionSettings.sample_step: must be in (0, 0.1] m (got " + std::to_string(sample_step) + ")");
  }
  if (!std::isfinite(min_clearance)) throw std::invalid_argument("RobotRegionSettings.min_clearance: must be finite");
  if (!std::isfinite(hip_height_fraction) || hip_height_fraction <= 0.0 || hip_height_fraction > 1.0) {
    throw std::invalid_argument("RobotRegionSettings.hip_height_fraction: must be in (0, 1]");
  }
}

std::vector<RobotRegion> FindRobotCollisionRegions(const RobotKinematics& kinematics, const RobotCollisionModel& robot,
                                                   const Staircase& stairs, Facing facing,
                                                   const RobotRegionSettings& settings) {
  settings.Validate();
  const StairCollisionModel solids(stairs);
  RobotWorkspace ws(kinematics);
  const double yaw = facing == Facing::kForward ? 0.0 : M_PI;
  const double pitch = FlightPitch(stairs, yaw);
  std::vector<RobotRegion> regions;
  for (const StairSurface& surface : stairs.surfaces()) {
    bool open = false;
    RobotRegion current;
    const int samples = static_cast<int>(std::floor((surface.x_end - surface.x_begin) / settings.sample_step));
    for (int i = 0; i <= samples; ++i) {
      const double x = std::min(surface.x_end, surface.x_begin + i * settings.sample_step);
      int hit_leg = -1;
      StairPart hit_part = StairPart::kOther;
      for (int l = 0; l < kinematics.leg_count() && hit_leg < 0; ++l) {
        const LegKinematics& leg = kinematics.leg(l);
        const LegModel& model = leg.model();
        BodyPose body;
        body.pitch = pitch;
        body.yaw = yaw;
        const Eigen::Vector3d contact(x, std::cos(yaw) * model.foot_zero_B.y(), surface.z);
        // Hip straight above the foot's sphere at the planner's hip height.
        const Eigen::Vector3d hip_W = contact + Eigen::Vector3d(0, 0, model.foot_radius + settings.hip_height_fraction * model.max_reach);
        body.position_W = hip_W - body.ToIsometry().linear() * leg.hip_B();
        // The contact point lies off the foot origin (a wheel radius for a mesh foot, the sphere's
        // offset in the foot link for some URDFs) in a direction that turns with the shank: placed
        // with the body's orientation it would sit millimetres under the tread (Go2: 2.4 mm, the
        // whole landing a region), so it is re-aimed as the stance check does.
        const IkResult ik = SolveContactIk(leg, contact, body.ToIsometry(), leg.nominal(), ws.leg(l));
        if (!ik.ok()) continue;
        const Clearance c = LegStairClearance(kinematics, robot, solids, l, ik.q, body, ws);
        if (!(c.distance > settings.min_clearance)) {
          hit_leg = l;
          hit_part = c.part;
        }
      }
      if (hit_leg >= 0) {
        if (!open) {
          current = RobotRegion{surface.index, std::max(surface.x_begin, x - 0.5 * settings.sample_step), x, hit_part, hit_leg};
          open = true;
        }
        current.x1 = std::min(surface.x_end, x + 0.5 * settings.sample_step);
      } else if (open) {
        regions.push_back(current);
        open = false;
      }
    }
    if (open) regions.push_back(current);
  }
  return regions;
}

void AddRobotCollisionRegions(const RobotKinematics& kinematics, const RobotCollisionModel& robot,
                              const Staircase& stairs, ConstrainedMap& map, const RobotRegionSettings& settings) {
  for (const RobotRegion& region : FindRobotCollisionRegions(kinematics, robot, stairs, map.facing(), settings)) {
    map.AddCollisionBand(region.stair_index, region.x0, region.x1, RegionKind::kRobot);
  }
}

}  // namespace stairplan
