#include "stairplan/perception/lzf.h"

#include <cstring>

namespace stairplan {

// The format: a control byte c. c < 32: a literal run of c + 1 bytes follows. Otherwise a back
// reference of length (c >> 5) + 2 bytes (when c >> 5 is 7, the next byte adds to the length),
// starting ((c & 31) << 8) + next byte + 1 bytes before the end of the output so far; it may
// overlap the bytes it produces (a run), so it is copied byte by byte.
std::string LzfDecompress(const std::uint8_t* in, std::size_t in_size, std::uint8_t* out, std::size_t out_size) {
  std::size_t ip = 0, op = 0;
  const auto at = [&](std::size_t byte) { return " at input byte " + std::to_string(byte); };
  while (ip < in_size) {
    const std::size_t start = ip;
    const unsigned ctrl = in[ip++];
    if (ctrl < 32) {
      const std::size_t run = ctrl + 1u;
      if (run > in_size - ip) return "literal run of " + std::to_string(run) + " bytes past the end of the block" + at(start);
      if (run > out_size - op) return "literal run past the declared uncompressed size" + at(start);
      std::memcpy(out + op, in + ip, run);
      ip += run;
      op += run;
      continue;
    }
    std::size_t length = ctrl >> 5;
    if (length == 7) {
      if (ip >= in_size) return "back reference cut off by the end of the block" + at(start);
      length += in[ip++];
    }
    length += 2;
    if (ip >= in_size) return "back reference cut off by the end of the block" + at(start);
    const std::size_t distance = ((static_cast<std::size_t>(ctrl & 31u) << 8) | in[ip++]) + 1;
    if (distance > op) return "back reference before the start of the data" + at(start);
    if (length > out_size - op) return "back reference past the declared uncompressed size" + at(start);
    for (std::size_t k = 0; k < length; ++k, ++op) out[op] = out[op - distance];
  }
  if (op != out_size) return "the block makes " + std::to_string(op) + " of the declared " + std::to_string(out_size) + " bytes";
  return {};
}

}  // namespace stairplan
