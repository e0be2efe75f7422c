// Parsing URDF text with urdfdom so that every failure becomes an exception naming the source and
// the element: urdfdom reports problems only through console_bridge log lines and a null model,
// it silently drops the collision list of a link with a <capsule>, and its XML parser (TinyXML 2.6)
// must not read untrusted bytes (checked_xml.h).
#pragma once

#include <memory>
#include <string>

namespace urdf {
class ModelInterface;
}

namespace stairplan {

/// Checks `xml` (CheckedXml: UTF-8, well-formed, with its line on failure), then parses its
/// canonical text with urdfdom, never `xml` itself. Throws std::invalid_argument starting with
/// `source_name` and naming the line or the offending element: text that is not UTF-8 or not
/// well-formed XML, a link with a <capsule> collision (urdfdom 3.0.1 would drop all of that link's
/// collisions), joints forming a loop, or urdfdom's own error text (e.g. a joint naming a missing
/// link). Nothing is printed: console_bridge output is captured while parsing.
std::shared_ptr<urdf::ModelInterface> ParseUrdf(const std::string& xml, const std::string& source_name);

}  // namespace stairplan
