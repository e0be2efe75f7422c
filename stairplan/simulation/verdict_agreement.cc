#include "stairplan/simulation/verdict_agreement.h"

#include <iomanip>
#include <sstream>

namespace stairplan {

AgreementReport CompareVerdicts(const std::vector<VerdictPair>& pairs) {
  AgreementReport report;
  for (const VerdictPair& p : pairs) {
    ++report.compared;
    if (p.validator_ok == p.physics_ok) {
      ++report.agreed;
      ++(p.physics_ok ? report.both_ok : report.both_failed);
    } else {
      (p.validator_ok ? report.valid_but_failed : report.invalid_but_passed).push_back(p);
    }
  }
  report.rate = report.compared > 0 ? static_cast<double>(report.agreed) / report.compared : 1.0;
  return report;
}

std::string AgreementToText(const AgreementReport& report) {
  std::ostringstream out;
  out << "validator vs physics: " << report.agreed << "/" << report.compared << " agree (" << std::fixed
      << std::setprecision(1) << 100.0 * report.rate << "%): " << report.both_ok << " both ok, " << report.both_failed
      << " both failed\n";
  out << "valid but failed in physics: " << report.valid_but_failed.size() << "\n";
  for (const VerdictPair& p : report.valid_but_failed) out << "  " << p.label << ": " << p.physics_cause << "\n";
  out << "invalid but passed in physics: " << report.invalid_but_passed.size() << "\n";
  for (const VerdictPair& p : report.invalid_but_passed) out << "  " << p.label << ": " << p.validator_cause << "\n";
  return out.str();
}

}  // namespace stairplan
