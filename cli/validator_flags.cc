#include "cli/validator_flags.h"

#include <sstream>
#include <stdexcept>

#include "cli/cli_common.h"

namespace stairplan::cli {

double SettingValue(const std::string& assignment) {
  const std::size_t eq = assignment.find('=');
  try {
    if (eq == std::string::npos) throw std::invalid_argument("no '='");
    std::size_t used = 0;
    const double value = std::stod(assignment.substr(eq + 1), &used);
    if (used != assignment.size() - eq - 1) throw std::invalid_argument("trailing characters");
    return value;
  } catch (const std::exception&) {
    throw BadInput("--set: '" + (eq == std::string::npos ? assignment : assignment.substr(eq + 1)) + "' is not a number (in '" +
                   assignment + "')");
  }
}

void ApplyValidatorSetting(const std::string& assignment, ValidationSettings& settings) {
  const std::string prefix = "validator.";
  const std::size_t eq = assignment.find('=');
  if (eq == std::string::npos || assignment.compare(0, prefix.size(), prefix) != 0) {
    throw BadInput("--set: expected validator.NAME=VALUE (got '" + assignment + "')");
  }
  const double value = SettingValue(assignment);
  try {
    settings.Set(assignment.substr(prefix.size(), eq - prefix.size()), value);
    settings.Validate();
  } catch (const std::invalid_argument& e) {
    throw BadInput(std::string("--set: validator.") + e.what());
  }
}

std::string DynamicsSummary(const ValidationReport& report) {
  const DynamicsReport& d = report.dynamics;
  if (d.mode == DynamicsCheckMode::kOff) return "dynamics: not checked (validator.dynamics=0)";
  std::ostringstream text;
  text << "dynamics (" << ToString(d.mode) << "): ";
  if (d.failed_instants == 0) {
    text << "ok";
  } else {
    text << "FAILS at " << d.failed_instants << " instants, first t=" << d.first_failure_t << " s "
         << ToString(d.first_failure_leg) << " " << ToString(d.first_failure_kind);
  }
  text << ", max wrench residual " << d.max_residual_n << " N at t=" << d.max_residual_t << " s (tolerance "
       << d.tolerance_n << " N, friction " << d.friction << ", "
       << (d.torque_limits_checked ? "torque limits checked" : "no torque limits: the URDF lacks efforts")
       << (d.body_inertia_known ? "" : ", no base inertia: dL/dt taken as 0") << ")";
  return text.str();
}

}  // namespace stairplan::cli
