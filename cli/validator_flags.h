// The validator's settings on the command line (--set validator.NAME=VALUE, shared by `plan` and
// `validate`) and the one-line summary of its dynamic check both print.
#pragma once

#include <string>

#include "stairplan/planning/validation/traversal_validator.h"

namespace stairplan::cli {

/// The number after the '=' of a "--set NAME=VALUE" assignment; throws BadInput naming it when it
/// is not one.
double SettingValue(const std::string& assignment);

/// Applies "validator.NAME=VALUE" to `settings` (ValidationSettings::Set); throws BadInput naming
/// the assignment for a bad name, number or value.
void ApplyValidatorSetting(const std::string& assignment, ValidationSettings& settings);

/// "dynamics: ok, max wrench residual ... N at t=... s (friction 0.8, torque limits checked)".
std::string DynamicsSummary(const ValidationReport& report);

}  // namespace stairplan::cli
