// `stairplan sweep`: plan and validate over a grid of stair geometries; CSV rows appended as points
// finish (so `--resume` continues a killed run), an SVG heatmap, threads, shards and MPI ranks with
// output identical for any split, and an atlas of several robots. `stairplan sweep-merge` joins
// the shards of one sweep and refuses anything else.
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>

#include "stairplan/geometry/field_error.h"
#include "cli/cli_common.h"
#include "cli/sweep_cluster.h"
#include "cli/sweep_journal.h"
#include "cli/sweep_progress.h"
#include "stairplan/pipeline/plan_pipeline.h"
#include "stairplan/simulation/sweep_physics.h"
#include "stairplan/sweep/pipeline_sweep_row.h"
#include "stairplan/sweep/sweep_atlas.h"
#include "stairplan/sweep/sweep_merge.h"
#include "stairplan/sweep/sweep_region.h"
#include "stairplan/sweep/sweep_runner.h"

namespace stairplan::cli {
namespace {

struct SweepOptions {
  std::string rise = "0.10:0.25:20", run = "0.20:0.35:20", nosing = "0.02", steps = "7";
  std::string directions = "up", facing = "forward", robot, robots, out, csv, svg, shard = "0/1";
  std::string gait = "crawl";
  int threads = 1;
  double validation_step = ValidationSettings{}.time_step;  // plan's: a coarser step judges a body QP at its knots alone
  bool times = false;
  bool simulate = false;
  bool resume = false;
  RobotFlags robot_flags;  // --package-path, --mesh-collision
};

// One robot's sweep: where its robot comes from and where its files go.
struct SweepJob {
  std::string label;  // the atlas's name for it (file stem); empty for a single sweep
  std::string robot_path;
  std::string csv;
  std::string svg;    // one heatmap with every direction
  std::string svg_per_direction_prefix;  // <prefix>-<direction>.svg (the atlas)
};

// One point's results: its row and, with --simulate, its physics.
struct PointOutcome {
  SweepRow row;
  std::optional<PhysicsRow> physics;
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

// One grid point through the same pipeline as `stairplan plan`, validation included; what it
// throws besides bad stairs is a "failed" row, so one broken point never ends a sweep.
PointOutcome Evaluate(const SweepPoint& point, const RobotModel& robot, const PipelineOptions& options,
                      const SweepPhysics* physics) {
  PointOutcome outcome;
  SweepRow& row = outcome.row;
  row.point = point;
  try {
    const Staircase stairs(point.Spec());
    const PipelineResult result = RunPipeline(robot, stairs, options);
    if (physics != nullptr) {
      outcome.physics = SimulateSweepPoint(point, robot, stairs, result, physics->settings(), physics->clearance());
    }
    row = PipelineSweepRow(point, result);
  } catch (const std::invalid_argument& e) {
    row.status = "bad_stairs";
    row.reason = e.what();
  } catch (const std::exception& e) {
    outcome = PointOutcome{};
    outcome.row.point = point;
    outcome.row.status = "failed";
    outcome.row.reason = e.what();
  }
  return outcome;
}

// A point's results as text, the same whichever rank or thread computed them: the plans row
// (with times) and, on a second line, the physics row.
std::string Serialize(const SweepRow& row, const std::string& physics_line) {
  return SweepCsvLine(row, true) + (physics_line.empty() ? "" : "\n" + physics_line);
}

std::string RobotIdentity(const std::string& path, const RobotModel& robot) {
  if (path.empty()) return robot.name() + " builtin";
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  std::uint64_t hash = 14695981039346656037ull;  // FNV-1a: the file's content, not its path
  for (unsigned char c : text.str()) hash = (hash ^ c) * 1099511628211ull;
  char hex[17];
  std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(hash));
  return robot.name() + " " + std::filesystem::path(path).filename().string() + " fnv1a=" + hex;
}

std::string SettingsText(const SweepOptions& o) {
  std::ostringstream s;
  s << "validation_step=" << o.validation_step << " simulate=" << (o.simulate ? "yes" : "no") << " gait=" << o.gait;
  return s.str();
}

// What every point plans with: the grid's facing, --validation-step and --gait.
PipelineOptions PointOptions(const SweepOptions& o, const SweepGrid& grid) {
  PipelineOptions options;
  options.facing = grid.facing;
  options.validation.time_step = o.validation_step;
  try {
    options.gait = ParseGaitChoice(o.gait);
  } catch (const std::invalid_argument& e) {
    throw BadInput(std::string("--") + e.what());
  }
  return options;
}

// Rank 0's output files of one robot's sweep, opened (and with --resume, read) before any point.
struct SweepFiles {
  std::unique_ptr<SweepJournal> plans;
  std::unique_ptr<SweepJournal> physics;  // with --simulate
};

SweepFiles OpenSweepFiles(const SweepOptions& o, const SweepGrid& grid, const Shard& shard, const SweepJob& job,
                          const RobotModel& robot) {
  const std::string identity = RobotIdentity(job.robot_path, robot);
  const auto manifest = [&](SweepTable table) { return SweepManifest::Current(table, grid, identity, SettingsText(o), shard); };
  SweepFiles files;
  files.plans = std::make_unique<SweepJournal>(job.csv, manifest(SweepTable::kPlans), SweepCsvHeader(o.times), o.resume);
  if (o.simulate) {
    files.physics = std::make_unique<SweepJournal>(job.csv + ".physics.csv", manifest(SweepTable::kPhysics),
                                                   PhysicsCsvHeader(), o.resume);
    files.physics->RetainOnly(files.plans->lines());  // a point whose row was lost is simulated again
    files.physics->Open();
  }
  files.plans->Open();
  return files;
}

// Computes `todo` on the cluster's ranks or on this process's threads; `deliver` gets each
// point's Serialize()d results, serialised.
void ComputePoints(SweepCluster* cluster, const std::vector<int>& todo, const std::vector<SweepPoint>& points,
                   const std::function<PointOutcome(const SweepPoint&)>& evaluate,
                   const std::function<void(const std::string&)>& deliver, int threads) {
  if (cluster != nullptr) {
    cluster->Run(todo, [&](int index) {
      const PointOutcome r = evaluate(points[static_cast<std::size_t>(index)]);
      return Serialize(r.row, r.physics ? PhysicsCsvLine(*r.physics) : "");
    }, deliver, threads);
    return;
  }
  std::vector<SweepPoint> mine;
  for (int index : todo) mine.push_back(points[static_cast<std::size_t>(index)]);
  std::mutex physics_mutex;
  std::map<int, std::string> physics_lines;  // from a worker's evaluation to its row's delivery
  RunSweep(mine, [&](const SweepPoint& p) {
    const PointOutcome r = evaluate(p);
    if (r.physics) {
      const std::lock_guard<std::mutex> lock(physics_mutex);
      physics_lines[p.index] = PhysicsCsvLine(*r.physics);
    }
    return r.row;
  }, threads, Shard{}, nullptr, [&](const SweepRow& row) {
    std::string line;
    {
      const std::lock_guard<std::mutex> lock(physics_mutex);
      if (const auto it = physics_lines.find(row.point.index); it != physics_lines.end()) line = it->second;
    }
    deliver(Serialize(row, line));
  });
}

// The finished sweep's heatmaps and summary; the agreement with physics when it was simulated.
void ReportSweep(const std::vector<SweepRow>& rows, const SweepGrid& grid, const Shard& shard, const SweepJob& job,
                 const std::string& throughput, const SweepJournal* physics) {
  if (!job.svg.empty()) WriteFileAtomically(job.svg, SweepHeatmapSvg(rows, grid));
  for (TravelDirection d : grid.directions) {
    if (job.svg_per_direction_prefix.empty()) break;
    SweepGrid one = grid;
    one.directions = {d};
    WriteFileAtomically(job.svg_per_direction_prefix + "-" + ToString(d) + ".svg", SweepHeatmapSvg(rows, one));
  }
  int valid = 0;
  for (const SweepRow& r : rows) valid += r.status == "valid" ? 1 : 0;
  std::cout << "stairplan sweep" << (job.label.empty() ? "" : " (" + job.label + ")") << ": " << rows.size()
            << " points, " << valid << " valid; " << throughput << "\n";
  // The shape of the success region; a shard sees only its own points, so it says nothing.
  if (shard.count == 1) std::cout << SweepRegionsToText(AnalyseSweepRegions(rows));
  if (physics == nullptr) return;
  SweepPhysics collected;
  for (const auto& [index, line] : physics->lines()) collected.Add(PhysicsRowFromCsvLine(line));
  std::cout << "physics passes: got there, feet in their regions, no other link on the stairs\n"
            << AgreementToText(collected.Agreement()) << "... and no other link within the validator's "
            << ValidationSettings{}.min_clearance * 1000 << " mm of the stairs\n"
            << AgreementToText(collected.Agreement(true));
}

// Runs one robot's sweep; on rank 0 (or without MPI) returns the rows of the finished CSV.
// `options` are what every point plans with (PointOptions).
std::optional<std::vector<SweepRow>> SweepRobot(const SweepOptions& o, const SweepGrid& grid, const PipelineOptions& options,
                                                const Shard& shard, SweepCluster* cluster, const SweepJob& job) {
  const bool coordinator = cluster == nullptr || cluster->Rank() == 0;
  std::optional<RobotModel> robot;
  SweepFiles files;
  try {
    robot.emplace(LoadRobot(job.robot_path, o.robot_flags));
    if (coordinator) files = OpenSweepFiles(o, grid, shard, job, *robot);
  } catch (...) {
    if (cluster != nullptr) cluster->AllReady(false);
    throw;
  }
  if (cluster != nullptr && !cluster->AllReady(true)) {
    if (coordinator) throw BadInput("another MPI rank could not start the sweep (see its message)");
    return std::nullopt;
  }
  const std::vector<SweepPoint> points = EnumeratePoints(grid);
  std::vector<int> todo;
  for (const SweepPoint& p : points) {
    if (shard.Holds(p.index) && (!files.plans || files.plans->lines().count(p.index) == 0)) todo.push_back(p.index);
  }
  todo = SlowestFirst(std::move(todo), points);
  const int already = files.plans ? static_cast<int>(files.plans->lines().size()) : 0;
  SweepProgressReport progress(job.label.empty() ? "" : job.label + " ", already + static_cast<int>(todo.size()),
                               already, isatty(STDERR_FILENO) != 0);
  int done = 0;
  const auto deliver = [&](const std::string& text) {
    const std::size_t newline = text.find('\n');
    const SweepRow row = SweepRowFromCsvLine(text.substr(0, newline));
    if (newline != std::string::npos && files.physics) files.physics->Append(row.point.index, text.substr(newline + 1));
    files.plans->Append(row.point.index, SweepCsvLine(row, o.times));  // after its physics: a row means all is there
    progress.Update(++done);
  };
  const SweepPhysics physics_settings;
  const SweepPhysics* physics = o.simulate ? &physics_settings : nullptr;
  const auto start = std::chrono::steady_clock::now();
  ComputePoints(cluster, todo, points, [&](const SweepPoint& p) { return Evaluate(p, *robot, options, physics); },
                deliver, o.threads);
  if (!coordinator) return std::nullopt;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::vector<SweepRow> rows = SweepRowsFromCsv(files.plans->Finish(), job.csv);
  if (files.physics) files.physics->Finish();
  const int workers = cluster != nullptr ? cluster->Size() - 1 + o.threads : o.threads;
  std::ostringstream throughput;
  throughput << done << " computed in " << seconds << " s on " << workers << " worker(s)"
             << (cluster != nullptr ? " over " + std::to_string(cluster->Size()) + " MPI rank(s)" : "") << ", "
             << (seconds > 0 ? done / seconds : 0.0) << " points/s";
  ReportSweep(rows, grid, shard, job, throughput.str(), files.physics.get());
  return rows;
}

std::vector<std::string> SplitEntries(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, ',');) parts.push_back(part);
  return parts;
}

// The jobs of this run: one sweep, or with --robots one per robot into --out.
std::vector<SweepJob> Jobs(const SweepOptions& o) {
  if (o.robots.empty()) {
    if (o.csv.empty()) throw BadInput("--csv: required (or --robots with --out for an atlas)");
    if (!o.out.empty()) throw BadInput("--out: only with --robots (a single sweep writes --csv and --svg)");
    return {{"", o.robot, o.csv, o.svg, ""}};
  }
  if (o.out.empty()) throw BadInput("--robots: needs --out DIR for the atlas's files");
  if (!o.csv.empty() || !o.svg.empty() || !o.robot.empty()) {
    throw BadInput("--robots: writes into --out; --csv, --svg and --robot are for a single sweep");
  }
  MakeOutputDir(o.out, "--out");
  std::vector<SweepJob> jobs;
  for (const std::string& entry : SplitEntries(o.robots)) {
    if (entry.empty()) throw BadInput("--robots: an empty entry in '" + o.robots + "'");
    const bool builtin = entry == "builtin";
    SweepJob job;
    job.label = builtin ? "stairbot" : std::filesystem::path(entry).stem().string();
    job.robot_path = builtin ? "" : entry;
    for (const SweepJob& other : jobs) {
      if (other.label == job.label) throw BadInput("--robots: two robots named '" + job.label + "'");
    }
    job.csv = o.out + "/" + job.label + ".csv";
    job.svg_per_direction_prefix = o.out + "/" + job.label;
    jobs.push_back(job);
  }
  return jobs;
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
  app.add_option("--gait", o.gait, "crawl (default), walk, trot, or auto: the fastest gait that validates (as plan's)");
  app.add_option("--robot", o.robot, "Robot URDF (default: the built-in stairbot)");
  app.add_option("--robots", o.robots,
                 "An atlas: comma-separated URDFs ('builtin' for stairbot), each swept into --out DIR: "
                 "<robot>.csv, <robot>-<direction>.svg, and atlas.md with each robot's feasible region");
  app.add_option("--out", o.out, "The atlas's output folder (with --robots)");
  AddRobotFlags(app, o.robot_flags);
  app.add_option("--threads", o.threads,
                 "Worker threads (default 1; under mpirun, rank 0's); the output does not depend on it")
      ->check(CLI::Range(1, 256));
  app.add_option("--shard", o.shard, "Compute only shard i of N (i/N); join with sweep-merge");
  app.add_option("--csv", o.csv, "Output CSV file: a manifest ('#' lines), the header, a row per point");
  app.add_option("--svg", o.svg, "Output SVG heatmap");
  app.add_option("--validation-step", o.validation_step, "Validator replay step [s] (default 0.02, as plan)")
      ->check(CLI::Range(1e-3, 1.0));
  app.add_flag("--times", o.times, "Add plan_us and validate_us columns (not reproducible)");
  app.add_flag("--simulate", o.simulate,
               "Also execute every plan in MuJoCo: physics columns in <csv>.physics.csv, agreement on stdout");
  app.add_flag("--resume", o.resume,
               "Continue the sweep in --csv (same flags): keep its finished rows, compute the rest");
  if (const int code = Parse(app, args); code >= 0) return code;
  std::unique_ptr<SweepCluster> cluster;
  return Guarded("sweep", [&] {
    cluster = JoinSweepCluster();  // rows are computed on every rank, written by rank 0
    SweepGrid grid;
    PipelineOptions options;
    Shard shard;
    std::vector<SweepJob> jobs;
    try {
      grid = ParseGrid(o);
      options = PointOptions(o, grid);  // a bad --gait is refused before any file is written
      shard = Shard::Parse(o.shard, "--shard");
      jobs = Jobs(o);
    } catch (const FieldError& e) {
      throw BadInput(e.what());
    }
    std::vector<std::pair<std::string, std::vector<SweepRow>>> atlas;
    for (const SweepJob& job : jobs) {
      std::optional<std::vector<SweepRow>> rows = SweepRobot(o, grid, options, shard, cluster.get(), job);
      if (!rows) return kExitOk;  // a rank other than 0: rank 0 reports
      atlas.emplace_back(job.label, std::move(*rows));
    }
    if (!o.robots.empty() && shard.count == 1) {
      const std::string table = SweepAtlasMarkdown(atlas, grid);
      WriteFileAtomically(o.out + "/atlas.md", table);
      std::cout << table;
    }
    return kExitOk;
  });
}

std::string ReadInput(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw BadInput(path + ": cannot open");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

int RunSweepMerge(const std::vector<std::string>& args) {
  CLI::App app("Merge the shards of one sweep into the CSV of the whole sweep", "sweep-merge");
  std::string out, svg;
  std::vector<std::string> inputs;
  app.add_option("--csv", out, "Output CSV file (with --simulate shards, also <csv>.physics.csv)")->required();
  app.add_option("--svg", svg, "Output SVG heatmap of the merged sweep");
  app.add_option("inputs", inputs, "Shard CSV files, one per shard of the same sweep")->required();
  if (const int code = Parse(app, args); code >= 0) return code;
  return Guarded("sweep-merge", [&] {
    std::vector<std::pair<std::string, std::string>> texts;
    for (const std::string& path : inputs) texts.emplace_back(path, ReadInput(path));
    const std::string merged = MergeSweepCsv(texts);
    const SweepManifest manifest = SweepManifest::FromText(merged, out);
    if (manifest.table != SweepTable::kPlans) throw BadInput(inputs.front() + ": a physics CSV; give the plans CSVs (their .physics.csv files are merged with them)");
    const std::vector<SweepRow> rows = SweepRowsFromCsv(merged, out);
    // --simulate shards: each plans CSV has its physics CSV beside it, merged the same way.
    std::string physics;
    if (manifest.settings.find("simulate=yes") != std::string::npos) {
      std::vector<std::pair<std::string, std::string>> parts;
      for (const std::string& path : inputs) parts.emplace_back(path + ".physics.csv", ReadInput(path + ".physics.csv"));
      physics = MergeSweepCsv(parts);
    }
    WriteFileAtomically(out, merged);
    if (!svg.empty()) WriteFileAtomically(svg, SweepHeatmapSvg(rows, manifest.grid));
    std::cout << SweepRegionsToText(AnalyseSweepRegions(rows));  // the whole sweep's success region
    if (!physics.empty()) {
      WriteFileAtomically(out + ".physics.csv", physics);
      SweepPhysics collected;
      for (const auto& [index, line] : ReadSweepTable(physics, out + ".physics.csv").lines) {
        collected.Add(PhysicsRowFromCsvLine(line));
      }
      std::cout << "physics passes: got there, feet in their regions, no other link on the stairs\n"
                << AgreementToText(collected.Agreement());
    }
    return kExitOk;
  });
}

const CommandRegistrar kSweep({"sweep", "plan and validate over a grid of stair geometries (CSV, SVG)", RunSweepCommand});
const CommandRegistrar kMerge({"sweep-merge", "merge sweep shards into one CSV", RunSweepMerge});

}  // namespace
}  // namespace stairplan::cli
