// A URDF pose (urdfdom) as an Eigen transform, for the code that walks URDF trees.
#pragma once

#include <Eigen/Geometry>
#include <urdf_model/pose.h>

namespace stairplan {

inline Eigen::Isometry3d UrdfPoseToIsometry(const urdf::Pose& pose) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
                   .normalized()
                   .toRotationMatrix();
  t.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return t;
}

}  // namespace stairplan
