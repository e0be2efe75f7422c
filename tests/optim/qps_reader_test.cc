// The QPS reader: sections, RANGES, bound types, the objective constant, QUADOBJ mirroring, and
// errors that name the file and line.
#include <catch2/catch.hpp>

#include <string>

#include "stairplan/optim/qps_reader.h"

using namespace stairplan::optim;

namespace {

const char* kSmall = R"(NAME          SMALL
* a comment
ROWS
 N  obj
 G  g1
 L  l1
 E  e1
 E  e2
 G  r1
COLUMNS
    x1        obj        1.0   g1         1.0
    x1        l1         2.0   e1         1.0
    x2        obj       -2.0   g1         1.0
    x2        e2         1.0   r1         1.0
    x3        l1         1.0   e2         1.0
RHS
    rhs       obj        -3.5  g1         1.0
    rhs       l1         4.0   e1         2.0
    rhs       e2         1.0   r1         0.5
RANGES
    rng       l1         1.5   e1         2.0
    rng       e2        -1.0   r1         2.0
BOUNDS
 UP bnd       x1         8.0
 MI bnd       x2
 FX bnd       x3         0.25
QUADOBJ
    x1        x1         2.0
    x1        x2         0.5
    x2        x2         3.0
ENDATA
)";

std::string Error(const std::string& text) {
  try {
    ParseQps(text, "bad.qps");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST_CASE("a QPS file with every section is read", "[qps]") {
  const QpsProblem q = ParseQps(kSmall, "small.qps");
  const Program& p = q.program;
  CHECK(q.name == "SMALL");
  REQUIRE(p.num_variables() == 3);
  REQUIRE(p.num_rows() == 5);
  CHECK(p.constant() == 3.5);  // minus the objective row's RHS
  CHECK(p.linear_cost()[0] == 1.0);
  CHECK(p.linear_cost()[1] == -2.0);
  CHECK(p.hessian()(0, 1) == 0.5);  // mirrored
  CHECK(p.hessian()(1, 0) == 0.5);
  CHECK(p.hessian()(1, 1) == 3.0);
  CHECK(p.constraint_matrix()(1, 0) == 2.0);
  // G without range: [1, inf); L with range 1.5: [2.5, 4]; E with +2: [2, 4]; E with -1: [0, 1];
  // G with range 2: [0.5, 2.5].
  CHECK(p.row_lower()[0] == 1.0);
  CHECK(p.row_upper()[0] == kInf);
  CHECK(p.row_lower()[1] == 2.5);
  CHECK(p.row_upper()[1] == 4.0);
  CHECK(p.row_lower()[2] == 2.0);
  CHECK(p.row_upper()[2] == 4.0);
  CHECK(p.row_lower()[3] == 0.0);
  CHECK(p.row_upper()[3] == 1.0);
  CHECK(p.row_lower()[4] == 0.5);
  CHECK(p.row_upper()[4] == 2.5);
  // Bounds: x1 in [0, 8] (default lower), x2 in (-inf, inf) (MI, default upper), x3 fixed.
  CHECK(p.variable_lower()[0] == 0.0);
  CHECK(p.variable_upper()[0] == 8.0);
  CHECK(p.variable_lower()[1] == -kInf);
  CHECK(p.variable_upper()[1] == kInf);
  CHECK(p.variable_lower()[2] == 0.25);
  CHECK(p.variable_upper()[2] == 0.25);
  CHECK(q.variable_names[2] == "x3");
  CHECK(q.row_names[4] == "r1");
}

TEST_CASE("QPS errors name the file and the line", "[qps]") {
  std::string text = kSmall;
  CHECK_THAT(Error(std::string(text).replace(text.find("2.0   e1"), 3, "two")), Catch::Contains("bad.qps:12:") && Catch::Contains("'two'"));
  CHECK_THAT(Error(std::string(text).replace(text.find("x3        l1"), 12, "x3        zz")), Catch::Contains("bad.qps:15:") && Catch::Contains("zz"));
  CHECK_THAT(Error(std::string(text).replace(text.find(" MI bnd"), 7, " XX bnd")), Catch::Contains("bad.qps:25:"));
  CHECK_THAT(Error(std::string(text).substr(0, text.find("ENDATA"))), Catch::Contains("ENDATA"));
  CHECK_THAT(Error("NAME x\nROWS\n G r\nENDATA\n"), Catch::Contains("objective"));
  CHECK_THROWS_WITH(ReadQpsFile("/nonexistent/nowhere.qps"), Catch::Contains("nowhere.qps"));
}
