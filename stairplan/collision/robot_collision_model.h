// The robot's collision shapes (primitives and meshes) grouped by leg and body. Every link hanging from a leg chain
// link by fixed joints (Go1's rotors, Go2's lower calf, A1's shoulder) moves with that chain link;
// links fixed to the base (trunk, head, sensors) form the body. Shapes on the links fixed below
// the knee's link, down to the foot, are the foot's parts (CollisionShape::foot_part).
#pragma once

#include <vector>

#include "stairplan/collision/collision_shape.h"
#include "stairplan/kinematics/robot_kinematics.h"

namespace stairplan {

/// Const model: the shapes of each leg (in RobotKinematics leg order) and of the body.
class RobotCollisionModel {
 public:
  /// Throws std::invalid_argument naming the link for a mesh that spans no volume and naming the
  /// leg when a leg has no collision shape at all.
  explicit RobotCollisionModel(const RobotKinematics& kinematics);

  /// Shapes of leg `index`; each one's `segment` indexes that leg's LinkFrames().
  const std::vector<CollisionShape>& leg_shapes(int index) const { return legs_.at(static_cast<std::size_t>(index)); }
  /// Index into leg_shapes(index) of the leg's foot contact shape (its sphere, or a mesh foot's
  /// mesh); -1 when it has none.
  int foot_shape(int index) const { return foot_shapes_.at(static_cast<std::size_t>(index)); }
  /// Shapes fixed to the base frame (segment -1).
  const std::vector<CollisionShape>& body_shapes() const { return body_; }
  /// Number of legs (RobotKinematics leg order).
  int leg_count() const { return static_cast<int>(legs_.size()); }

 private:
  std::vector<std::vector<CollisionShape>> legs_;
  std::vector<int> foot_shapes_;
  std::vector<CollisionShape> body_;
};

}  // namespace stairplan
