#include "stairplan/simulation/sim_outcome.h"

#include <algorithm>
#include <sstream>

namespace stairplan {

const char* ToString(SimStatus status) {
  switch (status) {
    case SimStatus::kSuccess: return "success";
    case SimStatus::kFall: return "fall";
    case SimStatus::kStalled: return "stalled";
  }
  return "unknown";
}

double SimulationOutcome::MaxLandingError() const {
  double worst = 0.0;
  for (const FootLanding& l : landings) worst = std::max(worst, l.error_m);
  return worst;
}

bool SimulationOutcome::AllLandedInRegions() const {
  return std::all_of(landings.begin(), landings.end(), [](const FootLanding& l) { return l.in_step_region; });
}

bool SimulationOutcome::Passed() const {
  return status == SimStatus::kSuccess && other_contacts.empty() && AllLandedInRegions();
}

bool SimulationOutcome::PassedWithClearance(double clearance) const {
  return Passed() && min_link_clearance_m > clearance;
}

std::string SimulationOutcome::FirstCause() const {
  if (status != SimStatus::kSuccess) return std::string(ToString(status)) + ": " + cause;
  if (!other_contacts.empty()) {
    const auto first = std::min_element(other_contacts.begin(), other_contacts.end(),
                                        [](const LinkContact& a, const LinkContact& b) { return a.t_first < b.t_first; });
    std::ostringstream out;
    out << "contact: " << first->link << " on " << first->stair_geom << " at t=" << first->t_first << " s";
    return out.str();
  }
  for (const FootLanding& l : landings) {
    if (l.in_step_region) continue;
    std::ostringstream out;
    out << "landing: " << l.leg << " outside its step region at t=" << l.t_planned << " s (error "
        << l.error_m * 1000 << " mm)";
    return out.str();
  }
  return "";
}

}  // namespace stairplan
