// Sweep grids: axis parsing, the fixed point order, shards that partition the points, merging.
#include <catch2/catch.hpp>

#include <set>
#include <tuple>

#include "stairplan/geometry/field_error.h"
#include "stairplan/sweep/sweep_merge.h"
#include "stairplan/sweep/sweep_runner.h"

using namespace stairplan;

TEST_CASE("axes parse A:B:N and single values, and reject nonsense naming the flag", "[sweep]") {
  const SweepAxis a = SweepAxis::Parse("0.1:0.25:4", "--rise");
  REQUIRE(a.Values().size() == 4);
  CHECK(a.Values()[0] == Approx(0.1));
  CHECK(a.Values()[3] == Approx(0.25));
  CHECK(SweepAxis::Parse("0.3", "--run").Values() == std::vector<double>{0.3});
  for (const char* bad : {"0.1:0.2", "a:b:3", "0.2:0.1:3", "0.1:0.2:0", "0.1:0.2:2.5", "", "nan"}) {
    INFO(bad);
    CHECK_THROWS_WITH(SweepAxis::Parse(bad, "--rise"), Catch::Contains("--rise"));
  }
}

TEST_CASE("shards partition the points and a merge restores the order", "[sweep]") {
  SweepGrid grid;
  grid.rise = {0.1, 0.2, 5};
  grid.run = {0.2, 0.3, 7};
  grid.directions = {TravelDirection::kUp, TravelDirection::kDown};
  const auto points = EnumeratePoints(grid);
  REQUIRE(points.size() == 70);
  const auto fake = [](const SweepPoint& p) {
    SweepRow row;
    row.point = p;
    row.status = p.rise / p.run < 0.6 ? "valid" : "invalid";
    row.min_clearance_m = p.run - p.rise;
    if (row.status != "valid") row.reason = "joint_limits RF, \"quoted\"";  // commas and quotes survive the CSV
    return row;
  };
  const std::string whole = SweepToCsv(RunSweep(points, fake, 1), false);
  CHECK(SweepToCsv(RunSweep(points, fake, 3), false) == whole);  // thread count does not matter
  std::vector<std::pair<std::string, std::string>> parts;
  std::set<int> seen;
  for (int i = 0; i < 3; ++i) {
    const auto rows = RunSweep(points, fake, 2, Shard{i, 3});
    for (const auto& r : rows) CHECK(seen.insert(r.point.index).second);
    const SweepManifest manifest = SweepManifest::Current(SweepTable::kPlans, grid, "fake", "", Shard{i, 3});
    parts.emplace_back("part" + std::to_string(i) + ".csv", manifest.ToText() + SweepToCsv(rows, false));
  }
  CHECK(seen.size() == points.size());
  const std::string manifest = SweepManifest::Current(SweepTable::kPlans, grid, "fake", "", Shard{}).ToText();
  CHECK(MergeSweepCsv(parts) == manifest + whole);
  // The merged CSV reads back into the same rows (what sweep-merge summarises).
  const std::vector<SweepRow> back = SweepRowsFromCsv(MergeSweepCsv(parts), "merged.csv");
  CHECK(SweepToCsv(back, false) == whole);
  CHECK_THROWS_WITH(SweepRowsFromCsv(SweepCsvHeader(false) + "\n3,up,x\n", "bad.csv"), Catch::Contains("bad.csv:2"));
  parts.push_back(parts.front());
  CHECK_THROWS_WITH(MergeSweepCsv(parts), Catch::Contains("part0.csv: shard 0/3 given twice"));
  CHECK_THROWS_WITH(Shard::Parse("3/3", "--shard"), Catch::Contains("--shard"));
}

TEST_CASE("workers get the slowest points first: more steps, then higher risers, then longer runs", "[sweep]") {
  SweepGrid grid;
  grid.rise = {0.1, 0.2, 3};
  grid.run = {0.2, 0.3, 2};
  grid.steps = {2, 3, 2};
  grid.directions = {TravelDirection::kUp, TravelDirection::kDown};
  const auto points = EnumeratePoints(grid);
  std::vector<int> all;
  for (const auto& p : points) all.push_back(p.index);
  const std::vector<int> order = SlowestFirst(all, points);
  CHECK(std::multiset<int>(order.begin(), order.end()) == std::multiset<int>(all.begin(), all.end()));
  for (std::size_t i = 1; i < order.size(); ++i) {
    const SweepPoint& a = points[static_cast<std::size_t>(order[i - 1])];
    const SweepPoint& b = points[static_cast<std::size_t>(order[i])];
    INFO(i);
    CHECK(std::make_tuple(a.steps, a.rise, a.run) >= std::make_tuple(b.steps, b.rise, b.run));
    // Equal costs keep EnumeratePoints' order (up before down), so a resumed run hands out the same order.
    if (std::make_tuple(a.steps, a.rise, a.run) == std::make_tuple(b.steps, b.rise, b.run)) CHECK(order[i - 1] < order[i]);
  }
  CHECK(points[static_cast<std::size_t>(order.front())].rise == Approx(0.2));
  CHECK(points[static_cast<std::size_t>(order.front())].steps == 3);
}
