#include "stairplan/geometry/stair_mode_engagement.h"

#include <stdexcept>
#include <string>

namespace stairplan {

StairModeEngagement StairModeAtPose(const StairModel& stairs, const GroundPose& pose, const StairModeSettings& settings) {
  StairMode mode({stairs}, settings);
  StairModeEngagement e;
  e.engaged = mode.Update(pose.xy) == 0;
  e.pose = pose;
  e.distance = DistanceToFlight(stairs, pose.xy);
  e.engage_distance = settings.engage_distance;
  return e;
}

StairModeEngagement EngagementAlongTrack(const std::vector<GroundPose>& track, const std::vector<StairModel>& stairs,
                                         int staircase, const StairModeSettings& settings) {
  if (staircase < 0 || staircase >= static_cast<int>(stairs.size())) {
    throw std::invalid_argument("EngagementAlongTrack: staircase " + std::to_string(staircase) + " of " +
                                std::to_string(stairs.size()) + " known");
  }
  StairMode mode(stairs, settings);
  const StairModel& flight = stairs[static_cast<std::size_t>(staircase)];
  StairModeEngagement nearest;
  nearest.engage_distance = settings.engage_distance;
  for (const GroundPose& pose : track) {
    const double d = DistanceToFlight(flight, pose.xy);
    if (mode.Update(pose.xy) == staircase) return {true, pose, d, settings.engage_distance};
    if (d < nearest.distance) {
      nearest.pose = pose;
      nearest.distance = d;
    }
  }
  return nearest;
}

}  // namespace stairplan
