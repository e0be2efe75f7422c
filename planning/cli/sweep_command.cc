// `stairplan sweep`: plan and validate over a grid of stair geometries; CSV rows, an SVG heatmap,
// threads and shards with output identical for any split. `stairplan sweep-merge` joins shards.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "geometry/field_error.h"
#include "planning/cli/cli_common.h"
#include "planning/plan_pipeline.h"
#include "planning/simulation/sweep_physics.h"
#include "planning/sweep/sweep_region.h"
#include "planning/sweep/sweep_runner.h"

namespace stairplan::cli {
namespace {

struct SweepOptions {
  std::string rise = "0.10:0.25:20", run = "0.20:0.35:20", nosing = "0.02", steps = "7";
  std::string directions = "up", facing = "forward", robot, csv, svg, shard = "0/1";
  int threads = 1;
  double validation_step = 0.05;
  bool times = false;
  bool simulate = false;
};

SweepGrid ParseGrid(const SweepOptions& o) {
  SweepGrid grid;
  grid.rise = SweepAxis::Parse(o.rise, "--rise");
  grid.run = SweepAxis::Parse(o.run, "--run");
  grid.nosing = SweepAxis::Parse(o.nosing, "--nosing");
  grid.steps = SweepAxis::Parse(o.steps, "--steps");
  grid.directions = ParseDirections(o.directions, "--direction");
  if (o.facing != "forward" && o.facing != "backward") {
    throw BadInput("--facing: must be 'forward' or 'backward' (got '" + o.facing + "')");
  }
  grid.facing = o.facing == "forward" ? Facing::kForward : Facing::kBackward;
  return grid;
}

// One grid point through the same pipeline as `stairplan plan`, validation included.
SweepRow Evaluate(const SweepPoint& point, const RobotModel& robot, Facing facing, double validation_step,
                  SweepPhysics* physics) {
  SweepRow row;
  row.point = point;
  try {
    const Staircase stairs(point.Spec());
    PipelineOptions options;
    options.facing = facing;
    options.validation.time_step = validation_step;
    const PipelineResult result = RunPipeline(robot, stairs, options);
    if (physics != nullptr) physics->Record(point, robot, stairs, result);
    row.cadence_s = result.plan.cadence_s;
    row.footsteps = static_cast<int>(result.plan.footsteps.size());
    for (const auto& [stage, us] : result.plan.timing_us) (stage == "validate" ? row.validate_us : row.plan_us) += us;
    if (result.plan.status != PlanStatus::kOk) {
      row.status = "infeasible";
      row.reason = result.plan.status_reason;
      return row;
    }
    const ValidationReport& v = result.validation;
    row.min_clearance_m = v.min_clearance_m;
    row.min_stability_margin_m = v.min_stability_margin_m;
    row.status = v.ok ? "valid" : "invalid";
    if (!v.violations.empty()) {
      const Violation& first = v.violations.front();
      row.reason = std::string(ToString(first.kind)) + " " + first.leg + (first.detail.empty() ? "" : " " + first.detail);
    }
  } catch (const std::invalid_argument& e) {
    row.status = "bad_stairs";
    row.reason = e.what();
  }
  return row;
}

void ShowProgress(int done, int total) {
  const int width = 40, filled = total > 0 ? width * done / total : width;
  std::fprintf(stderr, "\r[%s%s] %d/%d", std::string(static_cast<std::size_t>(filled), '#').c_str(),
               std::string(static_cast<std::size_t>(width - filled), '.').c_str(), done, total);
  if (done == total) std::fprintf(stderr, "\n");
}

int RunSweepCommand(const std::vector<std::string>& args) {
  CLI::App app("Plan and validate over a grid of stair geometries", "sweep");
  SweepOptions o;
  app.add_option("--rise", o.rise, "Rise axis A:B:N or a value [m] (default 0.10:0.25:20)");
  app.add_option("--run", o.run, "Run axis A:B:N or a value [m] (default 0.20:0.35:20)");
  app.add_option("--nosing", o.nosing, "Nosing axis A:B:N or a value [m] (default 0.02)");
  app.add_option("--steps", o.steps, "Step count axis A:B:N or a value (default 7)");
  app.add_option("--direction", o.directions, "up, down or up,down (default up)");
  app.add_option("--facing", o.facing, "forward or backward (default forward)");
  app.add_option("--robot", o.robot, "Robot URDF (default: the built-in stairbot)");
  RobotFlags robot_flags;
  AddRobotFlags(app, robot_flags);
  app.add_option("--threads", o.threads, "Worker threads (default 1); the output does not depend on it")
      ->check(CLI::Range(1, 256));
  app.add_option("--shard", o.shard, "Compute only shard i of N (i/N); join with sweep-merge");
  app.add_option("--csv", o.csv, "Output CSV file")->required();
  app.add_option("--svg", o.svg, "Output SVG heatmap");
  app.add_option("--validation-step", o.validation_step, "Validator replay step [s] (default 0.05; plan uses 0.02)")
      ->check(CLI::Range(1e-3, 1.0));
  app.add_flag("--times", o.times, "Add plan_us and validate_us columns (not reproducible)");
  app.add_flag("--simulate", o.simulate,
               "Also execute every plan in MuJoCo: physics columns in <csv>.physics.csv, agreement on stdout");
  if (const int code = Parse(app, args); code >= 0) return code;
  return Guarded("sweep", [&] {
    SweepGrid grid;
    Shard shard;
    try {
      grid = ParseGrid(o);
      shard = Shard::Parse(o.shard, "--shard");
    } catch (const FieldError& e) {
      throw BadInput(e.what());
    }
    const RobotModel robot = LoadRobot(o.robot, robot_flags);
    const std::vector<SweepPoint> points = EnumeratePoints(grid);
    const bool terminal = isatty(STDERR_FILENO) != 0;
    const auto start = std::chrono::steady_clock::now();
    std::unique_ptr<SweepPhysics> physics = o.simulate ? std::make_unique<SweepPhysics>() : nullptr;
    const std::vector<SweepRow> rows = RunSweep(
        points, [&](const SweepPoint& p) { return Evaluate(p, robot, grid.facing, o.validation_step, physics.get()); }, o.threads, shard,
        terminal ? SweepProgress(ShowProgress) : SweepProgress());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    WriteFileAtomically(o.csv, SweepToCsv(rows, o.times));
    if (!o.svg.empty()) WriteFileAtomically(o.svg, SweepHeatmapSvg(rows, grid));
    int valid = 0;
    for (const SweepRow& r : rows) valid += r.status == "valid" ? 1 : 0;
    std::cout << "stairplan sweep: " << rows.size() << " points, " << valid << " valid; " << seconds << " s on "
              << o.threads << " thread(s), " << (seconds > 0 ? rows.size() / seconds / o.threads : 0.0)
              << " points/s per thread\n";
    // The shape of the success region; a shard sees only its own points, so it says nothing.
    if (shard.count == 1) std::cout << SweepRegionsToText(AnalyseSweepRegions(rows));
    if (physics) {
      WriteFileAtomically(o.csv + ".physics.csv", physics->Csv());
      std::cout << "physics passes: got there, feet in their regions, no other link on the stairs\n"
                << AgreementToText(physics->Agreement()) << "... and no other link within the validator's "
                << ValidationSettings{}.min_clearance * 1000 << " mm of the stairs\n"
                << AgreementToText(physics->Agreement(true));
    }
    return kExitOk;
  });
}

int RunSweepMerge(const std::vector<std::string>& args) {
  CLI::App app("Merge sweep shards into the CSV of the whole sweep", "sweep-merge");
  std::string out;
  std::vector<std::string> inputs;
  app.add_option("--csv", out, "Output CSV file")->required();
  app.add_option("inputs", inputs, "Shard CSV files")->required();
  if (const int code = Parse(app, args); code >= 0) return code;
  return Guarded("sweep-merge", [&] {
    std::vector<std::pair<std::string, std::string>> texts;
    for (const std::string& path : inputs) {
      std::ifstream in(path);
      if (!in) throw BadInput(path + ": cannot open");
      std::stringstream buffer;
      buffer << in.rdbuf();
      texts.emplace_back(path, buffer.str());
    }
    const std::string merged = MergeSweepCsv(texts);
    std::vector<SweepRow> rows;
    try {
      rows = SweepRowsFromCsv(merged, out);
    } catch (const std::invalid_argument& e) {
      throw BadInput(e.what());
    }
    WriteFileAtomically(out, merged);
    std::cout << SweepRegionsToText(AnalyseSweepRegions(rows));  // the whole sweep's success region
    return kExitOk;
  });
}

const CommandRegistrar kSweep({"sweep", "plan and validate over a grid of stair geometries (CSV, SVG)", RunSweepCommand});
const CommandRegistrar kMerge({"sweep-merge", "merge sweep shards into one CSV", RunSweepMerge});

}  // namespace
}  // namespace stairplan::cli
