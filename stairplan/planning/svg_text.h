// Text placed in an SVG we write (titles, labels, violation details): one escaping rule for every
// SVG writer.
#pragma once

#include <string>

namespace stairplan {

/// `text` with <, > and & as entities, for SVG character data.
inline std::string SvgEscaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else out += c;
  }
  return out;
}

}  // namespace stairplan
