#include "stairplan/sweep/sweep_grid.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>

#include "stairplan/geometry/field_error.h"
#include "stairplan/geometry/stair_spec_yaml.h"

namespace stairplan {
namespace {

double ParseNumber(const std::string& text, const std::string& flag) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty() || !std::isfinite(value)) {
    throw FieldError(flag, "'" + text + "' is not a number");
  }
  return value;
}

std::vector<std::string> Split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, separator);) parts.push_back(part);
  if (!text.empty() && text.back() == separator) parts.emplace_back();
  return parts;
}

}  // namespace

std::vector<double> SweepAxis::Values() const {
  std::vector<double> values;
  for (int i = 0; i < count; ++i) values.push_back(count == 1 ? lo : lo + (hi - lo) * i / (count - 1));
  return values;
}

SweepAxis SweepAxis::Parse(const std::string& text, const std::string& flag) {
  const std::vector<std::string> parts = Split(text, ':');
  SweepAxis axis;
  if (parts.size() == 1) {
    axis.lo = axis.hi = ParseNumber(parts[0], flag);
    return axis;
  }
  if (parts.size() != 3) throw FieldError(flag, "expected A:B:N or a single value (got '" + text + "')");
  axis.lo = ParseNumber(parts[0], flag);
  axis.hi = ParseNumber(parts[1], flag);
  const double n = ParseNumber(parts[2], flag);
  if (n != std::floor(n) || n < 1 || n > 1000) throw FieldError(flag, "N must be a whole number from 1 to 1000");
  if (axis.hi < axis.lo) throw FieldError(flag, "B must not be below A");
  axis.count = static_cast<int>(n);
  return axis;
}

StairSpec SweepPoint::Spec() const {
  StairSpec spec;
  spec.steps = steps;
  spec.rise = rise;
  spec.run = run;
  spec.nosing = nosing;
  spec.direction = direction;
  return spec;
}

std::vector<SweepPoint> EnumeratePoints(const SweepGrid& grid) {
  std::vector<SweepPoint> points;
  for (TravelDirection direction : grid.directions) {
    for (double steps : grid.steps.Values()) {
      for (double nosing : grid.nosing.Values()) {
        for (double rise : grid.rise.Values()) {
          for (double run : grid.run.Values()) {
            SweepPoint p;
            p.index = static_cast<int>(points.size());
            p.direction = direction;
            p.steps = static_cast<int>(std::lround(steps));
            p.nosing = nosing;
            p.rise = rise;
            p.run = run;
            points.push_back(p);
          }
        }
      }
    }
  }
  return points;
}

std::vector<int> SlowestFirst(std::vector<int> indices, const std::vector<SweepPoint>& points) {
  const auto cost = [&](int index) {
    const SweepPoint& p = points[static_cast<std::size_t>(index)];
    return std::make_tuple(p.steps, p.rise, p.run);
  };
  std::stable_sort(indices.begin(), indices.end(), [&](int a, int b) { return cost(a) > cost(b); });
  return indices;
}

Shard Shard::Parse(const std::string& text, const std::string& flag) {
  const std::vector<std::string> parts = Split(text, '/');
  if (parts.size() != 2) throw FieldError(flag, "expected i/N (got '" + text + "')");
  const double i = ParseNumber(parts[0], flag), n = ParseNumber(parts[1], flag);
  if (i != std::floor(i) || n != std::floor(n) || n < 1 || i < 0 || i >= n || n > 100000) {
    throw FieldError(flag, "expected whole numbers with 0 <= i < N (got '" + text + "')");
  }
  return {static_cast<int>(i), static_cast<int>(n)};
}

std::vector<TravelDirection> ParseDirections(const std::string& text, const std::string& flag) {
  std::vector<TravelDirection> directions;
  for (const std::string& part : Split(text, ',')) directions.push_back(ParseDirection(part, flag));
  if (directions.empty()) throw FieldError(flag, "names no direction");
  return directions;
}

}  // namespace stairplan
