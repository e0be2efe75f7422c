// An invalid_argument that remembers which input field was wrong, so callers can name the flag
// or the file field the value came from.
#pragma once

#include <stdexcept>
#include <string>

namespace stairplan {

class FieldError : public std::invalid_argument {
 public:
  FieldError(std::string field, const std::string& problem)
      : std::invalid_argument(field + ": " + problem), field_(std::move(field)), problem_(problem) {}
  const std::string& field() const { return field_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string field_;
  std::string problem_;
};

}  // namespace stairplan
