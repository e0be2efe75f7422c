// CheckedXml (issue #28): robot files are checked by tinyxml2 and urdfdom reads only their canonical
// ASCII text. That text must give urdfdom exactly the model the file itself gives, for every robot
// we ship or test with, and bad bytes must be refused with the file and the line.
#include <catch2/catch.hpp>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <tinyxml2.h>
#include <urdf_model/model.h>
#include <urdf_parser/urdf_parser.h>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/kinematics/checked_xml.h"
#include "test_paths.h"

namespace checked_xml_test {

namespace fs = std::filesystem;

void DumpPose(std::ostream& out, const urdf::Pose& p) {
  double x, y, z, w;
  p.rotation.getQuaternion(x, y, z, w);
  out << " pose " << p.position.x << ' ' << p.position.y << ' ' << p.position.z << " q " << x << ' ' << y << ' '
      << z << ' ' << w;
}

void DumpGeometry(std::ostream& out, const urdf::GeometrySharedPtr& g) {
  if (!g) {
    out << " no-geometry";
    return;
  }
  out << " geometry " << g->type;
  if (auto s = std::dynamic_pointer_cast<urdf::Sphere>(g)) out << " r " << s->radius;
  if (auto b = std::dynamic_pointer_cast<urdf::Box>(g)) out << " dim " << b->dim.x << ' ' << b->dim.y << ' ' << b->dim.z;
  if (auto c = std::dynamic_pointer_cast<urdf::Cylinder>(g)) out << " r " << c->radius << " l " << c->length;
  if (auto m = std::dynamic_pointer_cast<urdf::Mesh>(g)) {
    out << " mesh '" << m->filename << "' " << m->scale.x << ' ' << m->scale.y << ' ' << m->scale.z;
  }
}

void DumpMaterial(std::ostream& out, const urdf::MaterialSharedPtr& m) {
  if (!m) return;
  out << " material '" << m->name << "' '" << m->texture_filename << "' " << m->color.r << ' ' << m->color.g << ' '
      << m->color.b << ' ' << m->color.a;
}

// Everything urdfdom read, in a fixed order and at full precision: equal dumps, equal models.
std::string DumpModel(const urdf::ModelInterface& model) {
  std::ostringstream out;
  out.precision(17);
  out << "robot '" << model.getName() << "' root '" << (model.getRoot() ? model.getRoot()->name : "") << "'\n";
  for (const auto& [name, material] : model.materials_) {
    DumpMaterial(out, material);
    out << '\n';
  }
  for (const auto& [name, link] : model.links_) {
    out << "link '" << name << "' parent-joint '" << (link->parent_joint ? link->parent_joint->name : "") << "'";
    if (link->inertial) {
      const urdf::Inertial& i = *link->inertial;
      DumpPose(out, i.origin);
      out << " mass " << i.mass << " I " << i.ixx << ' ' << i.ixy << ' ' << i.ixz << ' ' << i.iyy << ' ' << i.iyz << ' '
          << i.izz;
    }
    out << '\n';
    for (const auto& v : link->visual_array) {
      out << "  visual '" << v->name << "'";
      DumpPose(out, v->origin);
      DumpGeometry(out, v->geometry);
      out << " material-name '" << v->material_name << "'";
      DumpMaterial(out, v->material);
      out << '\n';
    }
    for (const auto& c : link->collision_array) {
      out << "  collision '" << c->name << "'";
      DumpPose(out, c->origin);
      DumpGeometry(out, c->geometry);
      out << '\n';
    }
  }
  for (const auto& [name, j] : model.joints_) {
    out << "joint '" << name << "' type " << j->type << " '" << j->parent_link_name << "' -> '" << j->child_link_name
        << "' axis " << j->axis.x << ' ' << j->axis.y << ' ' << j->axis.z;
    DumpPose(out, j->parent_to_joint_origin_transform);
    if (j->limits) {
      out << " limits " << j->limits->lower << ' ' << j->limits->upper << ' ' << j->limits->effort << ' '
          << j->limits->velocity;
    }
    if (j->dynamics) out << " dynamics " << j->dynamics->damping << ' ' << j->dynamics->friction;
    if (j->safety) {
      out << " safety " << j->safety->soft_lower_limit << ' ' << j->safety->soft_upper_limit << ' '
          << j->safety->k_position << ' ' << j->safety->k_velocity;
    }
    if (j->calibration) out << " calibration " << (j->calibration->rising ? *j->calibration->rising : -1.0);
    if (j->mimic) out << " mimic '" << j->mimic->joint_name << "' " << j->mimic->multiplier << ' ' << j->mimic->offset;
    out << '\n';
  }
  return out.str();
}

struct RobotText {
  std::string label, text;
};

// stairbot and every URDF under ../shared/data/robots.
std::vector<RobotText> AllRobotTexts() {
  std::vector<RobotText> robots = {{"stairbot", stairplan::BuiltinRobotUrdf()}};
  const std::string dir = stairplan::testing::SharedPath("data/robots");
  if (dir.empty()) {
    WARN("../shared is absent: only stairbot is checked");
    return robots;
  }
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (entry.path().extension() == ".urdf") {
      robots.push_back({entry.path().string(), stairplan::testing::ReadFile(entry.path().string())});
    }
  }
  return robots;
}

std::string ErrorOf(const std::string& text, const std::string& source) {
  try {
    stairplan::CheckedXml checked(text, source);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "accepted";
}

std::string CanonicalOf(const std::string& text) { return stairplan::CheckedXml(text, "t.urdf").Canonical(); }

}  // namespace checked_xml_test


TEST_CASE("the canonical text gives urdfdom the same model as every robot file itself", "[checked_xml]") {
  const std::vector<checked_xml_test::RobotText> robots = checked_xml_test::AllRobotTexts();
  CHECK(robots.size() >= (stairplan::testing::SharedDir().empty() ? 1u : 7u));
  for (const checked_xml_test::RobotText& robot : robots) {
    INFO(robot.label);
    const std::string canonical = checked_xml_test::CanonicalOf(robot.text);
    for (const char ch : canonical) {
      const bool ascii = ch == '\n' || (ch >= 0x20 && ch < 0x7F);
      if (!ascii) FAIL("a byte outside printable ASCII: " << static_cast<int>(static_cast<unsigned char>(ch)));
    }
    // The file itself is trusted test data here: the comparison needs urdfdom to read it directly.
    const auto original = urdf::parseURDF(robot.text);
    const auto rewritten = urdf::parseURDF(canonical);
    REQUIRE(original);
    REQUIRE(rewritten);
    CHECK(checked_xml_test::DumpModel(*rewritten) == checked_xml_test::DumpModel(*original));
    CHECK(checked_xml_test::CanonicalOf(canonical) == canonical);
  }
}

TEST_CASE("references, non-ASCII text and whitespace survive the canonical text", "[checked_xml]") {
  const std::string text =
      "\xEF\xBB\xBF<?xml version='1.0' encoding='utf-8'?>\n<!DOCTYPE robot>\n<!-- dropped -->\n"
      "<robot name=\"a&amp;b&#x41;&#66;&lt;&quot;'\xE6\xB7\xB1\xF0\x9F\xA6\xBE\" v='tab\there'>"
      "<material name=\"\xE9\xBB\x91\"/><t>&#32;</t><u>x <![CDATA[<&>]]> y</u><!-- c --></robot>";
  const stairplan::CheckedXml checked(text, "t.urdf");
  CHECK(std::string(checked.root().Attribute("name")) == "a&bAB<\"'\xE6\xB7\xB1\xF0\x9F\xA6\xBE");
  const std::string canonical = checked.Canonical();
  CHECK(canonical ==
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        "<robot name=\"a&amp;bAB&lt;&quot;&apos;&#x6DF1;&#x1F9BE;\" v=\"tab&#x9;here\"><material name=\"&#x9ED1;\"/>"
        "<t>&#x20;</t><u>x &lt;&amp;&gt; y</u></robot>\n");
  CHECK(checked_xml_test::CanonicalOf(canonical) == canonical);
}

TEST_CASE("bytes that are not UTF-8 XML, and malformed XML, are refused with the file and the line", "[checked_xml]") {
  struct Bad {
    std::string text, line, reason;
  };
  const std::string head = "<robot name=\"r\">\n<link name=\"base\"/>\n";
  const std::vector<Bad> cases = {
      {head + "<link name=\"\xC6\xC6\"/>\n</robot>\n", "line 3", "not UTF-8"},
      {head + "</robot>\n\xE6\xB7", "line 4", "ends inside a multi-byte character"},
      {head + "<link name=\"\xC0\x80\"/>\n</robot>\n", "line 3", "not UTF-8"},          // overlong NUL
      {head + "<link name=\"\xED\xA0\x80\"/>\n</robot>\n", "line 3", "not UTF-8"},      // surrogate
      {head + "<link name=\"\xF4\x90\x80\x80\"/>\n</robot>\n", "line 3", "not UTF-8"},  // above U+10FFFF
      {head + "<link name=\"a\x01\"/>\n</robot>\n", "line 3", "U+0001"},
      {head + std::string("<link name=\"a\0\"/>\n</robot>\n", 23), "line 3", "U+0000"},
      {head + "<link name=\"x\">\n", "line 3", "<link> is never closed"},
      {head + "<visual>\n</link>\n</robot>\n", "line 4", "</link> closes <visual> (opened on line 3)"},
      {head + "</robot>\n</robot>\n", "line 4", "</robot> closes no element"},
      {head + "<link name=\"a\" name=\"b\"/>\n</robot>\n", "line 3", "attribute"},
      {head + "</robot>\n<robot/>\n", "line 4", "second root element"},
      {head + "<link name=\"a&foo;\"/>\n</robot>\n", "line 3", "'&foo;'"},
      {head + "<link name=\"a&#0;b\"/>\n</robot>\n", "line 3", "'&#0;'"},
      {head + "<link name=\"a&#xD800;b\"/>\n</robot>\n", "line 3", "'&#xD800;'"},
      {head + "<link name=\"a&#x110000;\"/>\n</robot>\n", "line 3", "'&#x110000;'"},
      {head + "<link name=\"a\n&\"/>\n</robot>\n", "line 4", "'&' in the attribute 'name' of <link>"},
      {head + "<link name=\"a<b\"/>\n</robot>\n", "line 3", "'<' in the attribute 'name' of <link>"},
      {head + "<l\xC3\xA9 name=\"a\"/>\n</robot>\n", "line 3", "not an ASCII XML name"},
      {head + "<link n\xC3\xA9=\"a\"/>\n</robot>\n", "line 3", "not an ASCII XML name"},
      {"<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?>\n<robot name=\"\xC3\xA9\"/>\n", "line 1", "ISO-8859-1"},
      {head + std::string(200, ' ') + std::string(120, '<') + "\n", "line 3", "is never ended"},
  };
  for (const Bad& c : cases) {
    INFO(c.text);
    const std::string error = checked_xml_test::ErrorOf(c.text, "bad.urdf");
    CHECK_THAT(error, Catch::StartsWith("bad.urdf: " + c.line) && Catch::Contains(c.reason));
  }
  // Pure ASCII under a Latin-1 declaration is the same text in UTF-8: accepted.
  CHECK(checked_xml_test::ErrorOf("<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?>\n<robot name=\"r\"/>\n", "ok.urdf") == "accepted");
}

TEST_CASE("elements nested past tinyxml2's limit are refused, not recursed into", "[checked_xml]") {
  std::string deep = "<robot>\n";
  for (int i = 0; i < 200; ++i) deep += "<a>";
  for (int i = 0; i < 200; ++i) deep += "</a>";
  deep += "\n</robot>\n";
  CHECK_THAT(checked_xml_test::ErrorOf(deep, "deep.urdf"), Catch::StartsWith("deep.urdf: line 2") && Catch::Contains("nested deeper"));
}
