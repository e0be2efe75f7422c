#include "stairplan/sweep/sweep_runner.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace stairplan {
namespace {

std::string CsvNumber(double v) {
  if (!std::isfinite(v)) return "";
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.6g", v);
  return buffer;
}

std::string CsvQuoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += (c == '\n' || c == '\r') ? ' ' : c;
  }
  return out + "\"";
}

}  // namespace

std::vector<std::string> CsvLineFields(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      fields.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

namespace {

double CsvNumber(const std::string& field) {
  if (field.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::size_t used = 0;
  const double v = std::stod(field, &used);
  if (used != field.size()) throw std::invalid_argument("not a number");
  return v;
}

// The columns every sweep CSV has begun with; the gait column came later.
constexpr const char* kHeaderStart =
    "index,direction,steps,rise,run,nosing,status,cadence_s,footsteps,min_clearance_m,min_stability_margin_m,reason";

SweepRow RowFromFields(const std::vector<std::string>& f) {
  SweepRow r;
  r.point.index = std::stoi(f[0]);
  if (f[1] != "up" && f[1] != "down") throw std::invalid_argument("bad direction");
  r.point.direction = f[1] == "up" ? TravelDirection::kUp : TravelDirection::kDown;
  r.point.steps = std::stoi(f[2]);
  r.point.rise = CsvNumber(f[3]);
  r.point.run = CsvNumber(f[4]);
  r.point.nosing = CsvNumber(f[5]);
  r.status = f[6];
  r.cadence_s = CsvNumber(f[7]);
  r.footsteps = std::stoi(f[8]);
  r.min_clearance_m = CsvNumber(f[9]);
  r.min_stability_margin_m = CsvNumber(f[10]);
  r.reason = f[11];
  // Rows written before the gait column have 12 fields (14 with times).
  const bool has_gait = f.size() == 13 || f.size() == 15;
  if (has_gait && !f[12].empty()) {
    r.gait = ParseGait(f[12]);
    if (!r.gait) throw std::invalid_argument("bad gait");
  }
  const std::size_t times = has_gait ? 13 : 12;
  if (f.size() >= times + 2) {
    r.plan_us = CsvNumber(f[times]);
    r.validate_us = CsvNumber(f[times + 1]);
  }
  return r;
}

}  // namespace

SweepRow SweepRowFromCsvLine(const std::string& line) {
  const std::vector<std::string> fields = CsvLineFields(line);
  if (fields.size() < 12 || fields.size() > 15) throw std::invalid_argument("not a sweep row");
  return RowFromFields(fields);
}

std::vector<SweepRow> SweepRowsFromCsv(const std::string& text, const std::string& file) {
  std::istringstream in(text);
  std::string line;
  int number = 1;
  while (std::getline(in, line) && line.rfind('#', 0) == 0) ++number;  // the manifest
  if (line.rfind(kHeaderStart, 0) != 0) {
    throw std::invalid_argument(file + ":" + std::to_string(number) + ": not a sweep CSV (no header)");
  }
  std::vector<SweepRow> rows;
  for (++number; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    try {
      rows.push_back(SweepRowFromCsvLine(line));
    } catch (const std::exception&) {
      throw std::invalid_argument(file + ":" + std::to_string(number) + ": not a sweep row");
    }
  }
  return rows;
}

SweepRow EvaluateGuarded(const PointEvaluator& evaluate, const SweepPoint& point) {
  SweepRow failed;
  failed.point = point;
  failed.status = "failed";
  try {
    return evaluate(point);
  } catch (const std::exception& e) {
    failed.reason = e.what();
  } catch (...) {
    failed.reason = "unknown exception";
  }
  return failed;
}

std::vector<SweepRow> RunSweep(const std::vector<SweepPoint>& points, const PointEvaluator& evaluate, int threads,
                               const Shard& shard, const SweepProgress& progress, const SweepRowSink& on_row) {
  std::vector<const SweepPoint*> mine;
  for (const SweepPoint& p : points) {
    if (shard.Holds(p.index)) mine.push_back(&p);
  }
  std::vector<SweepRow> rows(mine.size());
  std::atomic<std::size_t> next{0};
  std::mutex progress_mutex;
  int done = 0;
  const auto worker = [&] {
    for (std::size_t i = next++; i < mine.size(); i = next++) {
      rows[i] = EvaluateGuarded(evaluate, *mine[i]);
      if (progress || on_row) {
        const std::lock_guard<std::mutex> lock(progress_mutex);
        if (on_row) on_row(rows[i]);
        if (progress) progress(++done, static_cast<int>(mine.size()));
      }
    }
  };
  const int count = std::max(1, std::min(threads, static_cast<int>(mine.size())));
  std::vector<std::thread> pool;
  for (int t = 1; t < count; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  return rows;
}

std::string SweepCsvHeader(bool with_times) {
  const std::string header = std::string(kHeaderStart) + ",gait";
  return with_times ? header + ",plan_us,validate_us" : header;
}

std::string SweepToCsv(const std::vector<SweepRow>& rows, bool with_times) {
  std::ostringstream out;
  out << SweepCsvHeader(with_times) << "\n";
  for (const SweepRow& r : rows) out << SweepCsvLine(r, with_times) << "\n";
  return out.str();
}

std::string SweepCsvLine(const SweepRow& r, bool with_times) {
  std::ostringstream out;
  out << r.point.index << "," << ToString(r.point.direction) << "," << r.point.steps << "," << CsvNumber(r.point.rise)
      << "," << CsvNumber(r.point.run) << "," << CsvNumber(r.point.nosing) << "," << r.status << "," << CsvNumber(r.cadence_s)
      << "," << r.footsteps << "," << CsvNumber(r.min_clearance_m) << "," << CsvNumber(r.min_stability_margin_m) << ","
      << CsvQuoted(r.reason) << "," << GaitName(r.gait);
  if (with_times) out << "," << CsvNumber(r.plan_us) << "," << CsvNumber(r.validate_us);
  return out.str();
}

}  // namespace stairplan
