// Stairs YAML: fields, per-step lists, and errors that name the file, field and line.
#include <catch2/catch.hpp>

#include "geometry/field_error.h"
#include "geometry/stair_spec_yaml.h"

using namespace stairplan;

TEST_CASE("a full stairs YAML is read", "[yaml]") {
  const auto spec = StairSpecFromYaml("steps: 3\nrise: 0.16\nrun: 0.29\nnosing: 0.025\nwidth: 1.2\n"
                                      "direction: down\nrises: [0.16, 0.17, 0.16]\n", "s.yaml");
  CHECK(spec.steps == 3);
  CHECK(spec.run == Approx(0.29));
  CHECK(spec.direction == TravelDirection::kDown);
  REQUIRE(spec.rises.size() == 3);
  CHECK(spec.rises[1] == Approx(0.17));
}

TEST_CASE("YAML errors name the file and the field", "[yaml]") {
  const auto message = [](const std::string& text) {
    try {
      StairSpecFromYaml(text, "bad.yaml");
    } catch (const FieldError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  CHECK_THAT(message("run: -0.27\n"), Catch::Contains("bad.yaml") && Catch::Contains("'run'"));
  CHECK_THAT(message("rise: abc\n"), Catch::Contains("'rise'") && Catch::Contains("line 1"));
  CHECK_THAT(message("steps: 2.5\n"), Catch::Contains("'steps'"));
  CHECK_THAT(message("stairs: 3\n"), Catch::Contains("unknown field"));
  CHECK_THAT(message("rise: [1, 2\n"), Catch::Contains("not valid YAML"));
  CHECK_THAT(message("- 1\n- 2\n"), Catch::Contains("mapping"));
  CHECK_THAT(message("rise: .nan\n"), Catch::Contains("finite"));
  CHECK_THAT(message("direction: sideways\n"), Catch::Contains("'direction'"));
}
