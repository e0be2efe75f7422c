#include <catch2/catch.hpp>

#include "stairplan/simulation/verdict_agreement.h"

using namespace stairplan;

TEST_CASE("validator and physics verdicts are counted and every disagreement is listed", "[simulation]") {
  const std::vector<VerdictPair> pairs = {
      {"a", true, "", true, ""},
      {"b", false, "stair_collision LF", false, "contact: LF_SHANK"},
      {"c", true, "", false, "fall: roll 0.7 rad"},
      {"d", false, "stability body", true, ""},
  };
  const AgreementReport r = CompareVerdicts(pairs);
  CHECK(r.compared == 4);
  CHECK(r.agreed == 2);
  CHECK(r.both_ok == 1);
  CHECK(r.both_failed == 1);
  CHECK(r.rate == Approx(0.5));
  REQUIRE(r.valid_but_failed.size() == 1);
  CHECK(r.valid_but_failed[0].label == "c");
  REQUIRE(r.invalid_but_passed.size() == 1);
  CHECK(r.invalid_but_passed[0].label == "d");
  const std::string text = AgreementToText(r);
  CHECK(text.find("2/4 agree (50.0%)") != std::string::npos);
  CHECK(text.find("c: fall: roll 0.7 rad") != std::string::npos);
  CHECK(text.find("d: stability body") != std::string::npos);
  CHECK(CompareVerdicts({}).rate == 1.0);
}
