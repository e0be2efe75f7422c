// `stairplan qp solve` and `stairplan qp bench`: output, JSON keys and exit codes.
#include <catch2/catch.hpp>

#include <fstream>

#include <nlohmann/json.hpp>

#include "test_paths.h"

using namespace stairplan::testing;

namespace {

const char* kFeasible = R"(NAME          TINY
ROWS
 N  obj
 G  c1
COLUMNS
    x1        obj       -1.0   c1         1.0
    x2        c1         1.0
RHS
    rhs       c1         1.0
BOUNDS
 UP bnd       x1         4.0
QUADOBJ
    x1        x1         1.0
    x2        x2         1.0
ENDATA
)";

std::string WriteFile(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string path = dir + "/" + name;
  std::ofstream(path) << text;
  return path;
}

std::string Qp(const std::string& text, const std::string& from, const std::string& to) {
  std::string s = text;
  s.replace(s.find(from), from.size(), to);
  return s;
}

}  // namespace

TEST_CASE("qp solve prints JSON with the documented keys and exits 0", "[cli]") {
  const std::string dir = MakeTempDir("qp_cli");
  const std::string file = WriteFile(dir, "tiny.qps", kFeasible);
  const int code = RunCommand(BinDir() + "/stairplan qp solve " + file + " --json", dir + "/out", dir + "/err");
  REQUIRE(code == 0);
  const auto json = nlohmann::json::parse(ReadFile(dir + "/out"));
  for (const char* key : {"status", "objective", "iterations", "solve_time_us", "max_violation", "x"}) {
    CHECK(json.contains(key));
  }
  CHECK(json["status"] == "solved");
  // min 0.5 x1^2 - x1 + 0.5 x2^2 s.t. x1 + x2 >= 1: x = (1, 0) with objective -0.5.
  CHECK(json["objective"].get<double>() == Approx(-0.5).margin(1e-9));
  CHECK(json["x"][0].get<double>() == Approx(1.0).margin(1e-9));
  for (const char* solver : {"ipopt", "nlopt"}) {
    INFO(solver);
    CHECK(RunCommand(BinDir() + "/stairplan qp solve " + file + " --solver " + solver, dir + "/out", dir + "/err") == 0);
    CHECK_THAT(ReadFile(dir + "/out"), Catch::Contains("solved"));
  }
}

TEST_CASE("qp solve exits 3 on an infeasible QP and 2 on bad input", "[cli]") {
  const std::string dir = MakeTempDir("qp_cli_bad");
  // x1 <= 4 and x2 <= 4 (added) but x1 + x2 >= 9.
  const std::string infeasible2 = WriteFile(dir, "infeasible2.qps", Qp(Qp(kFeasible, "    rhs       c1         1.0", "    rhs       c1         9.0"),
                                                                         " UP bnd       x1         4.0", " UP bnd       x1         4.0\n UP bnd       x2         4.0"));
  CHECK(RunCommand(BinDir() + "/stairplan qp solve " + infeasible2 + " --json", dir + "/out", dir + "/err") == 3);
  CHECK(nlohmann::json::parse(ReadFile(dir + "/out"))["status"] == "infeasible");
  const std::string nan = WriteFile(dir, "nan.qps", Qp(kFeasible, "x1        x1         1.0", "x1        x1         nan"));
  CHECK(RunCommand(BinDir() + "/stairplan qp solve " + nan, dir + "/out", dir + "/err") == 2);
  CHECK_THAT(ReadFile(dir + "/err"), Catch::Contains("invalid"));
  const std::string broken = WriteFile(dir, "broken.qps", Qp(kFeasible, "-1.0   c1", "minus  c1"));
  CHECK(RunCommand(BinDir() + "/stairplan qp solve " + broken, dir + "/out", dir + "/err") == 2);
  CHECK_THAT(ReadFile(dir + "/err"), Catch::Contains("broken.qps:6:"));
  CHECK(RunCommand(BinDir() + "/stairplan qp solve " + dir + "/none.qps", dir + "/out", dir + "/err") == 2);
  CHECK(RunCommand(BinDir() + "/stairplan qp solve " + WriteFile(dir, "ok.qps", kFeasible) + " --solver cplex", dir + "/out", dir + "/err") == 2);
  CHECK_THAT(ReadFile(dir + "/err"), Catch::Contains("cplex"));
}

TEST_CASE("qp solve honours --time-limit", "[cli]") {
  const std::string dir = MakeTempDir("qp_cli_time");
  const std::string qps = SharedPath("data/qp/maros_meszaros/QISRAEL.SIF");
  if (qps.empty()) {
    WARN("qp solve --time-limit skipped: ../shared not found");
    return;
  }
  CHECK(RunCommand(BinDir() + "/stairplan qp solve " + qps + " --json --time-limit 1e-6", dir + "/out", dir + "/err") == 1);
  CHECK(nlohmann::json::parse(ReadFile(dir + "/out"))["status"] == "time_limit");
  CHECK(RunCommand(BinDir() + "/stairplan qp solve " + qps + " --time-limit -1", dir + "/out", dir + "/err") == 2);
  CHECK_THAT(ReadFile(dir + "/err"), Catch::Contains("--time-limit"));
}

TEST_CASE("qp bench reports each regime apart and writes CSV, a summary and a plot", "[cli]") {
  const std::string dir = MakeTempDir("qp_bench");
  WriteFile(dir, "a.qps", kFeasible);
  WriteFile(dir, "b.qps", Qp(kFeasible, "    rhs       c1         1.0", "    rhs       c1         2.0"));
  const int code = RunCommand(BinDir() + "/stairplan qp bench " + dir + " --solvers active-set,ipopt --repeat 2 --csv " +
                                  dir + "/out.csv --summary-csv " + dir + "/summary.csv --plot " + dir + "/plot.svg",
                              dir + "/out", dir + "/err");
  REQUIRE(code == 0);
  const std::string out = ReadFile(dir + "/out");
  CHECK_THAT(out, Catch::Contains("active-set cold") && Catch::Contains("ipopt cold") && Catch::Contains("re-solve"));
  CHECK_THAT(out, Catch::Contains("QPS files   cold") && Catch::Contains("QPS files   identical-resolve"));
  CHECK_THAT(out, Catch::Contains("cold: ipopt / active-set") && Catch::Contains("identical-resolve: ipopt / active-set"));
  const std::string csv = ReadFile(dir + "/out.csv");
  CHECK_THAT(csv, Catch::Contains("problem,qp,solver,regime,status,objective,iterations,cpu_us,wall_us,primal_residual"));
  CHECK_THAT(csv, Catch::Contains("a.qps,0,ipopt,cold,solved") && Catch::Contains("a.qps,0,active-set,identical-resolve,solved"));
  // Both tiny QPs are solved at 1e-6 by our solver in both regimes.
  const std::string summary = ReadFile(dir + "/summary.csv");
  CHECK_THAT(summary, Catch::Contains("QPS files,cold,active-set,2,2,") &&
                          Catch::Contains("QPS files,identical-resolve,active-set,2,2,"));
  const std::string svg = ReadFile(dir + "/plot.svg");
  CHECK_THAT(svg, Catch::StartsWith("<svg") && Catch::Contains("QPS files, cold, 2 problems") &&
                      Catch::Contains("identical-resolve"));
  CHECK(RunCommand(BinDir() + "/stairplan qp bench " + dir + " --regimes lukewarm", dir + "/out", dir + "/err") == 2);
  CHECK_THAT(ReadFile(dir + "/err"), Catch::Contains("--regimes"));
}

TEST_CASE("qp bench runs a sequence warm, every solver warm-started", "[cli]") {
  const std::string seq = SharedPath("data/qp/online_qp/diesel");
  if (seq.empty()) {
    WARN("qp bench sequence test skipped: ../shared not found");
    return;
  }
  const std::string dir = MakeTempDir("qp_bench_seq");
  const int code = RunCommand(BinDir() + "/stairplan qp bench " + seq + " --solvers active-set,ipopt --max-qps 4 --csv " +
                                  dir + "/out.csv", dir + "/out", dir + "/err");
  REQUIRE(code == 0);
  const std::string out = ReadFile(dir + "/out");
  CHECK_THAT(out, Catch::Contains("diesel    active-set   warm-sequence      3") &&
                      Catch::Contains("diesel    ipopt        warm-sequence      3") && Catch::Contains("diesel, warm-sequence: ipopt / active-set"));
  CHECK_THAT(ReadFile(dir + "/out.csv"), Catch::Contains("diesel,1,active-set,warm-sequence,solved"));
}
