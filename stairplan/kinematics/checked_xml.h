// The XML of an untrusted robot file, checked with a maintained parser (tinyxml2) before anything
// else reads it, and written back out in one canonical form. urdfdom 3.0.1 parses with TinyXML
// 2.6.2, unmaintained since 2011, whose multi-byte character handling can read past the end of its
// buffer (the URDF fuzzer caught it; third_party_notes/tinyxml2.md): it is only ever given the
// canonical text, which is pure ASCII, well-formed XML with one root element, ASCII names and no
// character it cannot represent.
#pragma once

#include <memory>
#include <string>

namespace tinyxml2 {
class XMLDocument;
class XMLElement;
}  // namespace tinyxml2

namespace stairplan {

/// A checked XML document. Construction throws std::invalid_argument "<source>: line N (<text of
/// the line>): <reason>" when `text` is not UTF-8 made of XML characters (a stray or truncated
/// multi-byte character, a control character, a NUL), when it is not well-formed XML (an element
/// that is never closed, a mismatched tag, a repeated attribute, a second root element, nesting
/// deeper than tinyxml2's limit of 100), when an element or attribute name is not an ASCII XML name,
/// when a reference is neither one of XML's five entities nor a character reference to an XML
/// character, or when the declaration names another encoding than UTF-8 for a file with non-ASCII
/// bytes. Comments, the DOCTYPE and processing instructions are dropped.
class CheckedXml {
 public:
  /// Checks and parses `text`; `source_name` starts every error message.
  CheckedXml(const std::string& text, const std::string& source_name);
  ~CheckedXml();
  CheckedXml(const CheckedXml&) = delete;
  CheckedXml& operator=(const CheckedXml&) = delete;

  /// The root element; attribute values and text hold the characters they stand for (references
  /// already replaced), as valid UTF-8.
  const tinyxml2::XMLElement& root() const { return *root_; }

  /// The document as pure ASCII XML: a UTF-8 declaration, then the root element with its
  /// attributes in file order and its elements and text, written with XmlEscaped (below). Parsing
  /// it again gives the same tree and the same text.
  std::string Canonical() const;

 private:
  std::unique_ptr<tinyxml2::XMLDocument> document_;
  const tinyxml2::XMLElement* root_ = nullptr;
};

/// `text` (UTF-8) as an XML attribute value (in either quotes) or character data made of
/// printable ASCII: each of & < > " ' and every other character but the space as a reference.
/// For writers of XML that carries names from a robot file (the MJCF for MuJoCo). Throws
/// std::invalid_argument when `text` is not UTF-8.
std::string XmlEscaped(const std::string& text);

}  // namespace stairplan
