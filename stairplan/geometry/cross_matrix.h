// The cross-product matrix of a vector: [r]x v = r x v. Eigen has the product (cross()) but not
// the matrix, which the wrench models need as a block of a linear map (the moment r x f of a
// force f at r about the origin, in terms of f).
#pragma once

#include <Eigen/Core>

namespace stairplan {

/// The matrix [r]x with [r]x v = r x v for every v.
inline Eigen::Matrix3d CrossMatrix(const Eigen::Vector3d& r) {
  Eigen::Matrix3d m;
  m << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
  return m;
}

}  // namespace stairplan
