// The version fields every JSON object stairplan writes carries, so that a file says which release
// wrote it and which meaning of its keys it has (both from the generated "stairplan/version.h").
#pragma once

#include <nlohmann/json.hpp>

#include "stairplan/version.h"

namespace stairplan {

/// Adds "version" (kVersion, e.g. "0.1.0") and "schema_version" (kSchemaVersion) to `object`.
inline nlohmann::json& StampVersion(nlohmann::json& object) {
  object["version"] = kVersion;
  object["schema_version"] = kSchemaVersion;
  return object;
}

}  // namespace stairplan
