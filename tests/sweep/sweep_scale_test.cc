// Sweeps beyond one process, end to end: a run killed with SIGKILL and resumed ends with the CSV of
// an uninterrupted run; MPI ranks give the single process's CSV; sweep-merge refuses shard sets
// that are not one sweep, naming the file; an atlas writes a heatmap per robot and direction.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <fstream>

#include "stairplan/simulation/sweep_physics.h"
#include "stairplan/sweep/sweep_manifest.h"
#include "stairplan/sweep/sweep_runner.h"
#include "sanitized.h"
#include "test_paths.h"

using namespace stairplan::testing;

namespace {

int ScaleRun(const std::string& args, const std::string& dir) {
  return RunCommand(BinDir() + "/stairplan " + args, dir + "/out.txt", dir + "/err.txt");
}

int ScaleDataRows(const std::string& csv) {
  int rows = 0;
  for (std::size_t at = 0; (at = csv.find('\n', at)) != std::string::npos; ++at) {
    rows += at + 1 < csv.size() && csv[at + 1] >= '0' && csv[at + 1] <= '9' ? 1 : 0;
  }
  return rows;
}

}  // namespace

TEST_CASE("a sweep killed with SIGKILL and resumed ends with the uninterrupted run's CSV", "[sweep][cli]") {
  const std::string dir = MakeTempDir("sweep-resume");
  // 3 x 2 one-step flights (about 0.2 s of CPU each), killed after half; 2 x 1 under the sanitizers.
  const int rises = FullOrSanitized(3, 2), runs = FullOrSanitized(2, 1), total = rises * runs;
  const std::string grid = "sweep --rise 0.12:0.17:" + std::to_string(rises) + " --run 0.26:0.32:" +
                           std::to_string(runs) + " --steps 1 --validation-step 0.1";
  REQUIRE(ScaleRun(grid + " --csv " + dir + "/whole.csv", dir) == 0);
  const std::string csv = dir + "/killed.csv";
  // Start it, wait until half its rows are in the file, then SIGKILL it.
  const std::string kill = "(" + BinDir() + "/stairplan " + grid + " --csv " + csv + " >/dev/null 2>&1 & p=$!; n=0; " +
                           "while [ \"$n\" -lt " + std::to_string(total / 2) + " ] && kill -0 $p 2>/dev/null; do " +
                           "sleep 0.05; n=$(grep -c '^[0-9]' " + csv + " 2>/dev/null); n=${n:-0}; done; kill -9 $p)";
  RunCommand(kill, dir + "/kill.out", dir + "/kill.err");
  const int survived = ScaleDataRows(ReadFile(csv));
  CHECK(survived >= total / 2);
  CHECK(survived < total);  // it was killed before the end
  // A write cut off by the kill: a row without its end.
  RunCommand("printf '" + std::to_string(total - 1) + ",up,1,0.1' >> " + csv, dir + "/p.out", dir + "/p.err");
  REQUIRE(ScaleRun(grid + " --resume --csv " + csv, dir) == 0);
  CHECK_THAT(ReadFile(dir + "/out.txt"), Catch::Contains(std::to_string(total - survived) + " computed"));
  CHECK(ReadFile(csv) == ReadFile(dir + "/whole.csv"));
  // Resuming a finished sweep computes nothing; resuming with other flags is refused.
  REQUIRE(ScaleRun(grid + " --resume --csv " + csv, dir) == 0);
  CHECK_THAT(ReadFile(dir + "/out.txt"), Catch::Contains("valid; 0 computed"));
  CHECK(ScaleRun("sweep --rise 0.1 --run 0.3 --steps 1 --resume --csv " + csv, dir) == 2);
  CHECK_THAT(ReadFile(dir + "/err.txt"), Catch::Contains("killed.csv: --resume: the file holds a different sweep (rise:"));
  CHECK(ReadFile(csv) == ReadFile(dir + "/whole.csv"));
}

TEST_CASE("mpirun -np 3 sweep writes the single process's CSV", "[sweep][cli][mpi]") {
#ifndef STAIRPLAN_TEST_MPIEXEC
  WARN("skipped: this build has no MPI (libopenmpi-dev absent when configured)");
#else
  if (kSanitized) {
    // Not tried there: Open MPI is not built for ASan, and two 36-point sweeps would take minutes.
    WARN("skipped under the sanitizers; the normal build runs it");
    return;
  }
  const std::string dir = MakeTempDir("sweep-mpi");
  // The 6 x 6 grid of the acceptance test, one-step flights (about 0.2 s of CPU a point).
  const std::string grid = "sweep --rise 0.08:0.25:6 --run 0.20:0.35:6 --steps 1 --validation-step 0.1";
  REQUIRE(ScaleRun(grid + " --csv " + dir + "/one.csv", dir) == 0);
  const std::string mpirun = std::string(STAIRPLAN_TEST_MPIEXEC) + (geteuid() == 0 ? " --allow-run-as-root" : "") +
                             " --oversubscribe -np 3 ";
  REQUIRE(RunCommand(mpirun + BinDir() + "/stairplan " + grid + " --csv " + dir + "/mpi.csv", dir + "/out.txt",
                     dir + "/err.txt") == 0);
  CHECK_THAT(ReadFile(dir + "/out.txt"), Catch::Contains("over 3 MPI rank(s)"));
  CHECK(ScaleDataRows(ReadFile(dir + "/one.csv")) == 36);
  CHECK(ReadFile(dir + "/mpi.csv") == ReadFile(dir + "/one.csv"));
#endif
}

TEST_CASE("sweep-merge refuses a missing, a duplicated and a foreign shard, naming the file", "[sweep][cli]") {
  const std::string dir = MakeTempDir("sweep-merge-refusals");
  // Shard files as sweep writes them, of a sweep that is never planned: the merge checks them only.
  // With `physics`, as `sweep --simulate` writes them: a physics CSV beside each.
  const auto write = [&](const std::string& name, const std::string& rise, const stairplan::Shard& shard,
                         bool physics = false) {
    stairplan::SweepGrid grid;
    grid.rise = stairplan::SweepAxis::Parse(rise, "rise");
    grid.run = {0.26, 0.26, 1};
    const auto rows = stairplan::RunSweep(stairplan::EnumeratePoints(grid), [](const stairplan::SweepPoint& p) {
      stairplan::SweepRow row;
      row.point = p;
      row.status = "valid";
      return row;
    }, 1, shard);
    const std::string settings = physics ? "simulate=yes" : "simulate=no";
    const auto manifest = [&](stairplan::SweepTable table) {
      return stairplan::SweepManifest::Current(table, grid, "fake", settings, shard).ToText();
    };
    std::ofstream(dir + "/" + name) << manifest(stairplan::SweepTable::kPlans) + stairplan::SweepToCsv(rows, false);
    if (!physics) return;
    std::string text = manifest(stairplan::SweepTable::kPhysics) + stairplan::PhysicsCsvHeader() + "\n";
    for (const auto& r : rows) {
      stairplan::PhysicsRow p;
      p.index = r.point.index;
      p.validator = "valid";
      p.status = "success";
      p.passed = p.index % 2 == 0;
      text += stairplan::PhysicsCsvLine(p) + "\n";
    }
    std::ofstream(dir + "/" + name + ".physics.csv") << text;
  };
  write("a.csv", "0.1:0.2:4", {0, 2});
  write("b.csv", "0.1:0.2:4", {1, 2});
  write("b_again.csv", "0.1:0.2:4", {1, 2});
  write("other.csv", "0.1:0.2:5", {1, 2});
  const std::string merge = "sweep-merge --csv " + dir + "/m.csv " + dir + "/";
  REQUIRE(ScaleRun(merge + "a.csv " + dir + "/b.csv --svg " + dir + "/m.svg", dir) == 0);
  CHECK(ScaleDataRows(ReadFile(dir + "/m.csv")) == 4);
  CHECK_THAT(ReadFile(dir + "/m.svg"), Catch::Contains("<svg"));
  CHECK(ScaleRun(merge + "a.csv", dir) == 2);
  CHECK_THAT(ReadFile(dir + "/err.txt"), Catch::Contains("shard 1/2 missing") && Catch::Contains("a.csv"));
  CHECK(ScaleRun(merge + "a.csv " + dir + "/b.csv " + dir + "/b_again.csv", dir) == 2);
  CHECK_THAT(ReadFile(dir + "/err.txt"), Catch::Contains("b_again.csv: shard 1/2 given twice"));
  CHECK(ScaleRun(merge + "a.csv " + dir + "/other.csv", dir) == 2);
  CHECK_THAT(ReadFile(dir + "/err.txt"), Catch::Contains("other.csv: a different sweep from") && Catch::Contains("rise: '0.1:0.2:5'"));
  // --simulate shards: their physics CSVs are merged beside the plans.
  write("sa.csv", "0.1:0.2:4", {0, 2}, true);
  write("sb.csv", "0.1:0.2:4", {1, 2}, true);
  REQUIRE(ScaleRun(merge + "sb.csv " + dir + "/sa.csv", dir) == 0);
  const std::string physics = ReadFile(dir + "/m.csv.physics.csv");
  CHECK(ScaleDataRows(physics) == 4);
  CHECK_THAT(physics, Catch::Contains("# table: physics") && Catch::Contains("# shard: 0/1"));
  CHECK_THAT(ReadFile(dir + "/out.txt"), Catch::Contains("2 both ok"));
  CHECK(ScaleRun(merge + "sa.csv " + dir + "/b.csv", dir) == 2);  // a --simulate shard and a plain one
  CHECK_THAT(ReadFile(dir + "/err.txt"), Catch::Contains("b.csv: a different sweep from") && Catch::Contains("settings"));
}

TEST_CASE("an atlas sweeps each robot and writes its heatmaps and the summary table", "[sweep][cli]") {
  const std::string a1 = SharedPath("data/robots/unitree_a1.urdf");
  if (a1.empty()) {
    WARN("skipped: ../shared/data/robots is absent");
    return;
  }
  const std::string dir = MakeTempDir("sweep-atlas");
  // One point per robot and direction; under the sanitizers up only.
  const std::vector<std::string> directions = kSanitized ? std::vector<std::string>{"up"} : std::vector<std::string>{"up", "down"};
  REQUIRE(ScaleRun("sweep --robots builtin," + a1 + " --rise 0.12 --run 0.28 --steps 1 --direction " +
                   FullOrSanitized<std::string>("up,down", "up") + " --validation-step 0.1 --out " + dir + "/atlas", dir) == 0);
  for (const std::string robot : {"stairbot", "unitree_a1"}) {
    CHECK(!ReadFile(dir + "/atlas/" + robot + ".csv").empty());
    for (const std::string& d : directions) {
      INFO(robot << " " << d);
      CHECK_THAT(ReadFile(dir + "/atlas/" + robot + "-" + d + ".svg"), Catch::Contains("<svg"));
    }
  }
  const std::string table = ReadFile(dir + "/atlas/atlas.md");
  CHECK_THAT(table, Catch::Contains("| stairbot | up | ") && Catch::Contains("| unitree_a1 | " + directions.back() + " | "));
  CHECK(table == ReadFile(dir + "/out.txt").substr(ReadFile(dir + "/out.txt").find("Feasibility atlas")));
  CHECK(ScaleRun("sweep --robots builtin --rise 0.12 --run 0.28 --csv " + dir + "/x.csv", dir) == 2);
  CHECK_THAT(ReadFile(dir + "/err.txt"), Catch::Contains("--robots"));
}
