// The 2012 paper's crawl as a footstep source (stairplan/planning/step/paper_crawl.h): footholds at the
// paper's contact offsets, its swing order and its timing (5)-(7), on the robot of its dimensions.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "stairplan/kinematics/robot_kinematics.h"
#include "stairplan/planning/gait/crawl_stability.h"
#include "stairplan/pipeline/plan_pipeline.h"
#include "stairplan/planning/step/paper_crawl.h"
#include "stairplan/planning/swing_trajectory.h"
#include "stairplan/planning/validation/traversal_validator.h"
#include "sanitized.h"
#include "test_paths.h"

using namespace stairplan;

namespace {

// Three steps: two treads carry the periodic pattern; the plan's cost grows with the flight.
Staircase PaperFlight(double rise = 0.17, double run = 0.27) {
  StairSpec spec;
  spec.steps = 3;
  spec.rise = rise;
  spec.run = run;
  spec.nosing = 0.0;
  return Staircase(spec);
}

bool IsRightLeg(const std::string& leg) { return leg[0] == 'R'; }

// Where a hip stands, relative to the nose a leg climbs over, when that leg lifts off (Figure
// 2(a)): on the line d above the edges, on the bisector of its two contacts a behind their noses.
Eigen::Vector2d PaperHipFromNose(const GaitDesign& g, double a) {
  const double u = 0.5 * g.cl - a * std::cos(g.phi);
  return {-u * std::cos(g.phi) - g.d * std::sin(g.phi), -u * std::sin(g.phi) + g.d * std::cos(g.phi)};
}

// The climbing swings travel low to their riser, rise there and keep clear of it (the paper's
// swing, Footstep::swing_approach_share); returns how many swings climb.
int CheckClimbingSwings(const RobotModel& robot, const Staircase& stairs, const Plan& plan, const PaperCrawlSettings& settings) {
  const double radius = robot.legs().front().foot_radius;
  const double margin = settings.body.swing.clearance + radius;
  int climbs = 0;
  for (const Footstep& f : plan.footsteps) {
    CHECK(f.swing_approach_share >= 0.0);
    CHECK(f.swing_approach_share < 1.0);
    if (f.position_W.z() <= f.from_W.z() + 1e-6) continue;
    ++climbs;
    const SwingTrajectory swing(f.from_W, f.position_W, f.swing_apex_z, settings.body.swing, f.swing_approach_share);
    // The riser it climbs: the first edge ahead of the foothold it leaves.
    double riser = f.position_W.x();
    for (const StairEdge& e : stairs.edges()) {
      if (e.x_nose > f.from_W.x()) riser = std::min(riser, e.x_nose);
    }
    const Eigen::Vector3d top = swing.At(settings.body.swing.lift_fraction);
    CHECK(top.x() == Approx(riser - margin).margin(1e-9));
    CHECK(top.z() == Approx(f.swing_apex_z));
    // The foot's sphere keeps clear of the riser and its nose until it lowers onto the tread.
    for (int i = 0; i <= 100; ++i) {
      const double s = i / 100.0 * (1.0 - settings.body.swing.lower_fraction);
      const Eigen::Vector3d p = swing.At(s);
      if (p.x() + radius >= riser) CHECK(p.z() >= f.position_W.z() + settings.body.swing.clearance - 1e-9);
    }
  }
  return climbs;
}

// The COM's largest margin (negative: outside) to the support triangle through a swing of hind
// leg `r` (0 RH, 1 LH) in the paper's model (CrawlStabilityAt), over one cycle sampled as
// EvaluateCrawlStability samples it.
double PaperHindSwingBestMargin(const GaitDesignInput& in, const GaitDesign& g, CrawlCase arrangement, int r) {
  constexpr int kSamples = 7200;
  double best = -std::numeric_limits<double>::infinity();
  int in_swing = 0, most_in_air = 0;
  for (int k = 0; k < kSamples; ++k) {
    const CrawlInstant at = CrawlStabilityAt(in, g, arrangement, g.cl * (k + 0.5) / kSamples);
    most_in_air = std::max(most_in_air, at.legs_in_air);
    if (at.swing_leg != r) continue;
    ++in_swing;
    best = std::max(best, at.margin);
  }
  REQUIRE(most_in_air == 1);  // one leg in the air at a time
  REQUIRE(in_swing >= 200);  // the swing sampled at least as finely as a 200-step scan of it
  return best;
}

}  // namespace

TEST_CASE("paper crawl: footholds at a_min / a_max, the paper's order and timing", "[step][paper]") {
  const RobotModel robot = RobotModel::FromUrdfFile(testing::SourceDir() + "/data/robots/quattroped2012.urdf");
  REQUIRE(robot.legs().size() == 4);
  // The paper's dimensions: BL 44.4 cm between hips, BW 36 cm between feet, two-link legs that
  // reach l_max = 21 cm.
  for (const LegModel& leg : robot.legs()) {
    CHECK(std::abs(leg.hip_B.x()) == Approx(0.222).margin(1e-9));
    CHECK(std::abs(leg.foot_zero_B.y()) == Approx(0.18).margin(1e-9));
    CHECK(leg.joint_names.size() == 3);  // hip abduction, then the thigh and shank joints
    CHECK((leg.foot_zero_B - leg.hip_B).norm() > 0.21);
  }
  const Staircase stairs = PaperFlight();
  const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
  // Under the sanitizers case 1 only: each plan runs the body path.
  std::vector<CrawlCase> cases = {CrawlCase::kRightFirst};
  if (!testing::kSanitized) cases.push_back(CrawlCase::kFrontSwitched);
  for (CrawlCase arrangement : cases) {
    PaperCrawlSettings settings;
    settings.arrangement = arrangement;
    const bool switched = arrangement == CrawlCase::kFrontSwitched;
    INFO("case " << static_cast<int>(arrangement));
    const Plan plan = PlanPaperCrawl(robot, stairs, map, settings);
    REQUIRE(plan.status == PlanStatus::kOk);

    // The design it lays out: BL 0.444 from the URDF, the default d centring both offsets.
    GaitDesignInput in;
    in.body_length = 0.444;
    const double cl = std::hypot(0.27, 0.17), sin_phi = 0.17 / cl;
    in.hip_clearance = 0.5 * ((MinLegLength(0.27, 0.17) - 0.27) * sin_phi + std::sqrt(0.21 * 0.21 - 0.25 * cl * cl));
    const GaitDesign g = DesignGait(in);
    CHECK(g.a_min + g.a_max == Approx(0.27).margin(1e-9));

    int on_treads = 0;
    for (const Footstep& f : plan.footsteps) {
      CHECK(f.in_step_region);
      CHECK(f.t_touchdown - f.t_liftoff == Approx(settings.swing_duration).margin(1e-9));
      if (f.stair_index < 1 || f.stair_index >= stairs.steps()) continue;
      ++on_treads;
      const bool at_min = IsRightLeg(f.leg) != (switched && f.leg[1] == 'F');
      const double nose = stairs.edges()[static_cast<std::size_t>(f.stair_index - 1)].x_nose;
      CHECK(f.position_W.x() - nose == Approx(at_min ? g.a_min : g.a_max).margin(1e-9));
    }
    CHECK(on_treads >= 4 * (stairs.steps() - 1));
    CHECK(CheckClimbingSwings(robot, stairs, plan, settings) >= 4 * stairs.steps());

    std::vector<Footstep> by_liftoff = plan.footsteps;
    std::sort(by_liftoff.begin(), by_liftoff.end(), [](const Footstep& a, const Footstep& b) { return a.t_liftoff < b.t_liftoff; });
    // One leg in the air at a time (conditions (8) and (9) hold for this design).
    for (std::size_t i = 1; i < by_liftoff.size(); ++i) CHECK(by_liftoff[i].t_liftoff >= by_liftoff[i - 1].t_touchdown - 1e-9);
    // The swing sequence: HR, HL, FR, FL (case 1) or HR, HL, FL, FR (case 2), repeating.
    const std::string order = switched ? "RHLHLFRF" : "RHLHRFLF";
    const std::size_t first = order.find(by_liftoff.front().leg);
    REQUIRE(first != std::string::npos);
    for (std::size_t i = 0; i < by_liftoff.size(); ++i) {
      CHECK(by_liftoff[i].leg == order.substr((first + 2 * i) % 8, 2));
    }
    // Within a pair the second leg lifts D_s of hip travel after the first: D_s / D_i swings (eq.
    // (6): D_i = (1 - p) D_s), leaving the buffer p D_s; each leg lifts once per CL of hip travel.
    const double swing = settings.swing_duration;
    for (std::size_t i = 0; i + 1 < by_liftoff.size(); ++i) {
      const Footstep& a = by_liftoff[i];
      const Footstep& b = by_liftoff[i + 1];
      if (a.leg[1] != b.leg[1]) continue;  // not a pair
      CHECK(b.t_liftoff - a.t_liftoff == Approx(swing / (1.0 - 0.42)).epsilon(1e-9));
    }
    for (std::size_t i = 0; i + 4 < by_liftoff.size(); ++i) {
      CHECK(by_liftoff[i + 4].t_liftoff - by_liftoff[i].t_liftoff == Approx(swing * g.cl / g.d_i).epsilon(1e-9));
    }
    CHECK(plan.body.size() > 10);
  }
}

TEST_CASE("paper crawl: a design that fails on the stairs is a status, not a plan", "[step][paper]") {
  const RobotModel robot = RobotModel::FromUrdfFile(testing::SourceDir() + "/data/robots/quattroped2012.urdf");
  const Staircase stairs = PaperFlight();
  const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
  PaperCrawlSettings settings;
  settings.max_leg_length = 0.18;  // below l_min = 18.85 cm
  const Plan plan = PlanPaperCrawl(robot, stairs, map, settings);
  CHECK(plan.status == PlanStatus::kInfeasible);
  CHECK(plan.status_reason.find("(10)") != std::string::npos);
  settings.max_leg_length = -1.0;
  CHECK_THROWS_AS(PlanPaperCrawl(robot, stairs, map, settings), std::invalid_argument);
}

TEST_CASE("paper crawl on the paper's three stairs: no d lets both feet pass their noses and land in the step regions", "[step][paper]") {
  const RobotModel robot = RobotModel::FromUrdfFile(testing::SourceDir() + "/data/robots/quattroped2012.urdf");
  const RobotKinematics kinematics(robot);
  const LegKinematics& leg = kinematics.leg(0);
  const double lateral = leg.model().foot_zero_B.y() - leg.model().hip_B.y();  // the leg's plane beside its hip
  const PaperCrawlSettings settings;
  const PipelineOptions pipeline;  // the map `plan --planner paper` validates against
  // The foot's centre where it passes the nose: the swing's clearance from the riser and above
  // the tread, its sphere included.
  const double pass = settings.body.swing.clearance + leg.model().foot_radius;
  const auto hip_to_pass = [&](const GaitDesign& g, double a) {
    const Eigen::Vector2d hip = PaperHipFromNose(g, a);
    return std::sqrt(std::pow(-pass - hip.x(), 2) + std::pow(pass - hip.y(), 2) + lateral * lateral);
  };
  for (const auto& [run, rise] : {std::pair{0.27, 0.17}, std::pair{0.31, 0.175}, std::pair{0.28, 0.16}}) {
    INFO(run << " x " << rise);
    GaitDesignInput in;
    in.run = run;
    in.rise = rise;
    in.body_length = 0.444;
    const double cl = std::hypot(run, rise), sin_phi = rise / cl;
    // The controller's d (a_min + a_max = W): the left feet lift at l_max with their hips so near
    // the nose that the foot would pass closer to the hip than the folded leg reaches.
    in.hip_clearance = 0.5 * ((MinLegLength(run, rise) - run) * sin_phi + std::sqrt(0.21 * 0.21 - 0.25 * cl * cl));
    const GaitDesign centred = DesignGait(in);
    REQUIRE(centred.feasible);
    CHECK(hip_to_pass(centred, centred.a_max) < leg.reach().lo);
    // The paper's simulation's d = H / 2 leaves that foot room, but its right feet then stand so
    // near the nose that they are off the step regions.
    in.hip_clearance = 0.5 * rise;
    const GaitDesign paper = DesignGait(in);
    REQUIRE(paper.feasible);
    CHECK(hip_to_pass(paper, paper.a_max) > leg.reach().lo);
    const Staircase stairs = PaperFlight(rise, run);
    const ConstrainedMap map = BuildPipelineMap(robot, stairs, pipeline);
    const Eigen::Vector2d right_foot(stairs.edges()[0].x_nose + paper.a_min, leg.model().foot_zero_B.y());
    const int stair = map.StairAt(right_foot);
    REQUIRE(stair == 1);
    CHECK_FALSE(map.InStepRegion(stair, right_foot));
  }
}

TEST_CASE("the paper crawl's footstep sources are its two cases only", "[step][paper][pipeline]") {
  CHECK(IsPaperCrawl(FootstepSource::kPaperCrawl));
  CHECK(IsPaperCrawl(FootstepSource::kPaperCrawlAlternate));
  CHECK_FALSE(IsPaperCrawl(FootstepSource::kSelectedCrawl));
  CHECK_FALSE(IsPaperCrawl(FootstepSource::kStepPlanner));
}

TEST_CASE("the pipeline runs the paper crawl at the paper's posture, validated, the alignment stance made for it", "[step][paper][pipeline]") {
  const RobotModel robot = RobotModel::FromUrdfFile(testing::SourceDir() + "/data/robots/quattroped2012.urdf");
  const Staircase stairs = PaperFlight();
  CHECK(ParseFootstepSource("paper") == FootstepSource::kPaperCrawl);
  CHECK(ParseFootstepSource("paper-alt") == FootstepSource::kPaperCrawlAlternate);
  PipelineOptions options;
  options.footsteps = FootstepSource::kPaperCrawlAlternate;
  const PipelineResult r = RunPipeline(robot, stairs, options);
  // The same plan as the paper's crawl on the map made for its posture (hips at 0.8 of the reach,
  // not the pipeline's 0.6), validated.
  PaperCrawlSettings paper;
  paper.arrangement = CrawlCase::kFrontSwitched;
  PipelineOptions at_posture;
  at_posture.crawl.body.hip_height_fraction = paper.body.hip_height_fraction;
  REQUIRE(at_posture.crawl.body.hip_height_fraction != PipelineOptions{}.crawl.body.hip_height_fraction);
  const ConstrainedMap map = BuildPipelineMap(robot, stairs, at_posture);
  const Plan direct = PlanPaperCrawl(robot, stairs, map, paper);
  REQUIRE(direct.status == PlanStatus::kOk);
  REQUIRE(r.plan.status == PlanStatus::kOk);
  CHECK(r.plan.gait == Gait::kPaperCrawlAlternate);
  CHECK(r.plan.hip_height_fraction == paper.body.hip_height_fraction);
  REQUIRE(r.plan.footsteps.size() == direct.footsteps.size());
  for (std::size_t i = 0; i < direct.footsteps.size(); ++i) {
    CHECK(r.plan.footsteps[i].leg == direct.footsteps[i].leg);
    CHECK(r.plan.footsteps[i].t_liftoff == direct.footsteps[i].t_liftoff);
    CHECK((r.plan.footsteps[i].position_W - direct.footsteps[i].position_W).norm() == 0.0);
  }
  REQUIRE(r.plan.body.size() == direct.body.size());
  CHECK(r.plan.body.back().x == direct.body.back().x);
  CHECK(r.validated);
  // One attempt: the posture retries do not apply to the paper's posture.
  CHECK(std::count_if(r.plan.timing_us.begin(), r.plan.timing_us.end(), [](const auto& t) { return t.first == "plan"; }) == 1);
  // The alignment stance at the paper's posture: standing taller, it differs from the default one.
  const RobotKinematics kinematics(robot);
  const AlignmentStance expected = ComputeAlignmentStance(kinematics, stairs, map, Facing::kForward, paper.body.hip_height_fraction,
                                                          options.crawl.start_gap);
  const AlignmentStance& a = r.approach.alignment;
  REQUIRE(a.found);
  REQUIRE(a.feet.size() == expected.feet.size());
  CHECK((a.position - expected.position).norm() == 0.0);
  for (std::size_t i = 0; i < a.feet.size(); ++i) CHECK((a.feet[i] - expected.feet[i]).norm() == 0.0);
  const PipelineOptions defaults;
  const AlignmentStance at_default =
      ComputeAlignmentStance(kinematics, stairs, BuildPipelineMap(robot, stairs, defaults), Facing::kForward,
                             defaults.crawl.body.hip_height_fraction, defaults.crawl.start_gap);
  CHECK((a.position - at_default.position).norm() > 1e-4);
  CHECK(r.approach.stair_mode.engaged);
  // The paper's crawl has its own body path, whatever the body source (the body optimisation by
  // default); `plan --planner paper --body qp` is refused.
  CHECK(options.body == BodySource::kRecedingHorizonQp);
  CHECK(r.plan.body_planner == BodyPlannerKind::kQuasiStaticPath);
}

// Why no plan with the paper's design validates on its robot, from the paper's own geometry:
// conditions (8)-(10) and (13) hold on all three stairs, but the paper's body (hips on the line d
// above the edges, pitched at phi, no roll) keeps the COM outside the support triangle through
// the left hind swing by centimetres (the paper's own stability analysis), and the sideways sway
// that would bring it inside by the validator's margin cannot be carried by the swinging foot.
TEST_CASE("paper crawl on the paper's three stairs: its conditions hold but its body cannot sway the COM inside", "[step][paper]") {
  const RobotModel robot = RobotModel::FromUrdfFile(testing::SourceDir() + "/data/robots/quattroped2012.urdf");
  const RobotKinematics kinematics(robot);
  const LegModel& leg = robot.legs().front();
  const double plane = std::abs(leg.foot_zero_B.y() - leg.hip_B.y());  // leg plane beside the abduction axis
  const double abduction = std::min(-leg.limits[0].lower, leg.limits[0].upper);
  CHECK(abduction == Approx(0.5));
  const ValidationSettings validation;
  const PipelineOptions pipeline;
  // Over the nose the foot's centre stays at least its radius from the nose's corner (the
  // validator wants 5 mm more); any path from the lower tread to the upper one crosses the normal
  // to the edge line through the nose, so it does so at least `corner` above the edge line. The
  // hip line is d above it and the body parallel to it: there the foot is at most d - corner
  // below its hip.
  const double corner = leg.foot_radius;
  // How far outward of its plane the abduction puts a foot `depth` below (or above) its hip.
  const auto outward = [&](double depth) {
    const double q = std::clamp(std::atan2(depth, plane), -abduction, abduction);
    return plane * std::cos(q) + depth * std::sin(q) - plane;
  };
  // How far above its hip a foot must be to sit `out` outward of its plane.
  const auto above_hip = [&](double out) { return (out + plane * (1.0 - std::cos(abduction))) / std::sin(abduction); };
  for (const auto& [run, rise] : {std::pair{0.27, 0.17}, std::pair{0.31, 0.175}, std::pair{0.28, 0.16}}) {
    INFO(run << " x " << rise);
    const Staircase stairs = PaperFlight(rise, run);
    const ConstrainedMap map = BuildPipelineMap(robot, stairs, pipeline);
    const double nose = stairs.edges()[0].x_nose;
    double band = 0.0;  // the step region starts this far behind the nose
    while (!map.InStepRegion(1, {nose + band, leg.foot_zero_B.y()})) band += 0.001;
    CHECK(band == Approx(0.05).margin(0.002));
    GaitDesignInput in;
    in.run = run;
    in.rise = rise;
    in.body_length = 0.444;
    in.body_width = 0.36;
    // The largest d keeps a_min (eq. (4)) on the step region: every d the controller could take.
    // (8)-(10) do not depend on d and the offsets move monotonically with it, so its two ends
    // stand for the whole range; the COM's margin does not depend on it at all.
    const double d_max = (MinLegLength(run, rise) - band) * std::sin(std::atan2(rise, run));
    const double below_most = outward(d_max - corner);  // the foot below its hip, as the paper's leg swings
    for (const double d : {0.01, d_max}) {
      in.hip_clearance = d;
      INFO("d " << d);
      const GaitDesign g = DesignGait(in);
      CHECK(g.feasible);  // (8), (9), (10) = (13), and both offsets on the tread
      for (const CrawlCase arrangement : {CrawlCase::kRightFirst, CrawlCase::kFrontSwitched}) {
        INFO("case " << static_cast<int>(arrangement));
        const double least_outside = -PaperHindSwingBestMargin(in, g, arrangement, 1);
        CHECK(least_outside > 0.02);
        // A sideways sway of y moves the COM at most y toward the inside of the diagonal it
        // crosses; the swinging left hind foot must follow it outward as it passes the nose.
        const double sway = least_outside + validation.min_stability_margin;
        CHECK(sway > below_most + 0.01);
        // Unless it passes the nose raised 8 cm or more above its hip (on 31 x 17.5 beyond the
        // leg's reach), which the paper's leg, rotating about its hip, never is.
        CHECK(above_hip(sway) > 0.08);
        if (run > 0.3) CHECK(above_hip(sway) > kinematics.leg(0).reach().hi);
      }
    }
  }
}
