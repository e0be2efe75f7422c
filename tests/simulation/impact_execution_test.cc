// Impacts detected and answered while MuJoCo executes a plan (issue #26): a crawl planned with a
// low swing (its feet clear the model's nosings by 1 cm) on stairs whose second riser is 2 cm
// higher than the model stubs its toes there.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/pipeline/plan_pipeline.h"
#include "stairplan/simulation/impact_detection.h"
#include "stairplan/simulation/plan_executor.h"
#include "stairplan/simulation/sim_outcome_json.h"
#include "leg_row_pipeline.h"

using namespace stairplan;

namespace {

struct StubbedToeScene {
  StairSpec model;
  Plan plan;
  Staircase truth{StairSpec{}};
};

// Two steps: the toe stub is at the second riser, the landing after it is the goal.
const StubbedToeScene& StubbedToe() {
  static const StubbedToeScene scene = [] {
    StubbedToeScene s;
    s.model.steps = 2;
    PipelineOptions options;
    options.crawl.shift_duration = 0.6;
    options.crawl.swing.clearance = 0.01;
    options.crawl.swing.min_lift = 0.01;
    s.plan = RunPipeline(BuiltinRobot(), Staircase(s.model), options).plan;
    StairSpec truth = s.model;
    truth.rises = {s.model.rise, s.model.rise + 0.02};
    s.truth = Staircase(truth);
    return s;
  }();
  return scene;
}

// The stubbed-toe run with the default detection (torque residual) and responses; both tests read it.
const SimulationOutcome& AnsweredStub() {
  static const SimulationOutcome outcome = Simulate(BuiltinRobot(), StubbedToe().truth, StubbedToe().plan, SimSettings{});
  return outcome;
}

std::string ImpactLog(const SimulationOutcome& o) {
  std::string out = std::string(ToString(o.status)) + " / " + o.FirstCause() + "\n";
  for (const ImpactRecord& e : o.impacts) {
    out += "  t=" + std::to_string(e.t) + " contact " + std::to_string(e.t_contact) + " " + e.leg + " " + ToString(e.kind) +
           " -> " + ToString(e.response) + " (" + ToString(e.source) + ") phase " + std::to_string(e.swing_phase) + "\n";
  }
  return out;
}

std::vector<std::pair<std::string, double>> Trips(const SimulationOutcome& o) {
  std::vector<std::pair<std::string, double>> list;
  for (const ImpactRecord& e : o.impacts) {
    if (e.kind == ImpactKind::kTrip) list.emplace_back(e.leg, e.t);
  }
  return list;
}

}  // namespace

TEST_CASE("a toe stubbed on a riser 2 cm higher than the model: the torque residual finds the trip, the foot re-lifts, "
          "the flight completes, without responses the robot falls",
          "[simulation][impact]") {
  const StubbedToeScene& scene = StubbedToe();
  const RobotModel& robot = BuiltinRobot();
  REQUIRE(scene.plan.status == PlanStatus::kOk);
  SimSettings settings;
  REQUIRE(settings.impact.source == ImpactSource::kTorqueResidual);
  // On the stairs it was planned for, the low swing clears: no trip.
  const SimulationOutcome nominal = Simulate(robot, Staircase(scene.model), scene.plan, settings);
  INFO("nominal: " << ImpactLog(nominal));
  CHECK(nominal.Passed());
  CHECK(Trips(nominal).empty());

  const SimulationOutcome& answered = AnsweredStub();
  INFO("with responses: " << ImpactLog(answered));
  CHECK(answered.status == SimStatus::kSuccess);
  CHECK(answered.Passed());  // every foot in its step region, no other link on the stairs
  CHECK(answered.landings.size() == scene.plan.footsteps.size());
  for (const ImpactRecord& e : answered.impacts) {
    if (e.kind != ImpactKind::kTrip) continue;
    INFO(e.leg << " tripped at t=" << e.t);
    CHECK(e.source == ImpactSource::kTorqueResidual);
    CHECK(e.response == ResponseKind::kElevateFoot);
    // Found from the joint torques within 30 ms of the contact MuJoCo reports.
    REQUIRE(e.t_contact >= 0.0);
    CHECK(e.t >= e.t_contact);
    CHECK(e.t - e.t_contact <= 0.030);
  }
  CHECK(Trips(answered).size() >= 2);  // at least both front feet at the raised riser

  SimSettings no_responses = settings;
  no_responses.impact.respond = false;
  const SimulationOutcome unanswered = Simulate(robot, scene.truth, scene.plan, no_responses);
  INFO("without responses: " << ImpactLog(unanswered));
  CHECK_FALSE(unanswered.Passed());
  CHECK_FALSE(Trips(unanswered).empty());

  // The event log is in the outcome JSON: time, leg, kind and response.
  const nlohmann::json j = SimulationToJson(answered);
  REQUIRE(j["impacts"].size() == answered.impacts.size());
  const auto trip = std::find_if(j["impacts"].begin(), j["impacts"].end(), [](const nlohmann::json& e) { return e["kind"] == "trip"; });
  REQUIRE(trip != j["impacts"].end());
  CHECK((*trip)["response"] == "elevate_foot");
  CHECK((*trip)["source"] == "torque_residual");
  CHECK((*trip)["leg"].get<std::string>().size() == 2u);
  CHECK((*trip)["t"].get<double>() > 0.0);
}

TEST_CASE("MuJoCo's contact list finds the same trips as the torque residual", "[simulation][impact]") {
  const StubbedToeScene& scene = StubbedToe();
  SimSettings contacts;
  contacts.impact.source = ImpactSource::kContacts;
  const SimulationOutcome o = Simulate(BuiltinRobot(), scene.truth, scene.plan, contacts);
  INFO(ImpactLog(o));
  CHECK(o.Passed());
  const auto from_contacts = Trips(o), from_residual = Trips(AnsweredStub());
  REQUIRE(from_contacts.size() == from_residual.size());
  for (std::size_t k = 0; k < from_contacts.size(); ++k) {
    CHECK(from_contacts[k].first == from_residual[k].first);
    CHECK(std::abs(from_contacts[k].second - from_residual[k].second) <= 0.005);
  }
}



// Seed 000 [0058] and [0068]: a body carried too low drives knees into the stairs. 6 cm low, the
// front shank glances a nosing as it swings up the flight: no reaction. 14 cm low, the first hind
// swing's knee, behind its hip, meets the riser: the knee moves forward (the body still ends on the
// stairs: no response saves a plan that puts the body there).
TEST_CASE("knees driven into the stairs are detected, classified and answered, the log names time, leg, kind and response",
          "[simulation][impact]") {
  const RobotModel& robot = BuiltinRobot();
  StairSpec spec;
  spec.steps = 2;
  // The quasi-static path's plan, whose lowered body grazes a nosing with a shank before any knee
  // falls behind it: on the body optimisation's the front knee is judged behind the body first.
  PipelineOptions options = testing::PathBaselinePipeline();
  options.crawl.shift_duration = 0.6;
  const Plan nominal = RunPipeline(robot, Staircase(spec), options).plan;
  const auto lowered = [&](double dz) {
    Plan plan = nominal;
    for (BodyState& b : plan.body) b.z -= dz;
    return plan;
  };
  const auto first_of = [](const SimulationOutcome& o, ImpactKind kind) {
    return std::find_if(o.impacts.begin(), o.impacts.end(), [&](const ImpactRecord& e) { return e.kind == kind; });
  };

  SimSettings contacts;
  contacts.impact.source = ImpactSource::kContacts;
  const SimulationOutcome glancing = Simulate(robot, Staircase(spec), lowered(0.06), contacts);
  INFO("6 cm low: " << ImpactLog(glancing));
  const auto knee = first_of(glancing, ImpactKind::kKneeGlancingTerrain);
  REQUIRE(knee != glancing.impacts.end());
  CHECK(knee->response == ResponseKind::kProceed);
  CHECK(knee->link.find("shank") != std::string::npos);
  CHECK(knee->leg.size() == 2u);
  // The contact the log names is the one the outcome lists on a nosing.
  const auto shank = std::find_if(glancing.other_contacts.begin(), glancing.other_contacts.end(),
                                  [&](const LinkContact& c) { return c.link == knee->link; });
  REQUIRE(shank != glancing.other_contacts.end());
  CHECK(shank->stair_geom.find("nosing") != std::string::npos);
  CHECK(knee->t == Approx(shank->t_first).margin(1e-9));

  for (const ImpactSource source : {ImpactSource::kContacts, ImpactSource::kTorqueResidual}) {
    INFO(ToString(source));
    SimSettings settings;
    settings.impact.source = source;
    const SimulationOutcome low = Simulate(robot, Staircase(spec), lowered(0.14), settings);
    INFO("14 cm low: " << ImpactLog(low));
    const auto behind = first_of(low, ImpactKind::kKneeBehindBody);
    REQUIRE(behind != low.impacts.end());
    CHECK(behind->response == ResponseKind::kMoveKneeForward);
    CHECK(behind->leg[1] == 'H');
    // Found at the step MuJoCo first shows the shank on the stairs, torques or contacts alike.
    const auto hind_shank = std::find_if(low.other_contacts.begin(), low.other_contacts.end(),
                                         [&](const LinkContact& c) { return c.link == behind->leg + "_shank"; });
    REQUIRE(hind_shank != low.other_contacts.end());
    CHECK(behind->t - hind_shank->t_first <= 0.030);
    CHECK(behind->t >= hind_shank->t_first - 1e-9);
  }
}
