// A StairSpec as YAML, read and written. Keys: steps, rise, run, nosing, width, landing_before,
// landing_after, nosing_thickness, rises, runs, direction (up|down), and the optional uncertainty
// (StairSpec::uncertainty, written by the estimators; absent: 0). Unknown keys are errors.
#pragma once

#include <string>

#include "stairplan/geometry/staircase.h"

namespace stairplan {

/// Parses YAML text into a validated StairSpec, starting from `defaults`. Throws FieldError whose
/// field reads "<source>: field '<key>'" (and names the line where yaml-cpp knows it).
StairSpec StairSpecFromYaml(const std::string& text, const std::string& source, const StairSpec& defaults = {});

/// Reads and parses a YAML file; a missing or unreadable file is a FieldError naming the path.
StairSpec StairSpecFromYamlFile(const std::string& path, const StairSpec& defaults = {});

/// The YAML that StairSpecFromYaml reads back into `spec` exactly (shortest round-trip numbers).
/// `rises` and `runs` are written only where a step differs from `rise` or `run`, `uncertainty`
/// only when positive. Each line of
/// `comment` becomes a leading "# " line.
std::string StairSpecToYaml(const StairSpec& spec, const std::string& comment = "");

/// Parses "up" / "down"; throws FieldError naming `field` otherwise.
TravelDirection ParseDirection(const std::string& text, const std::string& field);

}  // namespace stairplan
