// Shared by the point-cloud fuzz targets: what every accepted cloud must satisfy.
#pragma once

#include <cstdio>
#include <cstdlib>

#include "stairplan/perception/point_cloud.h"

namespace stairplan::fuzz {

/// The readers promise a non-empty cloud of finite points; anything else is a finding.
inline void CheckCloud(const PointCloud& cloud, const char* reader) {
  bool ok = !cloud.empty();
  for (const auto& p : cloud.points) ok = ok && p.allFinite();
  if (!ok) {
    std::fprintf(stderr, "finding: the %s reader returned an empty or non-finite cloud\n", reader);
    std::abort();
  }
}

}  // namespace stairplan::fuzz
