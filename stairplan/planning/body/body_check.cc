#include "stairplan/planning/body/body_check.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <string>
#include <utility>

#include "stairplan/collision/stance_check.h"
#include "stairplan/geometry/shapes.h"
#include "stairplan/planning/plan_timeline.h"

namespace stairplan {

namespace {

// Instants checked per interval between two body samples, its end included: a swing foot moves
// up to 2 cm in a 50 ms knot, and a link can pass a nosing between two samples that both keep
// the margin. Thirds of a 50 ms knot are finer than the validator's 20 ms replay.
constexpr int kInstantsPerInterval = 3;

// Notes a violation; the first of each part and kind is kept, the very first as first_violation.
void Violated(BodyPlanCheck& check, double t, const std::string& part, const char* what) {
  ++check.violations;
  const std::string kind = part + ": " + what;
  // Each kept text ends in its kind, after the instant.
  for (const std::string& seen : check.first_of_each) {
    if (seen.size() >= kind.size() && seen.compare(seen.size() - kind.size(), kind.size(), kind) == 0) return;
  }
  char text[200];
  std::snprintf(text, sizeof(text), "t=%.3f s, %s", t, kind.c_str());
  check.first_of_each.emplace_back(text);
  if (check.first_violation.empty()) check.first_violation = text;
}

}  // namespace

std::string BodyPlanCheck::Summary() const {
  std::string summary;
  for (const std::string& v : first_of_each) summary += (summary.empty() ? "" : "; ") + v;
  return summary;
}

BodyChecker::BodyChecker(KinematicBodyBounds& bounds, const FootSchedule& schedule, const BodyCheckMargins& margins)
    : bounds_(bounds), schedule_(schedule), margins_(margins), com_(bounds.kinematics()), workspace_(bounds.kinematics()) {}

void BodyChecker::CheckAt(double t, const BodyPose& pose, BodyPlanCheck& check) {
  // Every leg where the schedule has its foot: on its contact, or along its swing.
  std::array<Eigen::Vector3d, 4> feet;
  std::array<bool, 4> down{};
  for (int l = 0; l < schedule_.leg_count() && l < 4; ++l) {
    const LegPhase phase = schedule_.Phase(l, t);
    feet[static_cast<std::size_t>(l)] = phase.stance ? phase.foot_W : schedule_.SwingFoot(l, phase);
    down[static_cast<std::size_t>(l)] = phase.stance;
  }
  const double min_clearance = margins_.clearance;
  // Only clearances below the margin and the smallest leg clearance so far are kept: a shape pair
  // surely farther apart than both needs no measuring, and the kept ones stay exact.
  const double prune = JudgePruneBound(check.min_clearance, min_clearance);
  const StanceResult r = bounds_.CheckFeet(pose, feet, min_clearance, prune);
  if (!(r.body.distance >= min_clearance)) Violated(check, t, "body", "clearance below the margin");
  bool reached = true;
  for (int l = 0; l < schedule_.leg_count() && l < 4; ++l) {
    const LegStance& leg = r.legs[static_cast<std::size_t>(l)];
    const std::string& name = bounds_.kinematics().leg(l).name();
    if (!leg.ik.ok()) {
      Violated(check, t, name, ToString(leg.ik.status));
      reached = false;
      continue;
    }
    if (FootGrazesTread(bounds_.collision_model(), l, leg.stairs)) continue;
    check.min_clearance = std::min(check.min_clearance, leg.stairs.distance);
    if (!(leg.stairs.distance >= min_clearance)) Violated(check, t, name, "clearance below the margin");
  }
  const std::array<std::pair<const char*, const Clearance*>, 4> pairs = {
      {{"LF/RF", &r.front_pair}, {"LH/RH", &r.hind_pair}, {"LF/LH", &r.left_pair}, {"RF/RH", &r.right_pair}}};
  for (const auto& [name, pair] : pairs) {
    if (!(pair->distance >= min_clearance)) Violated(check, t, name, "legs closer than the margin");
  }
  // A leg that does not reach has no joint angles to place its links' masses by.
  if (reached && margins_.stability >= 0.0) CheckStability(t, pose, r, down, feet, check);
}

void BodyChecker::CheckStability(double t, const BodyPose& pose, const StanceResult& stance, const std::array<bool, 4>& down,
                                 const std::array<Eigen::Vector3d, 4>& feet, BodyPlanCheck& check) {
  std::vector<Eigen::Vector2d> support;
  for (std::size_t l = 0; l < feet.size(); ++l) {
    if (down[l]) support.push_back(feet[l].head<2>());
  }
  if (support.size() < 3) return;
  std::array<Eigen::Vector3d, 4> q;
  for (std::size_t l = 0; l < q.size(); ++l) q[l] = stance.legs[l].ik.q;
  const Eigen::Vector3d com = com_.Com(pose, q, workspace_);
  const double margin = -ConvexHull(std::move(support)).SignedDistance(com.head<2>());
  check.min_stability_margin = std::min(check.min_stability_margin, margin);
  if (!(margin >= margins_.stability)) Violated(check, t, "body", "centre of mass closer than the stability margin to the support's edge");
}

void BodyChecker::CheckSample(const std::vector<BodyState>& body, std::size_t i, BodyPlanCheck& check) {
  ++check.samples;
  const BodyState& b = body[i];
  // Samples only: between two the body moves on a straight line.
  farthest_x_ = std::max(farthest_x_, b.x);
  check.max_retreat = std::max(check.max_retreat, farthest_x_ - b.x);
  if (!(farthest_x_ - b.x <= margins_.retreat)) Violated(check, b.t, "body", "moved back along the travel by more than the bound");
  const double t0 = i > 0 ? body[i - 1].t : b.t;
  for (int k = i > 0 ? 1 : kInstantsPerInterval; k <= kInstantsPerInterval; ++k) {
    const double t = k == kInstantsPerInterval ? b.t : t0 + (b.t - t0) * k / kInstantsPerInterval;
    CheckAt(t, BodyPoseAt(body, t), check);
    ++check.instants;
  }
}

BodyPlanCheck BodyChecker::CheckTrajectory(const std::vector<BodyState>& body) {
  BodyPlanCheck check;
  farthest_x_ = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < body.size(); ++i) CheckSample(body, i, check);
  return check;
}

BodyPlanCheck CheckBodyTrajectory(KinematicBodyBounds& bounds, const FootSchedule& schedule,
                                  const std::vector<BodyState>& body, const BodyCheckMargins& margins) {
  return BodyChecker(bounds, schedule, margins).CheckTrajectory(body);
}

}  // namespace stairplan
