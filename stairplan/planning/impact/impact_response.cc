#include "stairplan/planning/impact/impact_response.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>

#include "stairplan/geometry/field_error.h"

namespace stairplan {
namespace {

// Risk of stepping into a collision region of each kind in a remedial step ([0061]): glancing a
// riser is acceptable, unknown data less so; stepping off an edge or a side never is.
int RiskRank(RegionKind kind) {
  switch (kind) {
    case RegionKind::kRiser: return 0;
    case RegionKind::kRobot: return 1;
    case RegionKind::kData: return 2;
    case RegionKind::kEdge:
    case RegionKind::kSide: return -1;
  }
  return -1;
}

// Unit vector, in the world xy plane, from the body's midline toward this leg's own side.
Eigen::Vector2d OwnSide(const ImpactEvent& e) {
  const double side = (!e.leg.empty() && e.leg[0] == 'R') ? -1.0 : 1.0;
  return side * Eigen::Vector2d(-std::sin(e.body_yaw), std::cos(e.body_yaw));
}

Eigen::Vector2d Forward(const ImpactEvent& e) { return {std::cos(e.body_yaw), std::sin(e.body_yaw)}; }

// Where the foot should go to keep `clearance` from the contralateral foot, on its own side.
Eigen::Vector2d ShiftedAway(const ImpactEvent& e, const ImpactSettings& s) {
  const Eigen::Vector2d side = OwnSide(e);
  const double target_lat = side.dot(e.target_W.head<2>());
  const double contra_lat = side.dot(e.contralateral_foot_W.head<2>());
  const double wanted = std::max(target_lat + 0.5 * s.contralateral_clearance, contra_lat + s.contralateral_clearance);
  return e.target_W.head<2>() + (wanted - target_lat) * side;
}

// Inside a region no remedial step may use (strictly: shared boundaries are allowed).
bool InForbiddenRegion(const StairRegions& stair, const Eigen::Vector2d& p) {
  for (const CollisionRegion& region : stair.collision_regions) {
    if (RiskRank(region.kind) < 0 && region.polygon.SignedDistance(p) < -1e-9) return true;
  }
  return false;
}

bool ClearOfContralateral(const ImpactEvent& e, const Eigen::Vector2d& p, const ImpactSettings& s) {
  const Eigen::Vector2d side = OwnSide(e);
  return side.dot(p) - side.dot(e.contralateral_foot_W.head<2>()) >= s.contralateral_clearance - 1e-9;
}

// The adjusted step location: inside the step region and clear of the contralateral leg, or
// else the least risky acceptable spot of a collision region; kProceed when there is neither.
ImpactResponse AdjustedStep(const ImpactEvent& e, const ConstrainedMap& map, const ImpactSettings& s) {
  ImpactResponse r;
  r.target_W = e.target_W;
  if (e.target_stair < 0 || e.target_stair >= map.size()) {
    r.kind = ResponseKind::kProceed;
    r.reason = "target stair unknown; continuing the planned step";
    return r;
  }
  const StairRegions& stair = map.stair(e.target_stair);
  const Eigen::Vector2d wanted = ShiftedAway(e, s);
  if (!stair.step_region.empty()) {
    const Eigen::Vector2d p = stair.step_region.ClosestPoint(wanted);
    if (ClearOfContralateral(e, p, s)) {
      r.kind = ResponseKind::kAdjustStep;
      r.target_W = {p.x(), p.y(), stair.z};
      r.reason = "shifted away from the contralateral leg inside the step region";
      return r;
    }
  }
  int best_rank = std::numeric_limits<int>::max();
  double best_distance = std::numeric_limits<double>::infinity();
  for (const CollisionRegion& region : stair.collision_regions) {
    const int rank = RiskRank(region.kind);
    if (rank < 0 || rank > best_rank) continue;
    const Eigen::Vector2d p = region.polygon.ClosestPoint(wanted);
    if (!ClearOfContralateral(e, p, s) || InForbiddenRegion(stair, p)) continue;
    const double d = (p - wanted).norm();
    if (rank < best_rank || d < best_distance) {
      best_rank = rank;
      best_distance = d;
      r.target_W = {p.x(), p.y(), stair.z};
      r.kind = ResponseKind::kAdjustStepRisky;
      r.reason = std::string("no free step region; least risky spot in the ") + ToString(region.kind) + " region";
    }
  }
  if (best_rank == std::numeric_limits<int>::max()) {
    r.kind = ResponseKind::kProceed;
    r.reason = "no acceptable adjusted location; continuing the planned step";
  }
  return r;
}

// Crossed legs: first fore/aft away from the stance leg, then sideways to the own side, then the
// adjusted target ([0062]); moving sideways first would trip on the stance leg.
ImpactResponse Untangle(const ImpactEvent& e, const ConstrainedMap& map, const ImpactSettings& s) {
  ImpactResponse r = AdjustedStep(e, map, s);
  const Eigen::Vector2d forward = Forward(e);
  const double ahead = forward.dot(e.swing_foot_W.head<2>() - e.contralateral_foot_W.head<2>());
  const Eigen::Vector3d fore_aft(forward.x(), forward.y(), 0.0);
  const Eigen::Vector3d first = e.swing_foot_W + (ahead >= 0.0 ? 1.0 : -1.0) * s.untangle_distance * fore_aft;
  const Eigen::Vector2d side = OwnSide(e);
  const double lateral = side.dot(e.contralateral_foot_W.head<2>()) + s.contralateral_clearance - side.dot(first.head<2>());
  const Eigen::Vector3d second = first + lateral * Eigen::Vector3d(side.x(), side.y(), 0.0);
  r.waypoints_W = {first, second};
  r.kind = ResponseKind::kUntangle;
  r.reason = std::string(ahead >= 0.0 ? "crossed in front: forward" : "crossed behind: backward") +
             " first, then sideways; " + r.reason;
  return r;
}

// `poly` (convex, counter-clockwise) with every edge moved `d` inwards; empty when it vanishes.
Polygon2 Inset(const Polygon2& poly, double d) {
  Polygon2 out;
  out.z = poly.z;
  const std::size_t n = poly.vertices.size();
  if (n < 3) return out;
  const auto inward = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    const Eigen::Vector2d e = (b - a).normalized();
    return Eigen::Vector2d(-e.y(), e.x());  // left of a counter-clockwise edge is inside
  };
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = poly.vertices[(i + n - 1) % n];
    const Eigen::Vector2d& v = poly.vertices[i];
    const Eigen::Vector2d& b = poly.vertices[(i + 1) % n];
    const Eigen::Vector2d n1 = inward(a, v), n2 = inward(v, b);
    Eigen::Matrix2d lines;
    lines << n1.transpose(), n2.transpose();
    const Eigen::Vector2d offsets(n1.dot(v) + d, n2.dot(v) + d);
    out.vertices.push_back(std::abs(lines.determinant()) < 1e-12 ? Eigen::Vector2d(v + d * n1)
                                                                  : Eigen::Vector2d(lines.partialPivLu().solve(offsets)));
  }
  for (const Eigen::Vector2d& q : out.vertices) {
    if (poly.SignedDistance(q) > -d + 1e-9) return {};
  }
  if (out.Area() <= 1e-12) return {};
  return out;
}

// A foot down outside the step region: the nearest point of the target stair's step region, a
// margin inside, where the foot is moved with a short re-swing.
ImpactResponse IntoStepRegion(const ImpactEvent& e, const ConstrainedMap& map, const ImpactSettings& s) {
  ImpactResponse r;
  r.target_W = e.target_W;
  if (e.target_stair < 0 || e.target_stair >= map.size() || map.stair(e.target_stair).step_region.empty()) {
    r.kind = ResponseKind::kProceed;
    r.reason = "outside the step region, and the target stair has none: staying";
    return r;
  }
  const StairRegions& stair = map.stair(e.target_stair);
  const Polygon2 inner = Inset(stair.step_region, s.step_region_margin);
  const Eigen::Vector2d p = (inner.empty() ? stair.step_region : inner).ClosestPoint(e.swing_foot_W.head<2>());
  r.kind = ResponseKind::kAdjustStep;
  r.target_W = {p.x(), p.y(), stair.z};
  r.reason = "down outside the step region: moved to its nearest point";
  return r;
}

ImpactResponse Simple(ResponseKind kind, const ImpactEvent& e, const std::string& reason) {
  ImpactResponse r;
  r.kind = kind;
  r.target_W = e.target_W;
  r.reason = reason;
  return r;
}

}  // namespace

const char* ToString(ImpactKind kind) {
  switch (kind) {
    case ImpactKind::kTouchdown: return "touchdown";
    case ImpactKind::kKneeBehindBody: return "knee_behind_body";
    case ImpactKind::kContralateralStrike: return "contralateral_strike";
    case ImpactKind::kContralateralCrossing: return "contralateral_crossing";
    case ImpactKind::kTrip: return "trip";
    case ImpactKind::kThighAgainstBody: return "thigh_against_body";
    case ImpactKind::kLiftoffScuff: return "liftoff_scuff";
    case ImpactKind::kKneeGlancingTerrain: return "knee_glancing_terrain";
    case ImpactKind::kIpsilateralStrike: return "ipsilateral_strike";
    case ImpactKind::kMisplacedTouchdown: return "misplaced_touchdown";
  }
  return "unknown";
}

const char* ToString(ResponseKind kind) {
  switch (kind) {
    case ResponseKind::kClassifyStance: return "classify_stance";
    case ResponseKind::kMoveKneeForward: return "move_knee_forward";
    case ResponseKind::kAdjustStep: return "adjust_step";
    case ResponseKind::kAdjustStepRisky: return "adjust_step_risky";
    case ResponseKind::kUntangle: return "untangle";
    case ResponseKind::kElevateFoot: return "elevate_foot";
    case ResponseKind::kTouchdownNow: return "touchdown_now";
    case ResponseKind::kProceed: return "proceed";
  }
  return "unknown";
}

void ImpactSettings::Validate() const {
  RequireInRange("early_swing_phase", early_swing_phase, 0.0, 1.0);
  RequireInRange("elevate_height", elevate_height, 0.0, 1.0);
  RequireInRange("contralateral_clearance", contralateral_clearance, 0.0, 1.0);
  RequireInRange("untangle_distance", untangle_distance, 0.0, 1.0);
  RequireInRange("knee_forward_distance", knee_forward_distance, 0.0, 1.0);
  RequireInRange("step_region_margin", step_region_margin, 0.0, 1.0);
}

ImpactResponse RespondToImpact(const ImpactEvent& event, const ConstrainedMap& map, const ImpactSettings& settings) {
  settings.Validate();
  if (!event.swing_foot_W.allFinite() || !event.target_W.allFinite() || !event.contralateral_foot_W.allFinite() ||
      !std::isfinite(event.swing_phase) || !std::isfinite(event.body_yaw)) {
    throw std::invalid_argument("RespondToImpact: event has a non-finite position, phase or yaw");
  }
  switch (event.kind) {
    case ImpactKind::kTouchdown:
      return Simple(ResponseKind::kClassifyStance, event, "touchdown: the swing leg becomes a stance leg");
    case ImpactKind::kKneeBehindBody: {
      ImpactResponse r = Simple(ResponseKind::kMoveKneeForward, event, "knee hit behind the body: knee forward, beneath the body");
      r.knee_forward = settings.knee_forward_distance;
      return r;
    }
    case ImpactKind::kContralateralStrike:
      return AdjustedStep(event, map, settings);
    case ImpactKind::kContralateralCrossing:
      return Untangle(event, map, settings);
    case ImpactKind::kTrip: {
      if (event.swing_phase < settings.early_swing_phase) {
        ImpactResponse r = Simple(ResponseKind::kElevateFoot, event, "trip early in swing: elevate the foot");
        r.extra_swing_height = settings.elevate_height;
        return r;
      }
      ImpactResponse r = Simple(ResponseKind::kTouchdownNow, event, "trip late in swing: touch down at once");
      const int below = map.StairAt(event.swing_foot_W.head<2>());
      r.target_W = event.swing_foot_W;
      if (below >= 0) r.target_W.z() = map.stair(below).z;
      return r;
    }
    case ImpactKind::kThighAgainstBody:
      return Simple(ResponseKind::kProceed, event, "thigh against body: no reaction");
    case ImpactKind::kLiftoffScuff:
      return Simple(ResponseKind::kProceed, event, "liftoff scuff: the rising foot clears it");
    case ImpactKind::kKneeGlancingTerrain:
      return Simple(ResponseKind::kProceed, event, "knee glanced the terrain: no reaction");
    case ImpactKind::kIpsilateralStrike:
      return Simple(ResponseKind::kProceed, event, "foot struck the leg on its own side: the legs part as the swing goes on");
    case ImpactKind::kMisplacedTouchdown:
      return IntoStepRegion(event, map, settings);
  }
  return Simple(ResponseKind::kProceed, event, "unknown impact");
}

}  // namespace stairplan
