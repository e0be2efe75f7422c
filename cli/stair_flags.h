// The stair flags shared by the sub-commands that plan (plan, robustness): a YAML file with
// --steps/--rise/--run/--nosing/--width/--direction on top, and --facing.
#pragma once

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "stairplan/geometry/constrained_map.h"
#include "stairplan/geometry/staircase.h"

namespace stairplan::cli {

struct StairFlags {
  std::string file;
  std::optional<int> steps;
  std::optional<double> rise, run, nosing, width;
  std::optional<std::string> direction;  ///< optional, so an empty value is an error, not a default
};

/// Adds --stairs, --steps, --rise, --run, --nosing, --width, --direction to `app`.
void AddStairFlags(CLI::App& app, StairFlags& flags);

/// The stairs from the YAML file (if any) with the flags on top; BadInput names the flag or the
/// file and field that is wrong.
Staircase ResolveStairs(const StairFlags& flags);

/// "forward" or "backward"; BadInput naming --facing otherwise.
Facing ParseFacing(const std::string& text);

}  // namespace stairplan::cli
