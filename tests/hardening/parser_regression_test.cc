// Regression tests for what the fuzzers (tests/fuzz) found: each input once crashed or escaped a
// parser with something other than std::invalid_argument naming its source.
#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>

#include "geometry/stair_spec_yaml.h"

using namespace stairplan;

namespace {

// The parser's error for `text`, or "accepted".
template <typename Parse>
std::string ErrorOf(Parse parse) {
  try {
    parse();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST_CASE("stairs YAML: a key that is not a field name is a FieldError naming the file", "[hardening][fuzz][yaml]") {
  // fuzz_stairs_yaml, first minute: a complex key made yaml-cpp throw TypedBadConversion.
  const std::string found("? down\x06steps: 3z ", 17);
  CHECK_THAT(ErrorOf([&] { StairSpecFromYaml(found, "found.yaml"); }), Catch::Contains("found.yaml"));
  CHECK_THAT(ErrorOf([&] { StairSpecFromYaml("[steps]: 3\n", "list-key.yaml"); }), Catch::Contains("list-key.yaml"));
  CHECK_THAT(ErrorOf([&] { StairSpecFromYaml("? {rise: 1}\n: 3\n", "map-key.yaml"); }), Catch::Contains("map-key.yaml"));
}
