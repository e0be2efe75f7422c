#include "stairplan/planning/body/body_check.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <string>
#include <utility>

#include "stairplan/collision/stance_check.h"
#include "stairplan/planning/plan_timeline.h"

namespace stairplan {

namespace {

// Instants checked per interval between two body samples, its end included: a swing foot moves
// up to 2 cm in a 50 ms knot, and a link can pass a nosing between two samples that both keep
// the margin. Thirds of a 50 ms knot are finer than the validator's 20 ms replay.
constexpr int kInstantsPerInterval = 3;

// Notes a violation; the first one's text becomes the check's first_violation.
void Violated(BodyPlanCheck& check, double t, const std::string& part, const char* what) {
  if (check.violations++ > 0) return;
  char text[160];
  std::snprintf(text, sizeof(text), "t=%.3f s, %s: %s", t, part.c_str(), what);
  check.first_violation = text;
}

// Checks the body at `pose` at time t.
void CheckBodyAt(KinematicBodyBounds& bounds, const FootSchedule& schedule, double t, const BodyPose& pose,
                 double min_clearance, BodyPlanCheck& check) {
  // Every leg where the schedule has its foot: on its contact, or along its swing.
  std::array<Eigen::Vector3d, 4> feet;
  for (int l = 0; l < schedule.leg_count() && l < 4; ++l) {
    const LegPhase phase = schedule.Phase(l, t);
    feet[static_cast<std::size_t>(l)] = phase.stance ? phase.foot_W : schedule.SwingFoot(l, phase);
  }
  const StanceResult r = bounds.CheckFeet(pose, feet, min_clearance);
  if (!(r.body.distance >= min_clearance)) Violated(check, t, "body", "clearance below the margin");
  for (int l = 0; l < schedule.leg_count() && l < 4; ++l) {
    const LegStance& leg = r.legs[static_cast<std::size_t>(l)];
    const std::string& name = bounds.kinematics().leg(l).name();
    if (!leg.ik.ok()) {
      Violated(check, t, name, ToString(leg.ik.status));
      continue;
    }
    if (FootGrazesTread(bounds.collision_model(), l, leg.stairs)) continue;
    check.min_clearance = std::min(check.min_clearance, leg.stairs.distance);
    if (!(leg.stairs.distance >= min_clearance)) Violated(check, t, name, "clearance below the margin");
  }
  const std::array<std::pair<const char*, const Clearance*>, 4> pairs = {
      {{"LF/RF", &r.front_pair}, {"LH/RH", &r.hind_pair}, {"LF/LH", &r.left_pair}, {"RF/RH", &r.right_pair}}};
  for (const auto& [name, pair] : pairs) {
    if (!(pair->distance >= min_clearance)) Violated(check, t, name, "legs closer than the margin");
  }
}

}  // namespace

void CheckBodySample(KinematicBodyBounds& bounds, const FootSchedule& schedule, const std::vector<BodyState>& body,
                     std::size_t i, double min_clearance, BodyPlanCheck& check) {
  ++check.samples;
  const BodyState& b = body[i];
  const double t0 = i > 0 ? body[i - 1].t : b.t;
  for (int k = i > 0 ? 1 : kInstantsPerInterval; k <= kInstantsPerInterval; ++k) {
    const double t = k == kInstantsPerInterval ? b.t : t0 + (b.t - t0) * k / kInstantsPerInterval;
    CheckBodyAt(bounds, schedule, t, BodyPoseAt(body, t), min_clearance, check);
    ++check.instants;
  }
}

BodyPlanCheck CheckBodyTrajectory(KinematicBodyBounds& bounds, const FootSchedule& schedule,
                                  const std::vector<BodyState>& body, double min_clearance) {
  BodyPlanCheck check;
  for (std::size_t i = 0; i < body.size(); ++i) CheckBodySample(bounds, schedule, body, i, min_clearance, check);
  return check;
}

}  // namespace stairplan
