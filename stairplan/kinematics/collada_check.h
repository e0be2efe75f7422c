// What assimp 5.2.5's COLLADA importer trusts and we check before it reads a file. It reads an
// index list (<p>, <vcount>, <v>, <h>) by parsing integers until the text ends, and a character
// that is not part of one stops the parse without moving on: the loop then appends zeros until the
// process runs out of memory (a 1 kB file took 3 GB; found by the mesh fuzzer, issue #28). It also
// reserves memory for a `count` attribute before reading any value, so count="4000000000" asks for
// gigabytes whatever the file holds.
#pragma once

#include <string>

namespace stairplan {

/// Throws std::invalid_argument "<path>: line N: <reason>" when the COLLADA file at `path` is not
/// well-formed XML, when an index list holds anything but whitespace and (optionally negative)
/// integers, when an array (`<float_array>`, `<Name_array>`, ...) has no `count`, or when a
/// `count`, `stride` or `offset` attribute is not a whole number or exceeds the file's size in
/// bytes (no array in the file can hold more values than it has bytes).
void CheckColladaFile(const std::string& path);

}  // namespace stairplan
