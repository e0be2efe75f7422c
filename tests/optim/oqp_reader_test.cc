// The qpOASES sequence reader: sizes from dims.oqp, per-problem application, and errors naming
// the file and line.
#include <catch2/catch.hpp>

#include <fstream>

#include "stairplan/optim/oqp_reader.h"
#include "test_paths.h"

using namespace stairplan::optim;
using stairplan::testing::MakeTempDir;

namespace {

void Write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

std::string TinySequence() {
  const std::string dir = MakeTempDir("oqp");
  Write(dir + "/dims.oqp", "2\n2\n1\n0\n");
  Write(dir + "/H.oqp", "2 0\n0 2\n");
  Write(dir + "/A.oqp", "1 1\n");
  Write(dir + "/g.oqp", "-2 -2\n-4 0\n");
  Write(dir + "/lb.oqp", "-1e20 -1e20\n0 0\n");
  Write(dir + "/ub.oqp", "1e20 1e20\n1 1\n");
  Write(dir + "/lbA.oqp", "-1e20\n-1e20\n");
  Write(dir + "/ubA.oqp", "1\n1.5\n");
  Write(dir + "/x_opt.oqp", "0.5 0.5\n1 0.5\n");
  Write(dir + "/obj_opt.oqp", "-1.5\n-2.75\n");
  return dir;
}

}  // namespace

TEST_CASE("a sequence is read and applied problem by problem", "[oqp]") {
  const OqpSequence s = ReadOqpSequence(TinySequence());
  CHECK(s.num_qps == 2);
  CHECK(s.num_variables == 2);
  CHECK(s.num_constraints == 1);
  Program p = s.MakeProgram();
  CHECK(p.variable_lower()[0] == -kInf);  // 1e20 means no bound
  s.Apply(1, &p);
  CHECK(p.variable_upper()[1] == 1.0);
  CHECK(p.row_upper()[0] == 1.5);
  CHECK(p.linear_cost()[0] == -4.0);
  // The reference objective of problem 1 is what the program evaluates at x_opt.
  CHECK(p.Objective(s.x_opt.row(1).transpose()) == Approx(s.obj_opt[1]));
}

TEST_CASE("sequence errors name the file and line", "[oqp]") {
  const std::string dir = TinySequence();
  Write(dir + "/g.oqp", "-2 -2\n-4 zero\n");
  CHECK_THROWS_WITH(ReadOqpSequence(dir), Catch::Contains("g.oqp:2:") && Catch::Contains("zero"));
  Write(dir + "/g.oqp", "-2 -2\n-4\n");
  CHECK_THROWS_WITH(ReadOqpSequence(dir), Catch::Contains("g.oqp:2:") && Catch::Contains("expected 2 values"));
  CHECK_THROWS_WITH(ReadOqpSequence(dir + "/missing"), Catch::Contains("missing"));
}
