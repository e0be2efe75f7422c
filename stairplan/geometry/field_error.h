// An invalid_argument that remembers which input field was wrong, so callers can name the flag
// or the file field the value came from.
#pragma once

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace stairplan {

/// An std::invalid_argument that remembers the input field that was wrong, so a caller can name it.
class FieldError : public std::invalid_argument {
 public:
  /// `field` names the input (a flag, a file field); `problem` says what is wrong with it.
  FieldError(std::string field, const std::string& problem)
      : std::invalid_argument(field + ": " + problem), field_(std::move(field)), problem_(problem) {}
  /// The input that was wrong.
  const std::string& field() const { return field_; }
  /// What is wrong with it.
  const std::string& problem() const { return problem_; }

 private:
  std::string field_;
  std::string problem_;
};

/// Settings checks share this: throws FieldError(field, ...) unless `value` is finite and in [lo, hi].
inline void RequireInRange(const std::string& field, double value, double lo, double hi) {
  if (std::isfinite(value) && value >= lo && value <= hi) return;
  std::ostringstream problem;
  problem << "must be in [" << lo << ", " << hi << "] (got " << value << ")";
  throw FieldError(field, problem.str());
}

}  // namespace stairplan
