// The success-region summary on hand-made grids: connected areas (rise and run neighbours only)
// and the points that break "steeper stairs fail first", each with a steeper valid witness.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "stairplan/sweep/sweep_region.h"

using namespace stairplan;

namespace {

// A grid from a picture: row 0 is the lowest rise, column 0 the shortest run; '#' valid,
// '.' invalid.
std::vector<SweepRow> Grid(const std::vector<std::string>& picture, TravelDirection direction = TravelDirection::kUp,
                           int first_index = 0) {
  std::vector<SweepRow> rows;
  for (std::size_t i = 0; i < picture.size(); ++i) {
    for (std::size_t j = 0; j < picture[i].size(); ++j) {
      SweepRow r;
      r.point.index = first_index + static_cast<int>(i * picture[i].size() + j);
      r.point.direction = direction;
      r.point.rise = 0.10 + 0.01 * static_cast<double>(i);
      r.point.run = 0.20 + 0.01 * static_cast<double>(j);
      r.status = picture[i][j] == '#' ? "valid" : "invalid";
      r.reason = r.status == "valid" ? "" : "joint_limits RF";
      rows.push_back(r);
    }
  }
  return rows;
}

SweepRegion Only(const std::vector<SweepRow>& rows) {
  const std::vector<SweepRegion> regions = AnalyseSweepRegions(rows);
  REQUIRE(regions.size() == 1);
  return regions.front();
}

}  // namespace

TEST_CASE("a staircase-shaped success region is connected and steeper stairs fail first", "[sweep]") {
  // Lowest rise first: the steep corner (high rise, short run) fails.
  const SweepRegion r = Only(Grid({"####", "####", ".###", "..##"}));
  CHECK(r.points == 16);
  CHECK(r.valid == 13);
  CHECK(r.areas == 1);
  CHECK(r.Connected());
  CHECK(r.SteeperFailFirst());
  CHECK_THAT(SweepRegionsToText({r}), Catch::Contains("13/16 valid; one connected area; steeper stairs fail first: yes"));
}

TEST_CASE("a failure below or beside a valid steeper point breaks monotonicity, with a witness", "[sweep]") {
  // (rise 0.10, run 0.23) fails although the shorter run beside it is valid; (0.11, 0.22) fails
  // below and beside valid points; the failing corner (0.12, 0.20) has nothing steeper.
  const SweepRegion r = Only(Grid({"###.", "##.#", ".###"}));
  CHECK(r.areas == 1);
  REQUIRE(r.breaks.size() == 2);
  CHECK(r.breaks[0].failed.point.rise == Approx(0.10));
  CHECK(r.breaks[0].failed.point.run == Approx(0.23));
  CHECK(r.breaks[0].steeper_valid.rise == Approx(0.10));  // the nearest: one run shorter
  CHECK(r.breaks[0].steeper_valid.run == Approx(0.22));
  CHECK(r.breaks[1].failed.point.rise == Approx(0.11));
  CHECK(r.breaks[1].failed.point.run == Approx(0.22));
  CHECK(r.breaks[1].steeper_valid.rise >= r.breaks[1].failed.point.rise);
  CHECK(r.breaks[1].steeper_valid.run <= r.breaks[1].failed.point.run);
  const std::string text = SweepRegionsToText({r});
  CHECK_THAT(text, Catch::Contains("2 points break it"));
  CHECK_THAT(text, Catch::Contains("rise 0.11 run 0.22: invalid (joint_limits RF), but rise"));
}

TEST_CASE("valid points touching only diagonally are separate areas", "[sweep]") {
  const SweepRegion r = Only(Grid({"#.", ".#"}));
  CHECK(r.areas == 2);
  CHECK_FALSE(r.Connected());
  CHECK_THAT(SweepRegionsToText({r}), Catch::Contains("2 separate areas"));
  CHECK(Only(Grid({"..", ".."})).areas == 0);
  CHECK_THAT(SweepRegionsToText({Only(Grid({"..", ".."}))}), Catch::Contains("no valid point"));
}

TEST_CASE("a failed column splits the region and each direction is its own region", "[sweep]") {
  CHECK(Only(Grid({"#.#", "#.#"})).areas == 2);
  std::vector<SweepRow> rows = Grid({"##", ".#"});
  const std::vector<SweepRow> down = Grid({".#", "##"}, TravelDirection::kDown, 4);
  rows.insert(rows.end(), down.begin(), down.end());
  const std::vector<SweepRegion> regions = AnalyseSweepRegions(rows);
  REQUIRE(regions.size() == 2);
  CHECK(regions[0].direction == TravelDirection::kUp);
  CHECK(regions[0].SteeperFailFirst());
  CHECK(regions[1].direction == TravelDirection::kDown);
  REQUIRE(regions[1].breaks.size() == 1);  // (0.10, 0.20) fails below the valid (0.11, 0.20)
  CHECK(regions[1].breaks[0].failed.point.index == 4);
}
