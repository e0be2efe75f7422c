#include "stairplan/geometry/stair_model.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace stairplan {
namespace {

Eigen::Vector2d Left(const Eigen::Vector2d& d) { return Eigen::Vector2d(-d.y(), d.x()); }

}  // namespace

double StairModel::yaw() const { return std::atan2(direction.y(), direction.x()); }

std::vector<EdgeLine> StairModel::Edges() const {
  std::vector<EdgeLine> edges;
  const Eigen::Vector2d left = Left(direction);
  for (std::size_t k = 0; k < edge_offsets.size(); ++k) {
    const Eigen::Vector2d mid = center + edge_offsets[k] * direction;
    const double z = k + 1 < levels.size() ? levels[k + 1] : 0.0;
    EdgeLine e;
    e.a << mid - 0.5 * width * left, z;
    e.b << mid + 0.5 * width * left, z;
    edges.push_back(e);
  }
  return edges;
}

double StairModel::TravelYaw(TravelDirection travel) const {
  return travel == TravelDirection::kUp ? yaw() : std::atan2(-direction.y(), -direction.x());
}

Staircase StairModel::ToStaircase(TravelDirection travel, double nosing, double landing) const {
  if (steps < 1) throw std::invalid_argument("StairModel::ToStaircase: the model has no steps");
  StairSpec spec;
  spec.steps = steps;
  spec.rise = rise;
  spec.run = run;
  spec.width = width;
  spec.nosing = nosing;
  spec.nosing_thickness = std::min(spec.nosing_thickness, 0.5 * rise);
  spec.landing_before = landing;
  spec.landing_after = landing;
  spec.direction = travel;
  spec.uncertainty = uncertainty;
  return Staircase(spec);
}

// The Staircase frame's origin is the first riser in travel order: the riser lies `nosing` behind
// its walking edge towards the upper level, ascending or descending.
Eigen::Vector3d StairModel::StairToWorld(const Eigen::Vector3d& p_S, TravelDirection travel, double nosing) const {
  const double first_edge = travel == TravelDirection::kUp ? 0.0 : (edge_offsets.empty() ? 0.0 : edge_offsets.back());
  const Eigen::Vector2d origin = center + (first_edge + nosing) * direction;
  const double yaw_t = TravelYaw(travel);
  const Eigen::Vector2d x_axis(std::cos(yaw_t), std::sin(yaw_t));
  const Eigen::Vector2d xy = origin + p_S.x() * x_axis + p_S.y() * Left(x_axis);
  const double base = levels.empty() ? 0.0 : levels.front();
  return Eigen::Vector3d(xy.x(), xy.y(), p_S.z() + base);
}

Eigen::Vector3d StairModel::WorldToStair(const Eigen::Vector3d& p_W, TravelDirection travel, double nosing) const {
  const double first_edge = travel == TravelDirection::kUp ? 0.0 : (edge_offsets.empty() ? 0.0 : edge_offsets.back());
  const Eigen::Vector2d origin = center + (first_edge + nosing) * direction;
  const double yaw_t = TravelYaw(travel);
  const Eigen::Vector2d x_axis(std::cos(yaw_t), std::sin(yaw_t));
  const Eigen::Vector2d d = p_W.head<2>() - origin;
  const double base = levels.empty() ? 0.0 : levels.front();
  return Eigen::Vector3d(d.dot(x_axis), d.dot(Left(x_axis)), p_W.z() - base);
}

StairModel ModelOfStaircase(const Staircase& stairs, const Eigen::Vector3d& origin_W, double yaw) {
  const Eigen::Vector2d x_axis(std::cos(yaw), std::sin(yaw));
  const bool up = stairs.direction() == TravelDirection::kUp;
  const auto world = [&](double x, double y) { return Eigen::Vector2d(origin_W.head<2>() + x * x_axis + y * Left(x_axis)); };
  StairModel m;
  m.direction = up ? x_axis : Eigen::Vector2d(-x_axis);
  m.steps = stairs.steps();
  m.width = stairs.spec().width;
  std::vector<StairEdge> edges = stairs.edges();
  std::vector<StairSurface> surfaces = stairs.surfaces();
  if (!up) {
    std::reverse(edges.begin(), edges.end());
    std::reverse(surfaces.begin(), surfaces.end());
  }
  for (const StairSurface& s : surfaces) m.levels.push_back(origin_W.z() + s.z);
  m.center = world(edges.front().x_nose, 0.0);
  for (const StairEdge& e : edges) m.edge_offsets.push_back((world(e.x_nose, 0.0) - m.center).dot(m.direction));
  m.rise = (m.levels.back() - m.levels.front()) / m.steps;
  m.run = m.steps > 1 ? m.edge_offsets.back() / (m.steps - 1) : stairs.spec().run;
  m.uncertainty = stairs.spec().uncertainty;
  return m;
}

}  // namespace stairplan
