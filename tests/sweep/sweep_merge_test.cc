// Sweep integrity without planning anything: a throwing point is a failed row, manifests round-trip
// and name what differs, merges refuse every shard set that is not exactly one sweep's, a killed
// journal's cut-off line is dropped, and the atlas summary finds each region's edges.
#include <catch2/catch.hpp>

#include <stdexcept>

#include "stairplan/sweep/sweep_atlas.h"
#include "stairplan/sweep/sweep_merge.h"
#include "stairplan/sweep/sweep_runner.h"

using namespace stairplan;

namespace {

SweepGrid MergeTestGrid(int rises) {
  SweepGrid grid;
  grid.rise = {0.10, 0.20, rises};
  grid.run = {0.20, 0.32, 3};
  grid.steps = {3, 3, 1};
  return grid;
}

SweepRow MergeTestRow(const SweepPoint& p) {
  SweepRow row;
  row.point = p;
  row.status = p.rise / p.run < 0.6 ? "valid" : "invalid";
  return row;
}

// Shard `shard` of a sweep over `grid`, as its CSV would be written.
std::pair<std::string, std::string> MergeTestShard(const SweepGrid& grid, const Shard& shard, const std::string& file) {
  const auto rows = RunSweep(EnumeratePoints(grid), MergeTestRow, 1, shard);
  const SweepManifest manifest = SweepManifest::Current(SweepTable::kPlans, grid, "fake", "simulate=no", shard);
  return {file, manifest.ToText() + SweepToCsv(rows, false)};
}

}  // namespace

TEST_CASE("a point whose evaluation throws is a failed row and the sweep goes on", "[sweep]") {
  const auto points = EnumeratePoints(MergeTestGrid(3));
  int delivered = 0;
  const auto rows = RunSweep(points, [](const SweepPoint& p) {
    if (p.index == 4) throw std::runtime_error("solver blew up at point 4");
    return MergeTestRow(p);
  }, 2, Shard{}, nullptr, [&](const SweepRow&) { ++delivered; });
  REQUIRE(rows.size() == points.size());
  CHECK(delivered == static_cast<int>(points.size()));
  CHECK(rows[4].status == "failed");
  CHECK(rows[4].reason == "solver blew up at point 4");
  CHECK(rows[5].status == "valid");
  // The failed row survives the CSV with its message.
  CHECK(SweepRowFromCsvLine(SweepCsvLine(rows[4], false)).reason == "solver blew up at point 4");
}

TEST_CASE("a row keeps its gait through the CSV, and a row written before the gait column reads back without one",
          "[sweep]") {
  SweepRow row = MergeTestRow(EnumeratePoints(MergeTestGrid(3))[2]);
  row.gait = Gait::kWalk;
  row.plan_us = 12.5;
  row.validate_us = 3.0;
  for (const bool times : {false, true}) {
    CAPTURE(times);
    const SweepRow back = SweepRowFromCsvLine(SweepCsvLine(row, times));
    CHECK(back.gait == Gait::kWalk);
    CHECK(back.status == row.status);
    CHECK(back.plan_us == (times ? 12.5 : 0.0));
  }
  row.gait.reset();
  CHECK_FALSE(SweepRowFromCsvLine(SweepCsvLine(row, false)).gait.has_value());
  // The columns before the gait's, with and without times, as sweeps wrote them before it.
  const SweepRow old = SweepRowFromCsvLine("7,up,3,0.15,0.26,0.02,valid,0.45,20,0.011,0.03,\"\",8.5,1.5");
  CHECK(old.point.index == 7);
  CHECK_FALSE(old.gait.has_value());
  CHECK(old.plan_us == 8.5);
  CHECK(old.validate_us == 1.5);
  CHECK_FALSE(SweepRowFromCsvLine("7,up,3,0.15,0.26,0.02,valid,0.45,20,0.011,0.03,\"\"").gait.has_value());
  CHECK_THROWS(SweepRowFromCsvLine("7,up,3,0.15,0.26,0.02,valid,0.45,20,0.011,0.03,\"\",gallop"));
  CHECK_NOTHROW(SweepRowsFromCsv("index,direction,steps,rise,run,nosing,status,cadence_s,footsteps,min_clearance_m,"
                                 "min_stability_margin_m,reason\n7,up,3,0.15,0.26,0.02,valid,0.45,20,0.011,0.03,\"\"\n",
                                 "old.csv"));
}

TEST_CASE("a manifest reads back and names the field in which two sweeps differ", "[sweep]") {
  SweepGrid grid = MergeTestGrid(3);
  grid.directions = {TravelDirection::kUp, TravelDirection::kDown};
  const SweepManifest m = SweepManifest::Current(SweepTable::kPlans, grid, "stairbot builtin", "simulate=no", Shard{1, 4});
  const SweepManifest back = SweepManifest::FromText(m.ToText() + "index,rest\n", "m.csv");
  CHECK(back.ToText() == m.ToText());
  CHECK(back.Difference(m).empty());
  CHECK(EnumeratePoints(back.grid).size() == EnumeratePoints(grid).size());
  SweepManifest other = m;
  other.grid.run.count = 4;
  other.shard = Shard{2, 4};  // the shard is not a difference of sweeps
  CHECK(other.Difference(m) == "run: '0.2:0.32:4' vs '0.2:0.32:3'");
  CHECK_THROWS_WITH(SweepManifest::FromText("index,direction\n", "old.csv"), Catch::Contains("old.csv:1: no sweep manifest"));
  std::string broken = m.ToText();
  broken.replace(broken.find("# rise: "), 8, "# rice: ");
  CHECK_THROWS_WITH(SweepManifest::FromText(broken, "b.csv"), Catch::Contains("b.csv: manifest: no 'rise'"));
}

TEST_CASE("sweep-merge refuses missing, duplicated, incomplete and foreign shards naming the file", "[sweep]") {
  const SweepGrid grid = MergeTestGrid(3);
  const auto a = MergeTestShard(grid, Shard{0, 3}, "a.csv");
  const auto b = MergeTestShard(grid, Shard{1, 3}, "b.csv");
  const auto c = MergeTestShard(grid, Shard{2, 3}, "c.csv");
  const std::string whole = MergeSweepCsv({c, a, b});
  CHECK(SweepRowsFromCsv(whole, "w.csv").size() == 9);
  CHECK(SweepManifest::FromText(whole, "w.csv").shard.count == 1);

  CHECK_THROWS_WITH(MergeSweepCsv({a, c}), Catch::Contains("shard 1/3 missing") && Catch::Contains("a.csv"));
  CHECK_THROWS_WITH(MergeSweepCsv({a, b, std::make_pair(std::string("b2.csv"), b.second), c}),
                    Catch::Contains("b2.csv: shard 1/3 given twice (also b.csv)"));
  const auto other_grid = MergeTestShard(MergeTestGrid(4), Shard{1, 3}, "g.csv");
  CHECK_THROWS_WITH(MergeSweepCsv({a, other_grid, c}), Catch::Contains("g.csv: a different sweep from a.csv (rise:"));
  const auto two_way = MergeTestShard(grid, Shard{1, 2}, "h.csv");
  CHECK_THROWS_WITH(MergeSweepCsv({a, two_way}), Catch::Contains("h.csv: shard 1/2 of a 2-way split"));
  // A shard killed before it finished, and a row that is another shard's.
  std::string cut = b.second;
  cut.erase(cut.rfind('\n', cut.size() - 2) + 1);
  CHECK_THROWS_WITH(MergeSweepCsv({a, {"b.csv", cut}, c}), Catch::Contains("b.csv: shard 1/3 is incomplete: 1 of its points"));
  CHECK_THROWS_WITH(MergeSweepCsv({a, {"b.csv", b.second + "0,up,3\n"}, c}), Catch::Contains("b.csv: point 0 is not shard 1/3's"));
  CHECK_THROWS_WITH(MergeSweepCsv({a, {"old.csv", SweepCsvHeader(false) + "\n"}, c}), Catch::Contains("old.csv:1: no sweep manifest"));
}

TEST_CASE("a journal cut off mid-line keeps its finished rows only", "[sweep]") {
  const auto a = MergeTestShard(MergeTestGrid(3), Shard{}, "j.csv");
  const std::string cut = a.second.substr(0, a.second.size() - 5);  // the last row lost its end
  const SweepTableText table = ReadSweepTable(cut, "j.csv", true);
  CHECK(table.lines.size() == 8);
  CHECK(table.lines.count(8) == 0);
  CHECK(ReadSweepTable(a.second, "j.csv", true).ToCsv() == a.second);
  CHECK_THROWS_WITH(ReadSweepTable(a.second + "x,up\n", "j.csv", true), Catch::Contains("j.csv:24: not a sweep row"));
}

TEST_CASE("the atlas summary gives each robot's valid count and the edges of its region", "[sweep]") {
  SweepGrid grid = MergeTestGrid(3);  // rise 0.10, 0.15, 0.20 x run 0.20, 0.26, 0.32
  grid.directions = {TravelDirection::kUp, TravelDirection::kDown};
  const auto rows = RunSweep(EnumeratePoints(grid), MergeTestRow, 1);  // valid: rise/run < 0.6
  const auto entries = SummariseAtlas({{"fake", rows}}, grid);
  REQUIRE(entries.size() == 2);
  CHECK(entries[1].direction == TravelDirection::kDown);
  CHECK(entries[0].points == 9);
  CHECK(entries[0].valid == 5);  // 0.10 at every run, 0.15 at 0.26 and 0.32
  CHECK(entries[0].steepest_rise == Approx(0.15));
  CHECK(entries[0].steepest_run == Approx(0.26));
  CHECK(entries[0].highest_rise == Approx(0.15));
  CHECK(entries[0].shortest_run == Approx(0.20));
  CHECK(entries[0].connected);
  CHECK_THAT(SweepAtlasMarkdown({{"fake", rows}}, grid), Catch::Contains("| fake | down | 5 / 9 | yes | 0.150 / 0.260 m"));
}
