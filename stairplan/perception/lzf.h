// LZF decompression (Marc Lehmann's format, as PCL's binary_compressed PCD files use it). Written
// here rather than linked: see third_party_notes/lzf.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace stairplan {

/// The most an LZF stream can expand: a 3-byte back reference yields 264 bytes (ratio 88).
inline constexpr std::size_t kLzfMaxExpansion = 88;

/// Decompresses the LZF stream `in[0, in_size)` into exactly `out_size` bytes at `out`. Returns an
/// empty string on success, otherwise what is wrong and at which input byte (a back reference
/// before the start of the output, a literal run or reference past either end, a stream that
/// ends early or makes fewer than `out_size` bytes). Never reads or writes outside the buffers.
std::string LzfDecompress(const std::uint8_t* in, std::size_t in_size, std::uint8_t* out, std::size_t out_size);

}  // namespace stairplan
