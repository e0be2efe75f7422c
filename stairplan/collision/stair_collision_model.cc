#include "stairplan/collision/stair_collision_model.h"

#include <algorithm>
#include <cmath>

#include "stairplan/collision/collision_shape.h"

namespace stairplan {

const char* ToString(StairPart part) {
  switch (part) {
    case StairPart::kTread: return "tread";
    case StairPart::kRiser: return "riser";
    case StairPart::kNosing: return "nosing";
    case StairPart::kOther: return "other";
  }
  return "other";
}

StairCollisionModel::StairCollisionModel(const Staircase& stairs) {
  for (const Box3& box : stairs.Solids()) {
    StairSolid solid;
    solid.box = box;
    solid.geometry = MakeFclBox(box.Size());
    solid.pose.translation() = box.Center();
    solids_.push_back(solid);
  }
}

StairPart StairCollisionModel::PartAt(int index, const Eigen::Vector3d& point_W, double tol) const {
  const Box3& box = solids_.at(static_cast<std::size_t>(index)).box;
  if (box.kind == SolidKind::kNosing) return StairPart::kNosing;
  if (point_W.z() >= box.max.z() - tol) return StairPart::kTread;
  // The face nearest to the point (for a penetration the point is inside the solid).
  const double to_top = std::abs(box.max.z() - point_W.z());
  const double to_riser = std::min(std::abs(point_W.x() - box.min.x()), std::abs(point_W.x() - box.max.x()));
  const double to_other = std::min({std::abs(point_W.y() - box.min.y()), std::abs(point_W.y() - box.max.y()),
                                    std::abs(point_W.z() - box.min.z())});
  if (to_top <= to_riser && to_top <= to_other) return StairPart::kTread;
  return to_riser <= to_other ? StairPart::kRiser : StairPart::kOther;
}

}  // namespace stairplan
