#include "stairplan/geometry/stair_frame.h"

#include <cmath>

namespace stairplan {

GroundPose StairFrame::ToWorld(const GroundPose& pose_S) const {
  GroundPose w = pose_S;
  w.xy = model.StairToWorld(Eigen::Vector3d(pose_S.xy.x(), pose_S.xy.y(), 0.0), travel, nosing).head<2>();
  w.yaw = std::remainder(pose_S.yaw + model.TravelYaw(travel), 2.0 * M_PI);
  return w;
}

GroundPose StairFrame::ToStair(const GroundPose& pose_W) const {
  GroundPose s = pose_W;
  s.xy = model.WorldToStair(Eigen::Vector3d(pose_W.xy.x(), pose_W.xy.y(), 0.0), travel, nosing).head<2>();
  s.yaw = std::remainder(pose_W.yaw - model.TravelYaw(travel), 2.0 * M_PI);
  return s;
}

}  // namespace stairplan
