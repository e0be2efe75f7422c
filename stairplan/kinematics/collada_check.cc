#include "stairplan/kinematics/collada_check.h"

#include <cstdint>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

#include <tinyxml2.h>

namespace stairplan {
namespace {

[[noreturn]] void Refuse(const std::string& path, int line, const std::string& reason) {
  throw std::invalid_argument(path + ": line " + std::to_string(line) + ": " + reason);
}

bool IsSpace(char ch) { return ch == ' ' || ch == '\t' || ch == '\r' || ch == '\n'; }
bool IsDigit(char ch) { return ch >= '0' && ch <= '9'; }

// Whitespace-separated integers, each an optional '-' and at least one digit.
bool IsIntegerList(std::string_view text) {
  std::size_t at = 0;
  while (at < text.size()) {
    if (IsSpace(text[at])) {
      ++at;
      continue;
    }
    if (text[at] == '-') ++at;
    const std::size_t digits = at;
    while (at < text.size() && IsDigit(text[at])) ++at;
    if (at == digits || (at < text.size() && !IsSpace(text[at]))) return false;
  }
  return true;
}

bool IsIndexList(std::string_view name) { return name == "p" || name == "vcount" || name == "v" || name == "h"; }

// Up to 24 bytes of `value`, anything but printable ASCII as '?': safe to print in a message.
std::string Shown(std::string_view value) {
  std::string out(value.substr(0, 24));
  for (char& ch : out) ch = (ch >= 0x20 && ch < 0x7F) ? ch : '?';
  return out;
}

// A whole number no larger than `limit`.
bool IsBoundedCount(std::string_view value, std::uintmax_t limit) {
  if (value.empty() || value.size() > 20) return false;
  std::uintmax_t n = 0;
  for (const char ch : value) {
    if (!IsDigit(ch)) return false;
    n = n * 10 + static_cast<std::uintmax_t>(ch - '0');
  }
  return n <= limit;
}

void CheckElement(const tinyxml2::XMLElement& element, const std::string& path, std::uintmax_t file_size) {
  const std::string_view name = element.Name();
  for (const char* attribute : {"count", "stride", "offset"}) {
    const char* value = element.Attribute(attribute);
    if (value != nullptr && !IsBoundedCount(value, file_size)) {
      Refuse(path, element.GetLineNum(),
             "<" + std::string(name) + " " + attribute + "=\"" + Shown(value) +
                 "\"> is not a whole number the file's " + std::to_string(file_size) + " bytes could hold");
    }
  }
  // Without a count assimp reads an array as empty and then dereferences its missing values.
  if (name.size() > 6 && name.substr(name.size() - 6) == "_array" && element.Attribute("count") == nullptr) {
    Refuse(path, element.GetLineNum(), "<" + std::string(name) + "> has no count");
  }
  if (IsIndexList(name)) {
    for (const tinyxml2::XMLNode* child = element.FirstChild(); child; child = child->NextSibling()) {
      const tinyxml2::XMLText* text = child->ToText();
      if (text != nullptr && !IsIntegerList(text->Value())) {
        Refuse(path, text->GetLineNum(), "<" + std::string(name) + "> holds something other than integer indices");
      }
    }
  }
  for (const tinyxml2::XMLElement* child = element.FirstChildElement(); child; child = child->NextSiblingElement()) {
    CheckElement(*child, path, file_size);
  }
}

}  // namespace

void CheckColladaFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  tinyxml2::XMLDocument document;
  if (document.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS) {
    Refuse(path, document.ErrorLineNum(), std::string("not well-formed COLLADA XML (") + document.ErrorName() + ")");
  }
  const tinyxml2::XMLElement* root = document.RootElement();
  if (root == nullptr) Refuse(path, 1, "no COLLADA element");
  CheckElement(*root, path, text.size());
}

}  // namespace stairplan
