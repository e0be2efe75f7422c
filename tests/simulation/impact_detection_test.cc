// The impact classifiers: a swing foot's external force by direction and swing stage, a leg link
// on the stairs by where it is against its hip, a strike on the contralateral leg by which side the
// swing foot is on.
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>

#include "stairplan/simulation/impact_detection.h"

using namespace stairplan;

TEST_CASE("a swing foot's external force: touchdown, trip or scuff by direction and phase", "[impact]") {
  const Eigen::Vector3d forward(1.0, 0.0, 0.0);
  const double threshold = 10.0, touchdown = 0.5, scuff = 0.12;
  const auto kind = [&](const Eigen::Vector3d& f, double phase) {
    return ClassifySwingFootForce(f, forward, phase, touchdown, threshold, scuff);
  };
  CHECK_FALSE(kind({0.0, 0.0, 9.0}, 0.9).has_value());                    // below the threshold
  CHECK(kind({0.0, 0.0, 50.0}, 0.9) == ImpactKind::kTouchdown);           // the tread pushes up late in swing
  CHECK(kind({-5.0, 0.0, 50.0}, 0.6) == ImpactKind::kTouchdown);
  CHECK(kind({-80.0, 0.0, 20.0}, 0.6) == ImpactKind::kTrip);              // a riser pushes the foot back
  CHECK(kind({-80.0, 0.0, 20.0}, 0.3) == ImpactKind::kTrip);
  CHECK(kind({0.0, 0.0, 50.0}, 0.3) == ImpactKind::kTrip);                // something under the foot before it may land
  CHECK(kind({0.0, 0.0, 50.0}, 0.05) == ImpactKind::kLiftoffScuff);       // the tread it leaves
  // Direction is the swing's: the same force on a foot swinging backwards pushes it along.
  CHECK(ClassifySwingFootForce({-80.0, 0.0, 90.0}, -forward, 0.6, touchdown, threshold, scuff) == ImpactKind::kTouchdown);
}

TEST_CASE("a leg link on the stairs: behind its hip is behind the body, ahead is a glancing knee", "[impact]") {
  const Eigen::Vector3d hip(1.0, 0.0, 0.5);
  CHECK(ClassifyLegLinkOnStairs({0.9, 0.1, 0.3}, hip, 0.0) == ImpactKind::kKneeBehindBody);
  CHECK(ClassifyLegLinkOnStairs({1.1, 0.1, 0.3}, hip, 0.0) == ImpactKind::kKneeGlancingTerrain);
  // Facing -x (descending backwards), the same points swap.
  CHECK(ClassifyLegLinkOnStairs({0.9, 0.1, 0.3}, hip, M_PI) == ImpactKind::kKneeGlancingTerrain);
  CHECK(ClassifyLegLinkOnStairs({1.1, 0.1, 0.3}, hip, M_PI) == ImpactKind::kKneeBehindBody);
}

TEST_CASE("a swing leg on its contralateral leg: crossing when the foot is past it", "[impact]") {
  const Eigen::Vector3d right_foot(0.0, -0.15, 0.0);
  CHECK(ClassifyContralateral({0.0, -0.05, 0.1}, right_foot, true, 0.0) == ImpactKind::kContralateralStrike);
  CHECK(ClassifyContralateral({0.0, -0.20, 0.1}, right_foot, true, 0.0) == ImpactKind::kContralateralCrossing);
  const Eigen::Vector3d left_foot(0.0, 0.15, 0.0);
  CHECK(ClassifyContralateral({0.0, 0.05, 0.1}, left_foot, false, 0.0) == ImpactKind::kContralateralStrike);
  CHECK(ClassifyContralateral({0.0, 0.20, 0.1}, left_foot, false, 0.0) == ImpactKind::kContralateralCrossing);
  // Heading +y: the body's left is -x.
  CHECK(ClassifyContralateral({0.2, 0.0, 0.1}, {0.15, 0.0, 0.0}, true, 0.5 * M_PI) == ImpactKind::kContralateralCrossing);
}

TEST_CASE("impact detection settings name the offending field", "[impact]") {
  ImpactDetectionSettings s;
  s.Validate();
  s.force_threshold = 0.0;
  CHECK_THROWS_WITH(s.Validate(), Catch::Contains("impact.force_threshold"));
  s = ImpactDetectionSettings{};
  s.retract_distance = std::nan("");
  CHECK_THROWS_WITH(s.Validate(), Catch::Contains("impact.retract_distance"));
}
