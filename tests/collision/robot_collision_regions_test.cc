// Robot-aware collision regions: where stairbot's leg would touch the riser or nosing, and how
// that depends on the direction of travel and the way the robot faces.
#include <catch2/catch.hpp>

#include <algorithm>
#include <optional>
#include <string>

#include "stairplan/collision/robot_collision_regions.h"
#include "stairplan/kinematics/builtin_robot.h"
#include "test_paths.h"

using namespace stairplan;

namespace {

struct RegionsFixture {
  RobotKinematics kinematics{BuiltinRobot()};
  RobotCollisionModel robot{kinematics};
};

bool CoversMiddle(const RobotRegion& r, const Staircase& stairs) {
  const StairSurface& s = stairs.surface(r.stair_index);
  const double middle = 0.5 * (s.x_begin + s.x_end);
  return r.x0 < middle && r.x1 > middle;
}

// A robot of ../shared/data/robots by name; nothing (with a WARN) when ../shared is absent.
std::optional<RobotModel> RegionsRobot(const std::string& name) {
  const std::string path = testing::SharedPath("data/robots/" + name + ".urdf");
  if (path.empty()) {
    WARN("shared robots skipped: ../shared not found");
    return std::nullopt;
  }
  return RobotModel::FromUrdfFile(path);
}

}  // namespace

TEST_CASE("ascending forwards, only the foot's own width before each riser is a region", "[robot_regions]") {
  RegionsFixture f;
  const Staircase stairs{StairSpec{}};
  const auto regions = FindRobotCollisionRegions(f.kinematics, f.robot, stairs, Facing::kForward);
  for (int k = 1; k < stairs.steps(); ++k) {
    INFO("tread " << k);
    const StairSurface& tread = stairs.surface(k);
    const StairEdge& next = stairs.edges()[static_cast<std::size_t>(k)];  // the riser ahead of tread k
    int found = 0;
    for (const RobotRegion& r : regions) {
      if (r.stair_index != k) continue;
      ++found;
      CHECK(r.x1 == Approx(tread.x_end));  // up to the nosing above
      // Knees bend backwards, so the shank leans away from the riser: only the foot sphere
      // (radius 0.025) reaches it, 2 cm under the nosing.
      CHECK(r.x0 >= next.x_riser - 0.025 - 0.01);
      CHECK(r.part == StairPart::kRiser);
    }
    CHECK(found == 1);
  }
  for (const RobotRegion& r : regions) CHECK_FALSE(CoversMiddle(r, stairs));
}

TEST_CASE("ascending facing backwards, the forward-bent knees reach the nosing: wider regions", "[robot_regions]") {
  RegionsFixture f;
  const Staircase stairs{StairSpec{}};
  const auto regions = FindRobotCollisionRegions(f.kinematics, f.robot, stairs, Facing::kBackward);
  int wide = 0;
  for (const RobotRegion& r : regions) {
    CHECK_FALSE(CoversMiddle(r, stairs));
    if (r.stair_index >= 1 && r.stair_index < stairs.steps()) {
      CHECK(r.part == StairPart::kNosing);
      CHECK(r.x1 - r.x0 > 0.05);
      wide += 1;
    }
  }
  CHECK(wide == stairs.steps() - 1);
}

TEST_CASE("descending forwards, the shins meet the step behind: regions at the back of each tread", "[robot_regions]") {
  RegionsFixture f;
  StairSpec spec;
  spec.direction = TravelDirection::kDown;
  const Staircase stairs{spec};
  const auto regions = FindRobotCollisionRegions(f.kinematics, f.robot, stairs, Facing::kForward);
  REQUIRE(regions.size() >= static_cast<std::size_t>(stairs.steps() - 1));
  for (const RobotRegion& r : regions) {
    CHECK_FALSE(CoversMiddle(r, stairs));
    CHECK(r.x0 == Approx(stairs.surface(r.stair_index).x_begin));
    CHECK(r.x1 - r.x0 > 0.05);
  }
  RobotRegionSettings bad;
  bad.sample_step = 0.0;
  CHECK_THROWS_WITH(bad.Validate(), Catch::Contains("sample_step"));
}

TEST_CASE("robot regions merge into the constrained map and trim its step regions", "[robot_regions]") {
  RegionsFixture f;
  const Staircase stairs{StairSpec{}};
  ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kBackward);
  const ConstrainedMap analytic = map;
  AddRobotCollisionRegions(f.kinematics, f.robot, stairs, map);
  const auto regions = FindRobotCollisionRegions(f.kinematics, f.robot, stairs, Facing::kBackward);
  int robot_regions = 0;
  for (int k = 0; k < map.size(); ++k) {
    const StairRegions& s = map.stair(k);
    for (const CollisionRegion& c : s.collision_regions) robot_regions += c.kind == RegionKind::kRobot;
    // The analytic regions are kept, the robot's come on top.
    CHECK(s.collision_regions.size() >= analytic.stair(k).collision_regions.size());
    // No step region overlaps a robot region.
    if (s.step_region.empty()) continue;
    for (const RobotRegion& r : regions) {
      if (r.stair_index != k) continue;
      double lo = 1e9, hi = -1e9;
      for (const auto& v : s.step_region.vertices) {
        lo = std::min(lo, v.x());
        hi = std::max(hi, v.x());
      }
      CHECK((hi <= r.x0 + 1e-9 || lo >= r.x1 - 1e-9));
    }
  }
  CHECK(robot_regions == static_cast<int>(regions.size()));
}

TEST_CASE("ANYmal C ascending: its forward-bent hind knees reach the nosings", "[robot_regions]") {
  const std::optional<RobotModel> model = RegionsRobot("anymal_c");
  if (!model) return;
  const RobotKinematics kinematics(*model);
  const RobotCollisionModel robot(kinematics);
  const Staircase stairs{StairSpec{}};
  const auto regions = FindRobotCollisionRegions(kinematics, robot, stairs, Facing::kForward);
  int treads = 0;
  for (const RobotRegion& r : regions) {
    CHECK_FALSE(CoversMiddle(r, stairs));
    if (r.stair_index < 1 || r.stair_index >= stairs.steps()) continue;
    ++treads;
    CHECK(r.part == StairPart::kNosing);
    CHECK(kinematics.leg(r.leg).model().hip_B.x() < 0.0);  // a hind leg
    CHECK(r.x1 - r.x0 > 0.05);
  }
  CHECK(treads == stairs.steps() - 1);
}

TEST_CASE("Unitree Go2 descending at the pipeline's posture: landings free, a strip of each tread left", "[robot_regions]") {
  const std::optional<RobotModel> model = RegionsRobot("unitree_go2");
  if (!model) return;
  const RobotKinematics kinematics(*model);
  const RobotCollisionModel robot(kinematics);
  StairSpec spec;
  spec.direction = TravelDirection::kDown;
  const Staircase stairs{spec};
  RobotRegionSettings settings;
  settings.hip_height_fraction = 0.6;  // PipelineOptions' crawl body
  // Go2's foot sphere sits 2 mm off its link's origin: placed with the body's orientation instead
  // of the foot's, the sphere went 2.4 mm into the tread and every landing was one region.
  const auto regions = FindRobotCollisionRegions(kinematics, robot, stairs, Facing::kForward, settings);
  for (const RobotRegion& r : regions) {
    INFO("surface " << r.stair_index << " [" << r.x0 << ", " << r.x1 << "] " << ToString(r.part));
    CHECK(r.stair_index != 0);  // the top landing: nothing behind it to meet
    // The shins meet the step behind: regions start at the back of the tread (the bottom landing's
    // too), and the front of it stays a place to step.
    CHECK(r.x0 == Approx(stairs.surface(r.stair_index).x_begin));
    CHECK(r.x1 < stairs.surface(r.stair_index).x_end - 0.05);
  }
  CHECK(regions.size() == static_cast<std::size_t>(stairs.steps()));  // one behind each riser
}
