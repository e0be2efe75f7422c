#include "stairplan/planning/gait/tread_error.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace stairplan {

TreadErrorTolerance TreadDepthTolerance(const GaitDesign& g, double W, double H) {
  const double sin_phi = std::sin(g.phi);
  const double cos_phi = std::cos(g.phi);
  const double b = g.a_max;
  TreadErrorTolerance t;
  if (!(g.d_s > 0.0)) {  // without condition (10) there is no gait to tolerate errors
    t.upper = t.lower = std::numeric_limits<double>::quiet_NaN();
    return t;
  }
  t.upper = g.a_min;
  t.lower = (g.d_s * H * cos_phi + g.d_s * b * sin_phi - g.d_s * W * sin_phi - g.d / sin_phi * H) /
            (H + g.d_s * sin_phi);
  return t;
}

CumulativeTreadError CheckCumulativeTreadError(const std::vector<double>& errors, const TreadErrorTolerance& tolerance) {
  CumulativeTreadError result;
  result.cumulative.reserve(errors.size());
  double sum = 0.0;
  for (std::size_t i = 0; i < errors.size(); ++i) {
    if (!std::isfinite(errors[i])) {
      throw std::invalid_argument("errors[" + std::to_string(i) + "]: must be finite");
    }
    sum += errors[i];
    result.cumulative.push_back(sum);
    if (result.first_violation < 0 && !(sum < tolerance.upper && sum > tolerance.lower)) {
      result.first_violation = static_cast<int>(i);
    }
  }
  return result;
}

}  // namespace stairplan
