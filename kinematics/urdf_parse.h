// Parsing URDF text with urdfdom so that every failure becomes an exception naming the source and
// the element: urdfdom reports problems only through console_bridge log lines and a null model,
// and it silently drops the collision list of a link with a <capsule>.
#pragma once

#include <memory>
#include <string>

namespace urdf {
class ModelInterface;
}

namespace stairplan {

/// Parses `xml` with urdfdom. Throws std::invalid_argument starting with `source_name` and naming
/// the offending element: malformed XML (with its line), a link with a <capsule> collision (urdfdom
/// 3.0.1 would drop all of that link's collisions), or urdfdom's own error text (e.g. a joint naming
/// a missing link). Nothing is printed: console_bridge output is captured while parsing.
std::shared_ptr<urdf::ModelInterface> ParseUrdf(const std::string& xml, const std::string& source_name);

}  // namespace stairplan
