// Shared by the libFuzzer targets: the bytes as text, and the one property every parser error must
// have besides being a std::invalid_argument: its message names the source it was given.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

namespace stairplan::fuzz {

inline std::string Text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

/// A rejected input is fine; a rejection that does not say which file it is about is a finding.
inline void CheckNamesSource(const std::invalid_argument& e, const char* source) {
  if (std::strstr(e.what(), source) == nullptr) {
    std::fprintf(stderr, "finding: error message does not name the source '%s': %s\n", source, e.what());
    std::abort();
  }
}

}  // namespace stairplan::fuzz
