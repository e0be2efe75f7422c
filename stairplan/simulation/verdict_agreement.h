// Validator against physics: for a set of plans (a sweep), how often our validator and MuJoCo give
// the same verdict, and every case where they differ with each side's first cause. Each
// disagreement is a bug in one of the two, to be fixed or explained.
#pragma once

#include <string>
#include <vector>

namespace stairplan {

/// Both verdicts on one plan.
struct VerdictPair {
  std::string label;            ///< which plan, e.g. "up rise=0.17 run=0.27"
  bool validator_ok = false;  ///< the validator found no violation
  std::string validator_cause;  ///< the validator's first violation, "" when valid
  bool physics_ok = false;      ///< SimulationOutcome::Passed()
  std::string physics_cause;    ///< SimulationOutcome::FirstCause(), "" when passed
};

/// How often the validator and the physics agree over a set of plans, and where they differ.
struct AgreementReport {
  int compared = 0;  ///< plans compared
  int agreed = 0;  ///< plans on which both verdicts agree
  int both_ok = 0;  ///< both passed
  int both_failed = 0;  ///< both failed
  double rate = 1.0;  ///< agreed / compared (1 when nothing was compared)
  std::vector<VerdictPair> valid_but_failed;   ///< the validator said valid, physics failed
  std::vector<VerdictPair> invalid_but_passed; ///< the validator said invalid, physics passed
};

/// Counts agreements over `pairs` and collects the disagreements.
AgreementReport CompareVerdicts(const std::vector<VerdictPair>& pairs);

/// A short plain-text report: counts, rate, then each disagreement with both causes.
std::string AgreementToText(const AgreementReport& report);

}  // namespace stairplan
