// PCD files for the tests, written the way PCL writes them (x y z as float or double plus other
// fields, ascii, binary or binary_compressed), with our own LZF compressor: the library only reads
// PCD, and the decoder must be checked against a compressor that makes real back references.
#pragma once

#include <string>
#include <vector>

#include "stairplan/perception/pcd_io.h"
#include "stairplan/perception/point_cloud.h"

namespace stairplan::testing {

/// LZF-compresses `bytes` greedily (3-byte hash matches, literal runs of up to 32 bytes).
std::string LzfCompress(const std::string& bytes);

/// How a test PCD file lays out its fields.
struct PcdLayout {
  bool label_first = false;  ///< a 1-byte U field "label" before x (tests field offsets)
  bool xyz_double = false;   ///< x y z as SIZE 8 (else 4, as PCL's PointXYZ)
  int nan_points = 0;        ///< points without a return (NaN x y z) appended, as organised clouds have
};

/// A PCD file of `cloud` (plus an rgb field after z) in `encoding`.
std::string PcdFileBytes(const PointCloud& cloud, PcdEncoding encoding, const PcdLayout& layout = {});

/// The cloud with every coordinate rounded to float, as a float PLY or PCD stores it.
PointCloud RoundedToFloat(const PointCloud& cloud);

}  // namespace stairplan::testing
