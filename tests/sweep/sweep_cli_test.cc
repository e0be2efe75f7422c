// `stairplan sweep` end to end: the CSV does not depend on the thread count, shards merge into the
// unsharded CSV, points it calls valid are valid when planned and validated again alone, and it
// summarises the success region.
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "sanitized.h"
#include "stairplan/version.h"
#include "test_paths.h"

using namespace stairplan::testing;

namespace {

int Run(const std::string& args, const std::string& dir) {
  return RunCommand(BinDir() + "/stairplan " + args, dir + "/out.txt", dir + "/err.txt");
}

std::vector<std::vector<std::string>> Rows(const std::string& csv) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(csv);
  std::string line;
  while (std::getline(in, line) && line.rfind('#', 0) == 0) {
  }  // the manifest, then the header
  while (std::getline(in, line)) {
    std::vector<std::string> fields;
    std::istringstream fs(line);
    for (std::string f; std::getline(fs, f, ',');) fields.push_back(f);
    rows.push_back(fields);
  }
  return rows;
}

}  // namespace

TEST_CASE("sweep CSV is identical for 1 and 2 threads and its valid rows re-validate", "[sweep][cli]") {
  const std::string dir = MakeTempDir("sweep-threads");
  // A 3 x 3 grid of 4-step flights and 4 of its valid rows re-validated; under the sanitizers,
  // where every point plans 20-50x slower, two 2-step flights of one run and no re-validation
  // (the CLI tests plan and validate under the sanitizers too).
  const std::size_t n = FullOrSanitized<std::size_t>(3, 2);
  const std::size_t n_run = FullOrSanitized<std::size_t>(3, 1);
  const int wanted = FullOrSanitized(4, 0);
  const std::string steps = FullOrSanitized<std::string>("4", "2");
  const std::string run = FullOrSanitized<std::string>("0.25:0.33:", "0.29:0.29:");
  const std::string grid = "sweep --rise 0.12:0.20:" + std::to_string(n) + " --run " + run + std::to_string(n_run) + " --steps " + steps;
  REQUIRE(Run(grid + " --threads 1 --csv " + dir + "/one.csv --svg " + dir + "/map.svg", dir) == 0);
  // Its summary of the success region. (On these gentle stairs the default's plan at rise 0.20,
  // run 0.33 puts the left hind leg 0.4 degrees past a joint limit as it lifts, where run 0.29 is
  // valid: steeper stairs do not all fail first, issue 18's open reach.)
  const std::string summary = ReadFile(dir + "/out.txt");
  CHECK_THAT(summary, Catch::Contains("one connected area"));
  CHECK_THAT(summary, Catch::Contains("steeper stairs fail first: "));
  const std::string one = ReadFile(dir + "/one.csv");
  // The two-thread run in the normal build only: under the sanitizers the shards test below runs
  // a two-thread sweep (the same code), and this second sweep took a third of this test's 62 s.
  if (!kSanitized) {
    REQUIRE(Run(grid + " --threads 2 --csv " + dir + "/two.csv", dir) == 0);
    CHECK(one == ReadFile(dir + "/two.csv"));
  }
  // Its manifest names the version and file schema of the program that wrote it.
  CHECK_THAT(one, Catch::Contains("\n# version: " + std::string(stairplan::kVersion) + "\n# schema: " +
                                  std::to_string(stairplan::kSchemaVersion) + "\n"));
  CHECK_THAT(ReadFile(dir + "/map.svg"), Catch::Contains("US residential"));
  const auto rows = Rows(one);
  REQUIRE(rows.size() == n * n_run);
  int checked = 0;
  for (const auto& r : rows) {
    if (r[6] != "valid" || checked >= wanted) continue;
    // Plan the point alone with the finer default validation step.
    const std::string out = dir + "/p" + r[0];
    REQUIRE(Run("plan --steps " + r[2] + " --rise " + r[3] + " --run " + r[4] + " --nosing " + r[5] + " --out " + out, dir) == 0);
    const auto plan = nlohmann::json::parse(ReadFile(out + "/plan.json"));
    CHECK(plan["validation"]["ok"] == true);
    ++checked;
  }
  CHECK(checked == wanted);
}

TEST_CASE("sweep --gait auto names the gait each point took, and a gait it does not plan exits 2", "[sweep][cli]") {
  const std::string dir = MakeTempDir("sweep-gait");
  const std::string runs = FullOrSanitized<std::string>("0.26:0.30:2", "0.28");
  REQUIRE(Run("sweep --rise 0.12 --run " + runs + " --steps 3 --gait auto --csv " + dir + "/auto.csv", dir) == 0);
  const std::string csv = ReadFile(dir + "/auto.csv");
  CHECK_THAT(csv, Catch::Contains("gait=auto"));
  CHECK_THAT(csv, Catch::Contains(",reason,gait\n"));
  const auto rows = Rows(csv);
  REQUIRE_FALSE(rows.empty());
  for (const auto& r : rows) {
    CAPTURE(r[0]);
    REQUIRE(r.size() == 13);
    CHECK(r[6] == "valid");
    // Gentle stairs: the built-in robot's trot validates, and auto takes it.
    CHECK(r[12] == "trot");
  }
  CHECK(Run("sweep --rise 0.12 --run 0.28 --steps 3 --gait gallop --csv " + dir + "/gallop.csv", dir) == 2);
  CHECK_THAT(ReadFile(dir + "/err.txt"), Catch::Contains("--gait"));
  CHECK_FALSE(std::ifstream(dir + "/gallop.csv").good());
}

TEST_CASE("sweep shards merged equal the unsharded sweep", "[sweep][cli]") {
  const std::string dir = MakeTempDir("sweep-shards");
  // A 3 x 3 grid over the whole range, steep points the validator rejects among them: shards of
  // five and four points. Under the sanitizers, where a point plans 20-50x slower, two moderate
  // 2-step stairs of one run: shards of one point each, the same sharding and merging code.
  const std::size_t n = FullOrSanitized<std::size_t>(3, 2);
  const std::size_t n_run = FullOrSanitized<std::size_t>(3, 1);
  const std::string rise = FullOrSanitized<std::string>("0.10:0.25:", "0.12:0.17:");
  const std::string run = FullOrSanitized<std::string>("0.20:0.35:", "0.29:0.29:");
  const std::string grid = "sweep --rise " + rise + std::to_string(n) + " --run " + run + std::to_string(n_run) +
                           " --steps " + FullOrSanitized<std::string>("3", "2") + " --validation-step 0.1";
  REQUIRE(Run(grid + " --csv " + dir + "/all.csv --threads 2", dir) == 0);
  REQUIRE(Run(grid + " --shard 0/2 --csv " + dir + "/a.csv", dir) == 0);
  REQUIRE(Run(grid + " --shard 1/2 --csv " + dir + "/b.csv", dir) == 0);
  REQUIRE(Run("sweep-merge --csv " + dir + "/merged.csv " + dir + "/b.csv " + dir + "/a.csv", dir) == 0);
  CHECK_THAT(ReadFile(dir + "/out.txt"), Catch::Contains("/" + std::to_string(n * n_run) + " valid; "));  // the whole sweep's summary
  CHECK(Rows(ReadFile(dir + "/all.csv")).size() == n * n_run);
  CHECK(ReadFile(dir + "/merged.csv") == ReadFile(dir + "/all.csv"));
  CHECK(Run("sweep --rise 0.1:0.2:x --csv " + dir + "/bad.csv", dir) == 2);
  CHECK_THAT(ReadFile(dir + "/err.txt"), Catch::Contains("--rise"));
}
