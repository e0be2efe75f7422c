// `stairplan gait-design` end to end: JSON keys, the verdict as the exit code, flags named on error.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "test_paths.h"

using namespace stairplan::testing;

namespace {

int Run(const std::string& flags, std::string* out, std::string* err) {
  const std::string dir = MakeTempDir("gait-cli");
  const int code = RunCommand(BinDir() + "/stairplan gait-design " + flags, dir + "/out", dir + "/err");
  *out = ReadFile(dir + "/out");
  *err = ReadFile(dir + "/err");
  return code;
}

}  // namespace

TEST_CASE("gait-design --json: the paper's robot on its stairs", "[gait][cli]") {
  std::string out, err;
  const int code = Run("--rise 0.17 --run 0.27 --lmax 0.21 --body-length 0.444 --body-width 0.36 --buffer 0.42 --json", &out, &err);
  INFO(err);
  REQUIRE(code == 0);
  const auto j = nlohmann::json::parse(out);
  CHECK(j["l_min"].get<double>() == Approx(0.1885).margin(0.00005));
  CHECK(j["D_s"].get<double>() == Approx(0.05737).margin(0.00001));
  CHECK(j["D_o"].get<double>() == Approx(1.58 * 0.05737).margin(0.00002));
  CHECK(j["feasible"].get<bool>());
  CHECK_FALSE(j["binding"].get<std::string>().empty());
  CHECK(j["swing_sequence"] == nlohmann::json({"RH", "LH", "RF", "LF"}));
  CHECK(j["error_tolerance"]["dW_max"].get<double>() == Approx(0.029).margin(0.0005));
  CHECK(j["stability"]["case1"]["fraction_outside"].get<double>() > 0.0);
  // Ours, not the paper's 27.3 % and 30 %: third_party_notes/chen2012_stair_climbing.md.
  CHECK(j["stability"]["case1"]["fraction_outside"].get<double>() == Approx(0.293).margin(0.002));
  CHECK(j["stability"]["case2"]["fraction_outside"].get<double>() == Approx(0.2086).margin(0.002));
  CHECK(j["stability"]["hind_swing_share"].get<double>() == Approx(0.2086).margin(0.0005));
  CHECK(j["D_o_share"].get<double>() == Approx(0.284).margin(0.001));
}

TEST_CASE("gait-design --figure writes the paper's Figure 4(b)", "[gait][cli]") {
  const std::string dir = MakeTempDir("gait-figure");
  std::string out, err;
  const int code = Run("--rise 0.16 --run 0.28 --lmax 0.21 --body-length 0.444 --figure " + dir + "/fig.svg", &out, &err);
  INFO(err);
  CHECK(code == 0);
  const std::string svg = ReadFile(dir + "/fig.svg");
  CHECK(svg.rfind("<svg", 0) == 0);
  CHECK(svg.find("28 x 16") != std::string::npos);
  CHECK(svg.find("this stair") == std::string::npos);  // 28 x 16 is one of the paper's
  CHECK(Run("--rise 0.17 --run 0.27 --lmax 0.21 --body-length 0.444 --figure /nonexistent/dir/fig.svg", &out, &err) == 2);
  CHECK(err.find("/nonexistent/dir/fig.svg") != std::string::npos);
}

TEST_CASE("gait-design: a short leg is infeasible (exit 3) naming (10)", "[gait][cli]") {
  std::string out, err;
  const int code = Run("--rise 0.17 --run 0.27 --lmax 0.18 --body-length 0.444 --json", &out, &err);
  CHECK(code == 3);
  const auto j = nlohmann::json::parse(out);
  CHECK_FALSE(j["feasible"].get<bool>());
  CHECK(j["binding"] == "(10)");
  CHECK(j["stability"].is_null());
}

TEST_CASE("gait-design: bad input exits 2 naming the flag", "[gait][cli]") {
  std::string out, err;
  CHECK(Run("--rise -0.17 --run 0.27 --lmax 0.21 --body-length 0.444", &out, &err) == 2);
  CHECK_THAT(err, Catch::Contains("--rise"));
  CHECK(Run("--rise 0.17 --run 0.27 --lmax 0.21 --body-length 0.444 --buffer 1.5", &out, &err) == 2);
  CHECK_THAT(err, Catch::Contains("--buffer"));
  CHECK(Run("--rise 0.17 --run 0.27 --body-length 0.444", &out, &err) == 2);
  CHECK_THAT(err, Catch::Contains("--lmax"));
}

TEST_CASE("gait-design --tread-errors: the cumulative error of eq. (19)", "[gait][cli]") {
  std::string out, err;
  const std::string base = "--rise 0.17 --run 0.27 --lmax 0.21 --body-length 0.444 --json --tread-errors ";
  REQUIRE(Run(base + "0.01,0.01,0.01,0.01", &out, &err) == 0);  // the design itself stays feasible
  auto j = nlohmann::json::parse(out);
  CHECK(j["cumulative_error"]["first_violation"] == 2);
  CHECK_FALSE(j["cumulative_error"]["within"].get<bool>());
  CHECK(j["cumulative_error"]["dW_t"][3].get<double>() == Approx(0.04));
  REQUIRE(Run(base + "0.02,-0.02,0.02", &out, &err) == 0);
  j = nlohmann::json::parse(out);
  CHECK(j["cumulative_error"]["within"].get<bool>());
  CHECK(j["cumulative_error"]["first_violation"] == -1);
  CHECK(Run(base + "0.01,abc", &out, &err) == 2);
  CHECK_THAT(err, Catch::Contains("--tread-errors"));
}

TEST_CASE("gait-design: an empty tread-error range is said to be empty, not printed as an interval", "[gait][cli]") {
  std::string out, err;
  // Eq. (17) needs dW > -0.0205 m and dW < -0.0719 m here: no tread error is tolerated.
  const std::string flags = "--rise 0.10 --run 0.15 --lmax 0.2 --body-length 0.5 --hip-clearance 0.1";
  CHECK(Run(flags + " --json", &out, &err) == 3);
  auto j = nlohmann::json::parse(out);
  CHECK(j["error_tolerance"]["empty"] == true);
  CHECK(j["error_tolerance"]["dW_min"].get<double>() > j["error_tolerance"]["dW_max"].get<double>());
  CHECK(Run(flags, &out, &err) == 3);
  CHECK_THAT(out, Catch::Contains("tread error tolerance: none (eq. (17) needs dW > -0.02052 m and dW < -0.07194 m)"));
  CHECK_THAT(out, !Catch::Contains("< dW <"));
  // Without D_s > 0 there is no range at all; the paper's own stairs have one.
  CHECK(Run("--rise 0.17 --run 0.27 --lmax 0.18 --body-length 0.444", &out, &err) == 3);
  CHECK_THAT(out, Catch::Contains("tread error tolerance: none (undefined without D_s > 0)"));
  CHECK(Run("--rise 0.17 --run 0.27 --lmax 0.21 --body-length 0.444 --json", &out, &err) == 0);
  CHECK(nlohmann::json::parse(out)["error_tolerance"]["empty"] == false);
}
