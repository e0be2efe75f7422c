#include "stairplan/kinematics/urdf_parse.h"

#include <map>
#include <mutex>
#include <stdexcept>
#include <string>

#include <console_bridge/console.h>
#include <tinyxml2.h>
#include <urdf_model/model.h>
#include <urdf_parser/urdf_parser.h>

#include "stairplan/kinematics/checked_xml.h"

namespace stairplan {
namespace {

// Collects console_bridge messages instead of printing them (the library never prints).
class CapturingHandler : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level < console_bridge::CONSOLE_BRIDGE_LOG_ERROR) return;
    if (!errors_.empty()) errors_ += "; ";
    errors_ += text;
  }
  const std::string& errors() const { return errors_; }

 private:
  std::string errors_;
};

// console_bridge's handler is process-global: one parse at a time swaps it.
std::mutex& ParseMutex() {
  static std::mutex mutex;
  return mutex;
}

using tinyxml2::XMLElement;

std::string Attribute(const XMLElement& element, const char* name) {
  const char* value = element.Attribute(name);
  return value ? value : "";
}

// urdfdom 3.0.1 knows no <capsule>: it then discards the link's whole collision list, which would
// make a foot or a leg link vanish from collision checks without a word. Refuse such links.
void RejectCapsules(const XMLElement& robot, const std::string& source) {
  for (const XMLElement* link = robot.FirstChildElement("link"); link; link = link->NextSiblingElement("link")) {
    for (const XMLElement* collision = link->FirstChildElement("collision"); collision;
         collision = collision->NextSiblingElement("collision")) {
      const XMLElement* geometry = collision->FirstChildElement("geometry");
      if (geometry && geometry->FirstChildElement("capsule")) {
        throw std::invalid_argument(source + ": <link name=\"" + Attribute(*link, "name") + "\"> line " +
                                    std::to_string(geometry->GetLineNum()) +
                                    ": <capsule> collision geometry is not supported (urdfdom 3.0.1 drops every "
                                    "collision of this link); use a cylinder and two spheres");
      }
    }
  }
}

// urdfdom accepts joints that close a loop away from the root (a link its own parent, a ring of
// links): every walk up a leg would then never end, and the loop's links, owning each other
// through shared pointers, leak even when urdfdom rejects the file for another reason (both found
// by the URDF fuzzer). So loops are refused before urdfdom sees the file: a link more parents away
// than there are joints is on one.
void RejectLoops(const XMLElement& robot, const std::string& source) {
  std::map<std::string, std::pair<std::string, std::string>> parent_of;  // child -> (parent, joint)
  for (const XMLElement* joint = robot.FirstChildElement("joint"); joint; joint = joint->NextSiblingElement("joint")) {
    const XMLElement* parent = joint->FirstChildElement("parent");
    const XMLElement* child = joint->FirstChildElement("child");
    if (!parent || !child) continue;  // urdfdom names what is missing
    parent_of.emplace(Attribute(*child, "link"), std::make_pair(Attribute(*parent, "link"), Attribute(*joint, "name")));
  }
  for (const auto& [start, unused] : parent_of) {
    std::string link = start;
    for (std::size_t depth = 0; parent_of.count(link) > 0; ++depth) {
      const auto& [parent, joint] = parent_of.at(link);
      if (depth > parent_of.size()) {
        throw std::invalid_argument(source + ": <joint name=\"" + joint + "\">: the joints form a loop through link '" +
                                    link + "'; a URDF must be a tree");
      }
      link = parent;
    }
  }
}

// urdfdom names the culprit as "joint [name]" or "link [name]"; turn that into the element.
std::string ElementOf(const std::string& message, const std::string& robot_name) {
  for (const char* kind : {"joint", "link"}) {
    const std::string key = std::string(kind) + " [";
    const std::size_t at = message.find(key);
    if (at == std::string::npos) continue;
    const std::size_t end = message.find(']', at);
    if (end == std::string::npos) continue;
    // "child link [x] of joint [y]": the joint is the element that is wrong.
    if (std::string(kind) == "link" && message.find("joint [") != std::string::npos) continue;
    return "<" + std::string(kind) + " name=\"" + message.substr(at + key.size(), end - at - key.size()) + "\">";
  }
  return "<robot name=\"" + robot_name + "\">";
}

}  // namespace

std::shared_ptr<urdf::ModelInterface> ParseUrdf(const std::string& xml, const std::string& source_name) {
  if (xml.find_first_not_of(" \t\r\n") == std::string::npos) {
    throw std::invalid_argument(source_name + ": <robot>: the URDF is empty");
  }
  const CheckedXml checked(xml, source_name);
  const XMLElement& robot = checked.root();
  if (std::string(robot.Name()) != "robot") throw std::invalid_argument(source_name + ": <robot>: no <robot> root element");
  RejectCapsules(robot, source_name);
  RejectLoops(robot, source_name);
  // urdfdom parses with TinyXML 2.6, which must never see the file's own bytes (issue #28).
  const std::string canonical = checked.Canonical();

  std::lock_guard<std::mutex> lock(ParseMutex());
  CapturingHandler handler;
  console_bridge::OutputHandler* previous = console_bridge::getOutputHandler();
  console_bridge::useOutputHandler(&handler);
  urdf::ModelInterfaceSharedPtr parsed;
  try {
    parsed = urdf::parseURDF(canonical);
  } catch (...) {
    console_bridge::useOutputHandler(previous);
    throw;
  }
  console_bridge::useOutputHandler(previous);
  if (!parsed || !parsed->getRoot()) {
    const std::string why = handler.errors().empty() ? "not a valid URDF" : handler.errors();
    throw std::invalid_argument(source_name + ": " + ElementOf(why, Attribute(robot, "name")) + ": " + why);
  }
  return parsed;
}

}  // namespace stairplan
