#include "perception/footfall_scenes.h"

#include <cmath>

namespace stairplan::testing {
namespace {

PlacedFlight Flight(int steps, double rise, double run, TravelDirection direction, const Eigen::Vector3d& origin, double yaw) {
  StairSpec spec;
  spec.steps = steps;
  spec.rise = rise;
  spec.run = run;
  spec.width = 1.2;
  spec.direction = direction;
  PlacedFlight flight;
  flight.stairs = Staircase(spec);
  flight.origin_W = origin;
  flight.yaw = yaw;
  return flight;
}

}  // namespace

std::vector<PlacedFlight> TwoUpTwoDownLoop() {
  // Each flight starts where the previous one's landing ends, at the same height.
  return {Flight(6, 0.17, 0.28, TravelDirection::kUp, {0.0, 0.0, 0.0}, 0.0),
          Flight(5, 0.15, 0.30, TravelDirection::kUp, {3.6, 1.5, 1.02}, 0.5 * M_PI),
          Flight(6, 0.16, 0.26, TravelDirection::kDown, {2.0, 4.5, 1.77 - 0.96}, M_PI),
          Flight(5, 0.162, 0.29, TravelDirection::kDown, {-1.0, 3.6, 0.0}, -0.5 * M_PI)};
}

}  // namespace stairplan::testing
