#include "stairplan/geometry/stair_spec_yaml.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "stairplan/geometry/field_error.h"

namespace stairplan {
namespace {

std::string Where(const std::string& source, const std::string& key, const YAML::Node& node) {
  std::string where = source + ": field '" + key + "'";
  const YAML::Mark mark = node.Mark();
  if (mark.line >= 0) where += " (line " + std::to_string(mark.line + 1) + ")";
  return where;
}

double ReadNumber(const YAML::Node& node, const std::string& where) {
  if (!node.IsScalar()) throw FieldError(where, "must be a number");
  double value = 0.0;
  try {
    value = node.as<double>();
  } catch (const YAML::Exception&) {
    throw FieldError(where, "must be a number (got '" + node.Scalar() + "')");
  }
  if (!std::isfinite(value)) throw FieldError(where, "must be finite (got '" + node.Scalar() + "')");
  return value;
}

std::vector<double> ReadList(const YAML::Node& node, const std::string& where) {
  if (!node.IsSequence()) throw FieldError(where, "must be a list of numbers");
  std::vector<double> values;
  for (std::size_t i = 0; i < node.size(); ++i) values.push_back(ReadNumber(node[i], where + "[" + std::to_string(i) + "]"));
  return values;
}

int ReadCount(const YAML::Node& node, const std::string& where) {
  const double value = ReadNumber(node, where);
  if (value != std::floor(value) || value < 1 || value > 200) throw FieldError(where, "must be a whole number from 1 to 200");
  return static_cast<int>(value);
}

// The shortest text that parses back to `value` (std::to_chars), so a written spec reads back equal.
std::string Shortest(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string YamlList(const std::vector<double>& values) {
  std::string out = "[";
  for (std::size_t i = 0; i < values.size(); ++i) out += (i ? ", " : "") + Shortest(values[i]);
  return out + "]";
}

bool AllEqual(const std::vector<double>& values, double value) {
  for (double v : values) {
    if (v != value) return false;
  }
  return true;
}

}  // namespace

TravelDirection ParseDirection(const std::string& text, const std::string& field) {
  if (text == "up") return TravelDirection::kUp;
  if (text == "down") return TravelDirection::kDown;
  throw FieldError(field, "must be 'up' or 'down' (got '" + text + "')");
}

StairSpec StairSpecFromYaml(const std::string& text, const std::string& source, const StairSpec& defaults) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw FieldError(source + " (line " + std::to_string(e.mark.line + 1) + ")", "not valid YAML: " + e.msg);
  }
  if (!root.IsMap()) throw FieldError(source, "must be a YAML mapping of stair fields");
  StairSpec spec = defaults;
  const std::map<std::string, double*> numbers = {
      {"rise", &spec.rise}, {"run", &spec.run}, {"nosing", &spec.nosing}, {"width", &spec.width},
      {"landing_before", &spec.landing_before}, {"landing_after", &spec.landing_after},
      {"nosing_thickness", &spec.nosing_thickness}, {"uncertainty", &spec.uncertainty}};
  for (const auto& item : root) {
    // A key that is a list or a mapping ("? [a]: 1") names no field; as<std::string>() would throw
    // YAML::TypedBadConversion, which is not the FieldError callers handle (found by fuzz_stairs_yaml).
    if (!item.first.IsScalar()) {
      throw FieldError(source + " (line " + std::to_string(item.first.Mark().line + 1) + ")", "a key must be a field name");
    }
    const std::string key = item.first.Scalar();
    const std::string where = Where(source, key, item.second);
    if (auto it = numbers.find(key); it != numbers.end()) {
      *it->second = ReadNumber(item.second, where);
    } else if (key == "steps") {
      spec.steps = ReadCount(item.second, where);
    } else if (key == "rises") {
      spec.rises = ReadList(item.second, where);
    } else if (key == "runs") {
      spec.runs = ReadList(item.second, where);
    } else if (key == "direction") {
      spec.direction = ParseDirection(item.second.IsScalar() ? item.second.Scalar() : "", where);
    } else {
      throw FieldError(where, "unknown field");
    }
  }
  try {
    spec.Validate();
  } catch (const FieldError& e) {
    throw FieldError(source + ": field '" + e.field() + "'", e.problem());
  }
  return spec;
}

StairSpec StairSpecFromYamlFile(const std::string& path, const StairSpec& defaults) {
  std::ifstream in(path);
  if (!in) throw FieldError(path, "cannot open the stairs file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return StairSpecFromYaml(buffer.str(), path, defaults);
}

std::string StairSpecToYaml(const StairSpec& spec, const std::string& comment) {
  std::ostringstream out;
  std::istringstream lines(comment);
  for (std::string line; std::getline(lines, line);) out << "# " << line << "\n";
  out << "steps: " << spec.steps << "\nrise: " << Shortest(spec.rise) << "\nrun: " << Shortest(spec.run)
      << "\nnosing: " << Shortest(spec.nosing) << "\nwidth: " << Shortest(spec.width)
      << "\nlanding_before: " << Shortest(spec.landing_before) << "\nlanding_after: " << Shortest(spec.landing_after)
      << "\nnosing_thickness: " << Shortest(spec.nosing_thickness) << "\ndirection: " << ToString(spec.direction) << "\n";
  if (!AllEqual(spec.rises, spec.rise)) out << "rises: " << YamlList(spec.rises) << "\n";
  if (!AllEqual(spec.runs, spec.run)) out << "runs: " << YamlList(spec.runs) << "\n";
  if (spec.uncertainty > 0.0) {
    out << "# How far the true nosings may be from these (the estimate's bound); planners keep it as clearance.\n"
        << "uncertainty: " << Shortest(spec.uncertainty) << "\n";
  }
  return out.str();
}

}  // namespace stairplan
