#include "stairplan/kinematics/checked_xml.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <tinyxml2.h>

namespace stairplan {
namespace {

enum class Utf8Status { kOk, kBadByte, kTruncated };

// Decodes the UTF-8 character at text[at] into `c` and moves `at` past it. Overlong forms,
// surrogates and code points above U+10FFFF are bad bytes (RFC 3629).
Utf8Status NextChar(std::string_view text, std::size_t& at, char32_t& c) {
  const auto byte = [&](std::size_t i) { return static_cast<std::uint8_t>(text[i]); };
  const std::uint8_t lead = byte(at);
  if (lead < 0x80) {
    c = lead;
    ++at;
    return Utf8Status::kOk;
  }
  std::size_t length = 0;
  std::uint8_t low = 0x80, high = 0xBF;  // the range of the second byte
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2;
    c = lead & 0x1Fu;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3;
    c = lead & 0x0Fu;
    if (lead == 0xE0) low = 0xA0;
    if (lead == 0xED) high = 0x9F;
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4;
    c = lead & 0x07u;
    if (lead == 0xF0) low = 0x90;
    if (lead == 0xF4) high = 0x8F;
  } else {
    return Utf8Status::kBadByte;
  }
  for (std::size_t i = 1; i < length; ++i) {
    if (at + i >= text.size()) return Utf8Status::kTruncated;
    const std::uint8_t next = byte(at + i);
    if (next < (i == 1 ? low : 0x80) || next > (i == 1 ? high : 0xBF)) return Utf8Status::kBadByte;
    c = (c << 6) | (next & 0x3Fu);
  }
  at += length;
  return Utf8Status::kOk;
}

// XML 1.0's Char production.
bool IsXmlChar(char32_t c) {
  return c == 0x9 || c == 0xA || c == 0xD || (c >= 0x20 && c <= 0xD7FF) || (c >= 0xE000 && c <= 0xFFFD) ||
         (c >= 0x10000 && c <= 0x10FFFF);
}

void AppendUtf8(char32_t c, std::string& out) {
  if (c < 0x80) {
    out += static_cast<char>(c);
  } else if (c < 0x800) {
    out += static_cast<char>(0xC0 | (c >> 6));
    out += static_cast<char>(0x80 | (c & 0x3F));
  } else if (c < 0x10000) {
    out += static_cast<char>(0xE0 | (c >> 12));
    out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (c & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (c >> 18));
    out += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (c & 0x3F));
  }
}

std::string Hex(std::uint32_t value, int digits) {
  char buffer[16];
  std::snprintf(buffer, sizeof(buffer), "%0*X", digits, static_cast<unsigned>(value));
  return buffer;
}

// `bytes` with everything but printable ASCII as \xHH, shortened: safe to print on any terminal.
std::string Printable(std::string_view bytes, std::size_t limit = 80) {
  std::string out;
  for (const char ch : bytes.substr(0, limit)) {
    const auto b = static_cast<std::uint8_t>(ch);
    out += (b >= 0x20 && b < 0x7F) ? std::string(1, ch) : "\\x" + Hex(b, 2);
  }
  if (bytes.size() > limit) out += "...";
  return out;
}

// The text of line `row` (1-based), trimmed, to show where the file breaks.
std::string LineText(std::string_view text, int row) {
  std::size_t begin = 0;
  for (int r = 1; r < row && begin != std::string_view::npos; ++r) {
    begin = text.find('\n', begin);
    if (begin != std::string_view::npos) ++begin;
  }
  if (begin == std::string_view::npos || begin > text.size()) return "";
  std::string_view line = text.substr(begin, text.find('\n', begin) - begin);
  const std::size_t first = line.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return "";
  line = line.substr(first, line.find_last_not_of(" \t\r") + 1 - first);
  return Printable(line);
}

// Every message: "<source>: line N (<line text>): <reason>".
[[noreturn]] void Fail(const std::string& source, std::string_view text, int line, const std::string& reason) {
  std::string where = source;
  if (line > 0) {
    where += ": line " + std::to_string(line);
    const std::string excerpt = LineText(text, line);
    if (!excerpt.empty()) where += " (" + excerpt + ")";
  }
  throw std::invalid_argument(where + ": " + reason);
}

// The bytes must be UTF-8 and every character an XML character, before tinyxml2 (which checks
// neither) sees them. Returns whether there is any non-ASCII byte.
bool CheckCharacters(const std::string& text, const std::string& source) {
  int line = 1;
  std::size_t line_start = 0;
  bool non_ascii = false;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t start = at;
    char32_t c = 0;
    const auto column = [&] { return "column " + std::to_string(start - line_start + 1); };
    switch (NextChar(text, at, c)) {
      case Utf8Status::kOk:
        break;
      case Utf8Status::kTruncated:
        Fail(source, text, line,
             "not UTF-8: the file ends inside a multi-byte character (" + Printable(std::string_view(text).substr(start)) +
                 " at " + column() + ")");
      case Utf8Status::kBadByte:
        Fail(source, text, line,
             "not UTF-8: byte 0x" + Hex(static_cast<std::uint8_t>(text[start]), 2) + " at " + column() +
                 " does not start a valid character (robot files must be UTF-8)");
    }
    if (!IsXmlChar(c)) {
      Fail(source, text, line, "character U+" + Hex(c, 4) + " at " + column() + " is not allowed in XML");
    }
    non_ascii = non_ascii || c >= 0x80;
    if (c == '\n') {
      ++line;
      line_start = at;
    }
  }
  return non_ascii;
}

// The element a tinyxml2 error message names ("... XMLElement name=link"), or "".
std::string ElementInError(const tinyxml2::XMLDocument& document) {
  const std::string message = document.ErrorStr();
  const std::string key = "XMLElement name=";
  const std::size_t at = message.find(key);
  return at == std::string::npos ? "" : " <" + Printable(message.substr(at + key.size())) + ">";
}

int LineAt(std::string_view text, std::size_t offset) {
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(offset), '\n'));
}

// What a walk over the tags finds first: an end tag that does not close the open element, a tag
// that never ends, or the end of the file with elements still open. tinyxml2 reports only the line
// of the open element, and it ignores an end tag after the root element.
struct TagProblem {
  enum class Kind { kStrayEndTag, kUnterminatedTag, kUnclosedElement } kind;
  std::size_t at = 0;         ///< offset of the '<' of the offending tag (the open element for kUnclosedElement)
  std::string_view name;      ///< the offending tag's name
  std::string_view open;      ///< kStrayEndTag: the element it should have closed ("" at the top level)
  std::size_t open_at = 0;
};

std::optional<TagProblem> FindTagProblem(std::string_view text) {
  using Kind = TagProblem::Kind;
  std::vector<std::pair<std::string_view, std::size_t>> open;  // name, offset
  const auto skip_past = [&](std::size_t from, std::string_view end) {
    const std::size_t at = text.find(end, from);
    return at == std::string_view::npos ? at : at + end.size();
  };
  for (std::size_t at = text.find('<'); at != std::string_view::npos; at = text.find('<', at)) {
    const std::string_view rest = text.substr(at);
    std::size_t next = std::string_view::npos;
    if (rest.substr(0, 4) == "<!--") {
      next = skip_past(at + 4, "-->");
    } else if (rest.substr(0, 9) == "<![CDATA[") {
      next = skip_past(at + 9, "]]>");
    } else if (rest.substr(0, 2) == "<?") {
      next = skip_past(at + 2, "?>");
    } else if (rest.substr(0, 2) == "<!") {
      next = skip_past(at + 2, ">");
    } else {
      const bool closing = rest.substr(0, 2) == "</";
      const std::size_t name_begin = at + (closing ? 2 : 1);
      const std::size_t name_end = std::min(text.find_first_of(" \t\r\n/>", name_begin), text.size());
      const std::string_view name = text.substr(name_begin, name_end - name_begin);
      char quote = 0;
      std::size_t end = name_end;
      for (; end < text.size() && (quote != 0 || text[end] != '>'); ++end) {
        if (quote == 0 && (text[end] == '"' || text[end] == '\'')) {
          quote = text[end];
        } else if (text[end] == quote) {
          quote = 0;
        }
      }
      if (end == text.size()) return TagProblem{Kind::kUnterminatedTag, at, name, {}, 0};
      if (closing && (open.empty() || open.back().first != name)) {
        if (open.empty()) return TagProblem{Kind::kStrayEndTag, at, name, {}, 0};
        return TagProblem{Kind::kStrayEndTag, at, name, open.back().first, open.back().second};
      }
      if (closing) {
        open.pop_back();
      } else if (text[end - 1] != '/') {
        open.emplace_back(name, at);
      }
      next = end + 1;
    }
    if (next == std::string_view::npos) return std::nullopt;  // tinyxml2 names the open comment or section
    at = next;
  }
  if (open.empty()) return std::nullopt;
  return TagProblem{Kind::kUnclosedElement, open.back().second, open.back().first, {}, 0};
}

// The line and the reason for a tag problem.
std::pair<int, std::string> Describe(const TagProblem& problem, std::string_view text) {
  const int line = LineAt(text, problem.at);
  const std::string name = Printable(problem.name);
  switch (problem.kind) {
    case TagProblem::Kind::kUnclosedElement:
      return {line, "the element <" + name + "> is never closed"};
    case TagProblem::Kind::kUnterminatedTag:
      return {line, "a tag <" + name + " is never ended with '>'"};
    case TagProblem::Kind::kStrayEndTag:
      break;
  }
  if (problem.open.empty()) return {line, "</" + name + "> closes no element"};
  return {line, "</" + name + "> closes <" + Printable(problem.open) + "> (opened on line " +
                    std::to_string(LineAt(text, problem.open_at)) + ")"};
}

// The line and the reason of a tinyxml2 parse error; the walk over the tags, where it finds the
// problem, names the tags involved.
std::pair<int, std::string> ParseError(const tinyxml2::XMLDocument& document, std::string_view text,
                                       const std::optional<TagProblem>& tags) {
  const std::string element = ElementInError(document);
  const int line = document.ErrorLineNum();
  switch (document.ErrorID()) {
    case tinyxml2::XML_ERROR_PARSING:
      if (tags) return Describe(*tags, text);
      return {line, "an element opened on this line is never closed, or a tag in it is not valid XML"};
    case tinyxml2::XML_ERROR_MISMATCHED_ELEMENT:
      if (tags) return Describe(*tags, text);
      return {line, "the element" + element + " is closed by a tag of another name"};
    case tinyxml2::XML_ERROR_PARSING_ELEMENT:
      return {line, "the tag" + element + " is not valid XML"};
    case tinyxml2::XML_ERROR_PARSING_ATTRIBUTE:
      return {line, "an attribute of" + element + " is not valid (unquoted, unterminated or repeated)"};
    case tinyxml2::XML_ERROR_PARSING_TEXT:
      return {line, "text outside the root element, or text that runs to the end of the file"};
    case tinyxml2::XML_ERROR_PARSING_CDATA:
      return {line, "a CDATA section is never closed"};
    case tinyxml2::XML_ERROR_PARSING_COMMENT:
      return {line, "a comment is never closed"};
    case tinyxml2::XML_ERROR_PARSING_DECLARATION:
      return {line, "an <?...?> declaration is not valid here"};
    case tinyxml2::XML_ERROR_PARSING_UNKNOWN:
      return {line, "a <!...> construct is never closed"};
    case tinyxml2::XML_ELEMENT_DEPTH_EXCEEDED:
      return {line, "elements are nested deeper than " + std::to_string(TINYXML2_MAX_ELEMENT_DEPTH)};
    case tinyxml2::XML_ERROR_EMPTY_DOCUMENT:
      return {line, "there is no element"};
    default:
      return {line, document.ErrorName()};
  }
}

// An ASCII XML name, so that every XML parser, TinyXML 2.6 included, reads it the same way.
bool IsAsciiName(std::string_view name) {
  const auto letter = [](char ch) { return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || ch == '_'; };
  if (name.empty() || !letter(name[0])) return false;
  for (const char ch : name) {
    if (!letter(ch) && !(ch >= '0' && ch <= '9') && ch != '-' && ch != '.' && ch != ':') return false;
  }
  return true;
}

// The character `reference` (the text between '&' and ';') stands for, or 0 when it stands for
// none: one of XML's five entities or a character reference to an XML character.
char32_t ReferencedChar(std::string_view reference) {
  if (reference == "amp") return '&';
  if (reference == "lt") return '<';
  if (reference == "gt") return '>';
  if (reference == "quot") return '"';
  if (reference == "apos") return '\'';
  if (reference.size() < 2 || reference[0] != '#') return 0;
  const bool hex = reference[1] == 'x';
  const std::string_view digits = reference.substr(hex ? 2 : 1);
  if (digits.empty()) return 0;
  std::uint32_t value = 0;
  for (const char ch : digits) {
    int digit = -1;
    if (ch >= '0' && ch <= '9') digit = ch - '0';
    if (hex && ch >= 'a' && ch <= 'f') digit = ch - 'a' + 10;
    if (hex && ch >= 'A' && ch <= 'F') digit = ch - 'A' + 10;
    if (digit < 0) return 0;
    value = value * (hex ? 16 : 10) + static_cast<std::uint32_t>(digit);
    if (value > 0x10FFFF) return 0;
  }
  return IsXmlChar(value) ? value : 0;
}

// Where a value sits in the file, for messages about a reference inside it.
struct ValueSite {
  const std::string& source;
  std::string_view text;
  int line;           ///< the line the value starts on
  std::string what;   ///< e.g. "the attribute 'name' of <link>"
  bool attribute;
};

// `raw` with its references replaced by the characters they stand for (tinyxml2 parses with
// entity processing off so that a bad reference is an error here, not a silent truncation).
std::string DecodeReferences(std::string_view raw, const ValueSite& site) {
  std::string out;
  out.reserve(raw.size());
  int line = site.line;
  for (std::size_t at = 0; at < raw.size(); ++at) {
    if (raw[at] == '\n') ++line;
    if (site.attribute && raw[at] == '<') Fail(site.source, site.text, line, "'<' in " + site.what + " must be written &lt;");
    if (raw[at] != '&') {
      out += raw[at];
      continue;
    }
    const std::size_t end = raw.find(';', at);
    const std::string_view reference = raw.substr(at + 1, end == std::string_view::npos ? 0 : end - at - 1);
    const char32_t c = end == std::string_view::npos || end - at > 12 ? 0 : ReferencedChar(reference);
    if (c == 0) {
      Fail(site.source, site.text, line,
           "'" + Printable(raw.substr(at, end == std::string_view::npos ? 12 : end - at + 1), 16) + "' in " + site.what +
               " is neither one of XML's five entities nor a reference to an XML character (write & as &amp;)");
    }
    AppendUtf8(c, out);
    at = end;
  }
  return out;
}

// Checks the names below `element` and replaces every reference in its attributes and text.
void CheckAndDecode(tinyxml2::XMLElement& element, const std::string& source, std::string_view text) {
  const std::string name = element.Name();
  if (!IsAsciiName(name)) {
    Fail(source, text, element.GetLineNum(), "the element name '" + Printable(name) + "' is not an ASCII XML name");
  }
  for (const tinyxml2::XMLAttribute* a = element.FirstAttribute(); a; a = a->Next()) {
    if (!IsAsciiName(a->Name())) {
      Fail(source, text, a->GetLineNum(),
           "the attribute name '" + Printable(a->Name()) + "' of <" + name + "> is not an ASCII XML name");
    }
    const ValueSite site{source, text, a->GetLineNum(), "the attribute '" + std::string(a->Name()) + "' of <" + name + ">", true};
    // Replaces the value in place: the attribute keeps its place in the list.
    element.SetAttribute(a->Name(), DecodeReferences(a->Value(), site).c_str());
  }
  for (tinyxml2::XMLNode* child = element.FirstChild(); child; child = child->NextSibling()) {
    if (tinyxml2::XMLElement* e = child->ToElement()) {
      CheckAndDecode(*e, source, text);
    } else if (tinyxml2::XMLText* t = child->ToText(); t && !t->CData()) {
      const ValueSite site{source, text, t->GetLineNum(), "the text of <" + name + ">", false};
      t->SetValue(DecodeReferences(t->Value(), site).c_str());
    }
  }
}

// The encoding the XML declaration names ("" when none).
std::string DeclaredEncoding(const tinyxml2::XMLDeclaration& declaration) {
  const std::string value = declaration.Value();
  std::size_t at = value.find("encoding");
  if (at == std::string::npos) return "";
  at = value.find_first_of("'\"", at);
  if (at == std::string::npos) return "";
  const std::size_t end = value.find(value[at], at + 1);
  return value.substr(at + 1, end == std::string::npos ? std::string::npos : end - at - 1);
}

bool IsUtf8Name(std::string encoding) {
  for (char& ch : encoding) ch = static_cast<char>(ch >= 'A' && ch <= 'Z' ? ch - 'A' + 'a' : ch);
  return encoding == "utf-8" || encoding == "utf8";
}

// The one root element; a second one, or a non-UTF-8 declaration over non-ASCII bytes, is refused.
tinyxml2::XMLElement& RootOf(tinyxml2::XMLDocument& document, const std::string& text, const std::string& source,
                             bool non_ascii) {
  tinyxml2::XMLElement* root = nullptr;
  for (tinyxml2::XMLNode* node = document.FirstChild(); node; node = node->NextSibling()) {
    if (const tinyxml2::XMLDeclaration* declaration = node->ToDeclaration()) {
      const std::string encoding = DeclaredEncoding(*declaration);
      if (non_ascii && !encoding.empty() && !IsUtf8Name(encoding)) {
        Fail(source, text, node->GetLineNum(),
             "the file declares encoding '" + Printable(encoding) +
                 "' and has non-ASCII bytes; robot files are read as UTF-8 (convert it to UTF-8)");
      }
    } else if (tinyxml2::XMLElement* element = node->ToElement()) {
      if (root) Fail(source, text, node->GetLineNum(), "malformed XML: a second root element <" + Printable(element->Name()) + ">");
      root = element;
    }
  }
  if (!root) Fail(source, text, 0, "malformed XML: there is no element");
  return *root;
}

// Writes `value` as XML character data that only printable ASCII spells.
void AppendEscaped(std::string_view value, bool whitespace_as_references, std::string& out) {
  for (std::size_t at = 0; at < value.size();) {
    char32_t c = 0;
    if (NextChar(value, at, c) != Utf8Status::kOk) throw std::invalid_argument("XML text that is not UTF-8");
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        if (c > 0x20 && c < 0x7F) {
          out += static_cast<char>(c);
        } else if (c == ' ' && !whitespace_as_references) {
          out += ' ';
        } else {
          out += "&#x" + Hex(c, 1) + ";";
        }
    }
  }
}

bool IsWhitespace(std::string_view text) { return text.find_first_not_of(" \t\r\n") == std::string_view::npos; }

void AppendText(const std::string& run, std::string& out) {
  // A parser drops text that is only whitespace before an element; as references it stays.
  AppendEscaped(run, IsWhitespace(run), out);
}

void AppendElement(const tinyxml2::XMLElement& element, std::string& out) {
  out += '<';
  out += element.Name();
  for (const tinyxml2::XMLAttribute* a = element.FirstAttribute(); a; a = a->Next()) {
    out += ' ';
    out += a->Name();
    out += "=\"";
    AppendEscaped(a->Value(), false, out);
    out += '"';
  }
  // Adjacent text (split by a comment or a CDATA section) is written as one run.
  std::string content, run;
  for (const tinyxml2::XMLNode* child = element.FirstChild(); child; child = child->NextSibling()) {
    if (const tinyxml2::XMLText* t = child->ToText()) {
      run += t->Value();
    } else if (const tinyxml2::XMLElement* e = child->ToElement()) {
      if (!run.empty()) AppendText(run, content);
      run.clear();
      AppendElement(*e, content);
    }
  }
  if (!run.empty()) AppendText(run, content);
  if (content.empty()) {
    out += "/>";
    return;
  }
  out += '>';
  out += content;
  out += "</";
  out += element.Name();
  out += '>';
}

}  // namespace

CheckedXml::CheckedXml(const std::string& text, const std::string& source_name)
    : document_(std::make_unique<tinyxml2::XMLDocument>(false, tinyxml2::PRESERVE_WHITESPACE)) {
  const bool non_ascii = CheckCharacters(text, source_name);
  document_->Parse(text.data(), text.size());
  const std::optional<TagProblem> tags = FindTagProblem(text);
  if (document_->Error()) {
    const auto [line, reason] = ParseError(*document_, text, tags);
    Fail(source_name, text, line, "malformed XML: " + reason);
  }
  if (tags) {  // tinyxml2 accepts an end tag after the root element
    const auto [line, reason] = Describe(*tags, text);
    Fail(source_name, text, line, "malformed XML: " + reason);
  }
  tinyxml2::XMLElement& root = RootOf(*document_, text, source_name, non_ascii);
  CheckAndDecode(root, source_name, text);
  root_ = &root;
}

CheckedXml::~CheckedXml() = default;

std::string XmlEscaped(const std::string& text) {
  std::string out;
  AppendEscaped(text, false, out);
  return out;
}

std::string CheckedXml::Canonical() const {
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  AppendElement(*root_, out);
  out += '\n';
  return out;
}

}  // namespace stairplan
