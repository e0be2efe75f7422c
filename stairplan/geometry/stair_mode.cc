#include "stairplan/geometry/stair_mode.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "stairplan/geometry/field_error.h"

namespace stairplan {

void StairModeSettings::Validate() const {
  if (!(engage_distance >= 0.0) || !std::isfinite(engage_distance)) throw FieldError("engage_distance", "must be >= 0");
  if (!(release_distance >= engage_distance) || !std::isfinite(release_distance)) {
    throw FieldError("release_distance", "must be >= engage_distance");
  }
}

double DistanceToFlight(const StairModel& stairs, const Eigen::Vector2d& p) {
  const Eigen::Vector2d left(-stairs.direction.y(), stairs.direction.x());
  const Eigen::Vector2d d = p - stairs.center;
  const double length = stairs.edge_offsets.empty() ? 0.0 : stairs.edge_offsets.back();
  const double u = d.dot(stairs.direction), v = d.dot(left);
  const double du = u < 0.0 ? -u : (u > length ? u - length : 0.0);
  const double dv = std::max(0.0, std::abs(v) - 0.5 * stairs.width);
  return std::hypot(du, dv);
}

StairMode::StairMode(std::vector<StairModel> stairs, const StairModeSettings& settings) : stairs_(std::move(stairs)), settings_(settings) {
  settings_.Validate();
}

int StairMode::Update(const Eigen::Vector2d& robot_xy) {
  // Stay with the current flight until the robot is past the release distance (no flicker at
  // the threshold); otherwise engage for the nearest flight within the engage distance.
  if (active_ >= 0 && DistanceToFlight(stairs_[static_cast<std::size_t>(active_)], robot_xy) <= settings_.release_distance) return active_;
  active_ = -1;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < stairs_.size(); ++i) {
    const double d = DistanceToFlight(stairs_[i], robot_xy);
    if (d <= settings_.engage_distance && d < best) {
      best = d;
      active_ = static_cast<int>(i);
    }
  }
  return active_;
}

AlignmentPose ComputeAlignmentPose(const StairModel& stairs, TravelDirection travel, Facing facing, double standoff) {
  if (stairs.steps < 1 || stairs.levels.empty() || stairs.edge_offsets.empty()) {
    throw std::invalid_argument("ComputeAlignmentPose: the stair model has no steps");
  }
  if (!(standoff >= 0.0) || !std::isfinite(standoff)) throw std::invalid_argument("ComputeAlignmentPose: standoff must be >= 0");
  const bool up = travel == TravelDirection::kUp;
  const Eigen::Vector2d along = up ? stairs.direction : Eigen::Vector2d(-stairs.direction);
  // The first edge met, on the centre line (the model's centre is centred across the width).
  const Eigen::Vector2d first = stairs.center + (up ? 0.0 : stairs.edge_offsets.back()) * stairs.direction;
  AlignmentPose pose;
  pose.travel = travel;
  pose.facing = facing;
  pose.position << first - standoff * along, up ? stairs.levels.front() : stairs.levels.back();
  const double travel_yaw = std::atan2(along.y(), along.x());
  pose.yaw = facing == Facing::kForward ? travel_yaw : std::remainder(travel_yaw + M_PI, 2.0 * M_PI);
  // Sensors look along the direction vector the way the robot goes, with the stairs' slope.
  pose.sensor_direction << stairs.run * along, up ? stairs.rise : -stairs.rise;
  pose.sensor_direction.normalize();
  return pose;
}

}  // namespace stairplan
