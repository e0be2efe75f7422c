#include "stairplan/planning/step/paper_crawl.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "stairplan/planning/swing_trajectory.h"

namespace stairplan {
namespace {

struct PaperLeg {
  int robot_index = -1;
  double hip_x = 0.0;   // hip's horizontal offset from the hind hips at the stairs' slope [m]
  double offset = 0.0;  // contact offset a [m]
  double y = 0.0;       // foot's lateral position [m]
};

// The paper's roles (HR, HL, FR, FL) by leg name.
constexpr const char* kPaperLegNames[4] = {"RH", "LH", "RF", "LF"};

int LegIndex(const RobotModel& robot, const char* name) {
  for (std::size_t i = 0; i < robot.legs().size(); ++i) {
    if (robot.legs()[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

// The design's input from the robot's hips and feet and the stairs' nominal rise and run.
GaitDesignInput PaperDesignInput(const RobotModel& robot, const std::array<PaperLeg, 4>& legs, double W, double H,
                                 const PaperCrawlSettings& settings) {
  const auto leg = [&](std::size_t r) -> const LegModel& { return robot.legs()[static_cast<std::size_t>(legs[r].robot_index)]; };
  GaitDesignInput input;
  input.rise = H;
  input.run = W;
  input.max_leg_length = settings.max_leg_length;
  input.body_length = 0.5 * (leg(2).hip_B.x() + leg(3).hip_B.x() - leg(0).hip_B.x() - leg(1).hip_B.x());
  input.body_width = std::abs(leg(1).foot_zero_B.y() - leg(0).foot_zero_B.y());
  input.buffer = settings.buffer;
  if (settings.hip_clearance >= 0.0) {
    input.hip_clearance = settings.hip_clearance;
    return input;
  }
  // a_min + a_max = W with eqs. (3) and (4): 2 d csc(phi) = l_min + sqrt(l_max^2 - CL^2/4) csc(phi) - W.
  const double cl = std::hypot(W, H), sin_phi = H / cl;
  const double arm2 = settings.max_leg_length * settings.max_leg_length - 0.25 * cl * cl;
  if (arm2 > 0.0) input.hip_clearance = std::max(0.0, 0.5 * ((MinLegLength(W, H) - W) * sin_phi + std::sqrt(arm2)));
  return input;
}

// The share of a swing's horizontal travel the foot makes low before it rises (Footstep::
// swing_approach_share): up to `margin` before the first solid above the foothold it leaves (the
// riser it climbs). With l_max 21 cm on 17 cm risers the hip at lift-off is barely above the upper
// tread (that is what l_min means), so a foot lifted behind it could not reach the nose's height.
double ApproachShare(const Eigen::Vector3d& from_W, const Eigen::Vector3d& to_W, const Staircase& stairs, double margin) {
  const double travel = to_W.x() - from_W.x();
  if (travel <= 0.0) return 0.0;
  double edge = to_W.x();
  for (const Box3& box : stairs.Solids()) {
    if (box.max.z() > from_W.z() + 1e-6 && box.max.x() > from_W.x() && box.min.x() < edge) edge = std::max(box.min.x(), from_W.x());
  }
  return std::clamp((edge - margin - from_W.x()) / travel, 0.0, 0.9);
}

Plan PaperInfeasible(Plan plan, const std::string& reason) {
  plan.status = PlanStatus::kInfeasible;
  plan.status_reason = reason;
  return plan;
}

}  // namespace

void PaperCrawlSettings::Validate() const {
  const auto positive = [](const char* field, double v) {
    if (!std::isfinite(v) || v <= 0.0) throw std::invalid_argument(std::string(field) + ": must be a finite number > 0");
  };
  positive("max_leg_length", max_leg_length);
  positive("swing_duration", swing_duration);
  if (!std::isfinite(buffer) || buffer < 0.0 || buffer >= 1.0) throw std::invalid_argument("buffer: must be in [0, 1)");
  if (!std::isfinite(settle_s) || settle_s < 0.0) throw std::invalid_argument("settle_s: must be a finite number >= 0");
  if (!std::isfinite(hip_clearance)) throw std::invalid_argument("hip_clearance: must be finite");
  body.Validate();
}

Plan PlanPaperCrawl(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map,
                    const PaperCrawlSettings& settings) {
  settings.Validate();
  const bool switched = settings.arrangement == CrawlCase::kFrontSwitched;
  Plan plan;
  plan.robot_name = robot.name();
  plan.robot_source = robot.source();
  plan.facing = map.facing();
  plan.cadence_s = settings.swing_duration;
  plan.gait = switched ? Gait::kPaperCrawlAlternate : Gait::kPaperCrawl;
  plan.hip_height_fraction = settings.body.hip_height_fraction;
  for (const LegModel& leg : robot.legs()) plan.legs.push_back(leg.name);
  if (stairs.direction() != TravelDirection::kUp || map.facing() != Facing::kForward) {
    return PaperInfeasible(plan, "the paper's crawl climbs facing forward only");
  }
  const int steps = stairs.steps();
  const double W = stairs.spec().run, H = stairs.spec().rise;

  std::array<PaperLeg, 4> legs;  // HR, HL, FR, FL as in CrawlStability
  for (std::size_t r = 0; r < 4; ++r) {
    legs[r].robot_index = LegIndex(robot, kPaperLegNames[r]);
    if (legs[r].robot_index < 0) return PaperInfeasible(plan, std::string("the robot has no leg named ") + kPaperLegNames[r]);
  }
  const GaitDesignInput input = PaperDesignInput(robot, legs, W, H, settings);
  GaitDesign g;
  try {
    g = DesignGait(input);
  } catch (const std::invalid_argument& e) {
    return PaperInfeasible(plan, std::string("gait design: ") + e.what());
  }
  if (!g.feasible) return PaperInfeasible(plan, "gait design infeasible on these stairs: condition " + g.binding + " fails");
  const double cos_phi = std::cos(g.phi), sin_phi = std::sin(g.phi);
  for (std::size_t r = 0; r < 4; ++r) {
    const bool right = r == 0 || r == 2, front = r >= 2;
    legs[r].hip_x = front ? input.body_length * cos_phi : 0.0;
    legs[r].offset = (right != (front && switched)) ? g.a_min : g.a_max;
    legs[r].y = robot.legs()[static_cast<std::size_t>(legs[r].robot_index)].foot_zero_B.y();
  }

  // Noses: the flight's edges, continued one run apart over both landings (virtual steps).
  const double first_nose = stairs.edges().front().x_nose, last_nose = stairs.edges().back().x_nose;
  const auto nose = [&](int j) {
    if (j < 1) return first_nose + (j - 1) * W;
    if (j > steps) return last_nose + (j - steps) * W;
    return stairs.edges()[static_cast<std::size_t>(j - 1)].x_nose;
  };
  const auto foothold = [&](std::size_t r, int j) {
    const double x = nose(j) + legs[r].offset;
    return Eigen::Vector3d(x, legs[r].y, stairs.HeightAt(x, legs[r].y));
  };
  // Leg r leaves step j when its hip passes nose(j) + W/2 + a cos^2(phi) - d sin(phi) (Figure 2(a)).
  const double speed = g.d_i / settings.swing_duration * cos_phi;  // hip, horizontally [m/s]
  const auto lift_x = [&](std::size_t r, int j) { return nose(j) + 0.5 * W + legs[r].offset * cos_phi * cos_phi - g.d * sin_phi; };
  // The hind hips start so that the first front leg to swing leaves the bottom landing (step 0)
  // after settle_s.
  const std::size_t first_front = switched ? 3 : 2;
  const double hind_x0 = lift_x(first_front, 0) - legs[first_front].hip_x - speed * settings.settle_s;
  const auto lift_time = [&](std::size_t r, int j) { return (lift_x(r, j) - hind_x0 - legs[r].hip_x) / speed; };

  std::array<int, 4> start{};
  for (std::size_t r = 0; r < 4; ++r) {
    int j = 0;
    while (lift_time(r, j - 1) >= 0.0) --j;
    while (lift_time(r, j) < 0.0) ++j;
    start[r] = j;
    if (!std::isfinite(foothold(r, j).z())) return PaperInfeasible(plan, "landing_before is too short for the robot's " + std::string(kPaperLegNames[r]) + " foot");
  }
  plan.initial_feet_W.resize(4);
  for (std::size_t r = 0; r < 4; ++r) plan.initial_feet_W[static_cast<std::size_t>(legs[r].robot_index)] = foothold(r, start[r]);
  // Climb until the hind feet stand on the top landing.
  const double end = std::max(lift_time(0, steps - 1), lift_time(1, steps - 1)) + settings.swing_duration;
  // The rising foot keeps its swing clearance from the riser, sphere included.
  const double approach_margin = settings.body.swing.clearance + robot.legs().front().foot_radius;
  for (std::size_t r = 0; r < 4; ++r) {
    for (int j = start[r]; lift_time(r, j) <= end; ++j) {
      Footstep step;
      step.leg = kPaperLegNames[r];
      step.t_liftoff = lift_time(r, j);
      step.t_touchdown = step.t_liftoff + settings.swing_duration;
      step.from_W = foothold(r, j);
      step.position_W = foothold(r, j + 1);
      if (!std::isfinite(step.position_W.z())) return PaperInfeasible(plan, "landing_after is too short for the robot's " + step.leg + " foot");
      step.stair_index = map.StairAt(step.position_W.head<2>());
      step.in_step_region = step.stair_index >= 0 && map.InStepRegion(step.stair_index, step.position_W.head<2>());
      step.swing_apex_z = SwingTrajectory(step.from_W, step.position_W, stairs, settings.body.swing).apex_z();
      step.swing_approach_share = ApproachShare(step.from_W, step.position_W, stairs, approach_margin);
      plan.footsteps.push_back(step);
    }
  }
  std::sort(plan.footsteps.begin(), plan.footsteps.end(),
            [](const Footstep& a, const Footstep& b) { return a.t_touchdown < b.t_touchdown; });
  plan.body = BodyPathForFootsteps(robot, plan.legs, plan.initial_feet_W, plan.footsteps, 0.0, settings.body, &stairs);
  return plan;
}

}  // namespace stairplan
