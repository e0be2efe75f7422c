#include "cli/stair_flags.h"

#include <map>

#include "stairplan/geometry/field_error.h"
#include "stairplan/geometry/stair_spec_yaml.h"
#include "cli/cli_common.h"

namespace stairplan::cli {

void AddStairFlags(CLI::App& app, StairFlags& flags) {
  app.add_option("--stairs", flags.file, "Stairs YAML file (flags below override its fields)");
  app.add_option("--steps", flags.steps, "Number of steps (risers), default 7");
  app.add_option("--rise", flags.rise, "Riser height [m], default 0.17");
  app.add_option("--run", flags.run, "Tread going [m], default 0.27");
  app.add_option("--nosing", flags.nosing, "Nosing overhang [m], default 0.02");
  app.add_option("--width", flags.width, "Stair width [m], default 1.0");
  app.add_option("--direction", flags.direction, "up or down, default up");
}

Staircase ResolveStairs(const StairFlags& flags) {
  StairSpec spec;
  if (!flags.file.empty()) spec = StairSpecFromYamlFile(flags.file);
  std::map<std::string, bool> from_flag;
  const auto set = [&](const char* field, auto& target, const auto& value) {
    if (value) {
      target = *value;
      from_flag[field] = true;
    }
  };
  set("steps", spec.steps, flags.steps);
  set("rise", spec.rise, flags.rise);
  set("run", spec.run, flags.run);
  set("nosing", spec.nosing, flags.nosing);
  set("width", spec.width, flags.width);
  // A flag for the scalar replaces the file's per-step list of the same quantity.
  if (from_flag["rise"] || from_flag["steps"]) spec.rises.clear();
  if (from_flag["run"] || from_flag["steps"]) spec.runs.clear();
  if (flags.direction) {
    spec.direction = ParseDirection(*flags.direction, "--direction");
    from_flag["direction"] = true;
  }
  try {
    return Staircase(spec);
  } catch (const FieldError& e) {
    const std::string base = e.field().substr(0, e.field().find('['));
    if (from_flag[base] || flags.file.empty()) throw BadInput("--" + e.field() + ": " + e.problem());
    throw BadInput(flags.file + ": field '" + e.field() + "': " + e.problem());
  }
}

Facing ParseFacing(const std::string& text) {
  if (text == "forward") return Facing::kForward;
  if (text == "backward") return Facing::kBackward;
  throw BadInput("--facing: must be 'forward' or 'backward' (got '" + text + "')");
}

}  // namespace stairplan::cli
