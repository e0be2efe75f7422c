// Stairs YAML: fields, per-step lists, errors that name the file, field and line, and the
// writer's text read back to the same spec.
#include <catch2/catch.hpp>

#include <random>

#include "stairplan/geometry/field_error.h"
#include "stairplan/geometry/stair_spec_yaml.h"

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

TEST_CASE("written stairs YAML reads back to the same spec, bit for bit", "[yaml]") {
  std::mt19937 rng(25);
  std::uniform_real_distribution<double> rise(0.05, 0.3), run(0.15, 0.45), unit(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    StairSpec spec;
    spec.steps = 1 + trial % 12;
    spec.rise = rise(rng);
    spec.run = run(rng);
    spec.nosing = 0.03 * unit(rng);
    spec.nosing_thickness = 0.01 + 0.02 * unit(rng);
    spec.width = 0.6 + unit(rng);
    spec.landing_before = 0.3 + 2.0 * unit(rng);
    spec.landing_after = 0.3 + 2.0 * unit(rng);
    spec.direction = trial % 2 ? TravelDirection::kDown : TravelDirection::kUp;
    if (trial % 3 == 0) {  // irregular flights carry their lists
      for (int k = 0; k < spec.steps; ++k) spec.rises.push_back(rise(rng));
      for (int k = 0; k + 1 < spec.steps; ++k) spec.runs.push_back(run(rng));
    }
    spec.Validate();
    const std::string yaml = StairSpecToYaml(spec, "written by a test\nsecond line");
    INFO(yaml);
    CHECK(yaml.rfind("# written by a test\n# second line\n", 0) == 0);
    const StairSpec back = StairSpecFromYaml(yaml, "w.yaml");
    CHECK(back.steps == spec.steps);
    CHECK(back.rise == spec.rise);
    CHECK(back.run == spec.run);
    CHECK(back.nosing == spec.nosing);
    CHECK(back.nosing_thickness == spec.nosing_thickness);
    CHECK(back.width == spec.width);
    CHECK(back.landing_before == spec.landing_before);
    CHECK(back.landing_after == spec.landing_after);
    CHECK(back.direction == spec.direction);
    CHECK(back.rises == spec.rises);
    CHECK(back.runs == spec.runs);
  }
  // A regular flight's resolved lists (all equal to rise and run) are left out.
  const Staircase regular{StairSpec{}};
  CHECK(StairSpecToYaml(regular.spec()).find("rises") == std::string::npos);
}
