#include "stairplan/simulation/sweep_physics.h"

#include <algorithm>
#include <sstream>

#include "stairplan/simulation/plan_executor.h"
#include "stairplan/sweep/sweep_runner.h"

namespace stairplan {
namespace {

std::string PhysicsCsvQuoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' || c == '\r' ? ' ' : c);
  return out + "\"";
}

double Real(const std::string& field) {
  std::size_t used = 0;
  const double v = std::stod(field, &used);
  if (used != field.size()) throw std::invalid_argument("not a number");
  return v;
}

}  // namespace

SweepPhysics::SweepPhysics(const SimSettings& settings, double clearance) : settings_(settings), clearance_(clearance) {
  settings_.Validate();
}

std::optional<PhysicsRow> SimulateSweepPoint(const SweepPoint& point, const RobotModel& robot, const Staircase& stairs,
                                             const PipelineResult& result, const SimSettings& settings,
                                             double clearance) {
  if (result.plan.status != PlanStatus::kOk) return std::nullopt;
  PhysicsRow row;
  row.index = point.index;
  std::ostringstream label;
  label << ToString(point.direction) << " steps=" << point.steps << " rise=" << point.rise << " run=" << point.run
        << " nosing=" << point.nosing;
  row.label = label.str();
  row.validator = result.validation.ok ? "valid" : "invalid";
  if (!result.validation.violations.empty()) {
    const Violation& v = result.validation.violations.front();
    row.validator_cause = std::string(ToString(v.kind)) + " " + v.leg + (v.detail.empty() ? "" : " " + v.detail);
  }
  try {
    const SimulationOutcome o = Simulate(robot, stairs, result.plan, settings);
    row.status = ToString(o.status);
    row.passed = o.Passed();
    row.passed_with_clearance = o.PassedWithClearance(clearance);
    row.min_link_clearance_m = o.min_link_clearance_m;
    row.closest_link = o.closest_link;
    row.cause = o.FirstCause();
    row.landings = static_cast<int>(o.landings.size());
    row.max_landing_error_m = o.MaxLandingError();
    row.other_contacts = static_cast<int>(o.other_contacts.size());
    row.max_torque_ratio = o.max_torque_ratio;
    row.real_time_factor = o.real_time_factor;
  } catch (const std::exception& e) {
    row.status = "error";
    row.cause = e.what();
  }
  return row;
}

std::string PhysicsCsvHeader() {
  return "index,point,validator,validator_cause,physics_status,physics_passed,physics_cause,landings,"
         "max_landing_error_m,other_contacts,min_link_clearance_m,closest_link,passed_with_clearance,max_torque_ratio,"
         "real_time_factor";
}

std::string PhysicsCsvLine(const PhysicsRow& r) {
  std::ostringstream csv;
  csv << r.index << "," << PhysicsCsvQuoted(r.label) << "," << r.validator << "," << PhysicsCsvQuoted(r.validator_cause) << ","
      << r.status << "," << (r.passed ? 1 : 0) << "," << PhysicsCsvQuoted(r.cause) << "," << r.landings << ","
      << r.max_landing_error_m << "," << r.other_contacts << "," << r.min_link_clearance_m << ","
      << PhysicsCsvQuoted(r.closest_link) << "," << (r.passed_with_clearance ? 1 : 0) << "," << r.max_torque_ratio << ","
      << r.real_time_factor;
  return csv.str();
}

PhysicsRow PhysicsRowFromCsvLine(const std::string& line) {
  const std::vector<std::string> f = CsvLineFields(line);
  if (f.size() != 15) throw std::invalid_argument("not a physics row");
  PhysicsRow r;
  r.index = std::stoi(f[0]);
  r.label = f[1];
  r.validator = f[2];
  r.validator_cause = f[3];
  r.status = f[4];
  r.passed = f[5] == "1";
  r.cause = f[6];
  r.landings = std::stoi(f[7]);
  r.max_landing_error_m = Real(f[8]);
  r.other_contacts = std::stoi(f[9]);
  r.min_link_clearance_m = Real(f[10]);
  r.closest_link = f[11];
  r.passed_with_clearance = f[12] == "1";
  r.max_torque_ratio = Real(f[13]);
  r.real_time_factor = Real(f[14]);
  return r;
}

void SweepPhysics::Record(const SweepPoint& point, const RobotModel& robot, const Staircase& stairs,
                          const PipelineResult& result) {
  if (const auto row = SimulateSweepPoint(point, robot, stairs, result, settings_, clearance_)) Add(*row);
}

void SweepPhysics::Add(const PhysicsRow& row) {
  const std::lock_guard<std::mutex> lock(mutex_);
  rows_.push_back(row);
}

std::vector<PhysicsRow> SweepPhysics::Rows() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  std::vector<PhysicsRow> rows = rows_;
  std::sort(rows.begin(), rows.end(), [](const PhysicsRow& a, const PhysicsRow& b) { return a.index < b.index; });
  return rows;
}

std::string SweepPhysics::Csv() const {
  std::string csv = PhysicsCsvHeader() + "\n";
  for (const PhysicsRow& r : Rows()) csv += PhysicsCsvLine(r) + "\n";
  return csv;
}

AgreementReport SweepPhysics::Agreement(bool with_clearance) const {
  std::vector<VerdictPair> pairs;
  for (const PhysicsRow& r : Rows()) {
    const bool ok = with_clearance ? r.passed_with_clearance : r.passed;
    std::ostringstream cause;
    cause << r.cause;
    if (with_clearance && r.passed && !ok) cause << "clearance: " << r.closest_link << " " << r.min_link_clearance_m * 1000 << " mm";
    pairs.push_back({r.label, r.validator == "valid", r.validator_cause, ok, cause.str()});
  }
  return CompareVerdicts(pairs);
}

}  // namespace stairplan
