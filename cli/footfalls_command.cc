// `stairplan footfalls FILE.csv`: the staircases a robot walked, from its footfalls (seed 001).
#include <cmath>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "stairplan/perception/footfall_stairs.h"
#include "stairplan/geometry/stair_spec_yaml.h"
#include "cli/cli_common.h"
#include "stairplan/planning/json_version.h"

namespace stairplan::cli {
namespace {

nlohmann::json Xy(const Eigen::Vector2d& p) { return {p.x(), p.y()}; }
nlohmann::json Xyz(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

nlohmann::json StaircaseJson(const FootfallStaircase& s) {
  nlohmann::json edges = nlohmann::json::array();
  const std::vector<EdgeLine> lines = s.model.Edges();
  for (std::size_t k = 0; k < s.edges.size(); ++k) {
    edges.push_back({{"midpoint", Xyz(s.edges[k].midpoint)}, {"along", Xy(s.edges[k].along)}, {"a", Xyz(lines[k].a)}, {"b", Xyz(lines[k].b)}});
  }
  return {{"steps", s.model.steps}, {"rise", s.model.rise}, {"run", s.model.run}, {"direction", Xy(s.model.direction)},
          {"yaw_rad", s.model.yaw()}, {"traversal", ToString(s.traversal)}, {"width", s.model.width},
          {"uncertainty", s.model.uncertainty},
          {"center", Xy(s.model.center)}, {"tread_heights", s.tread_heights}, {"levels", s.model.levels},
          {"cluster_sizes", s.cluster_sizes}, {"edges", edges}, {"t_begin", s.t_begin}, {"t_end", s.t_end}};
}

// Staircase i of --stairs-out F.yaml: F.yaml for the first, F_1.yaml, F_2.yaml... for the others.
std::string StairsPath(const std::string& path, std::size_t i) {
  if (i == 0) return path;
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  const bool has_ext = dot != std::string::npos && (slash == std::string::npos || dot > slash);
  const std::string stem = has_ext ? path.substr(0, dot) : path;
  return stem + "_" + std::to_string(i) + (has_ext ? path.substr(dot) : "");
}

// The staircase as the YAML `plan --stairs` reads, traversed as it was walked.
std::string StairsYaml(const FootfallStaircase& s, const std::string& csv_path, std::size_t i, double nosing) {
  StairSpec spec;
  try {
    spec = s.model.ToStaircase(s.traversal, nosing).spec();
  } catch (const std::invalid_argument& e) {
    throw NoSolution("staircase " + std::to_string(i + 1) + " cannot be written as stairs YAML: " + e.what());
  }
  std::ostringstream comment;
  comment << "Staircase " << i + 1 << " walked " << ToString(s.traversal) << " from t = " << s.t_begin << " s to " << s.t_end
          << " s, found by stairplan " << kVersion << " footfalls in " << csv_path << "\n"
          << "plan with: stairplan plan --stairs FILE";
  return StairSpecToYaml(spec, comment.str());
}

int RunFootfalls(const std::vector<std::string>& args) {
  CLI::App app("Find the staircases a robot walked from its footfalls (CSV columns t,leg,x,y,z)", "footfalls");
  std::string path, stairs_out;
  bool json = false;
  double nosing = 0.0;
  FootfallStairsSettings settings;
  app.add_option("file", path, "Footfall CSV with the header t,leg,x,y,z")->required();
  app.add_option("--min-rise", settings.min_rise, "Smallest riser height [m] (default 0.08)");
  app.add_option("--max-rise", settings.max_rise, "Largest riser height [m] (default 0.30)");
  app.add_option("--min-depth", settings.min_depth, "Smallest horizontal step between treads [m] (default 0.12)");
  app.add_option("--max-depth", settings.max_depth, "Largest horizontal step between treads [m] (default 0.60)");
  app.add_option("--stairs-out", stairs_out,
                 "Write each staircase as the YAML that `stairplan plan --stairs` reads: the first to this file, the "
                 "others beside it with _1, _2... before the extension (F.yaml, F_1.yaml, ...), each with its `uncertainty`, "
                 "the bound on its nosings' error that the planners keep as clearance; exit 3 when none is found");
  app.add_option("--nosing", nosing,
                 "Nosing of the stairs written by --stairs-out [m]: footfalls find the walking edges but cannot see "
                 "the overhang, which a plan must clear (default 0)")
      ->check(CLI::Range(0.0, 0.1));
  app.add_flag("--json", json, "Print JSON (key staircases) instead of the summary");
  if (const int code = Parse(app, args); code >= 0) return code;
  return Guarded("footfalls", [&] {
    try {
      settings.Validate();
    } catch (const std::invalid_argument& e) {
      throw BadInput(std::string("--") + e.what());
    }
    const std::vector<Footfall> footfalls = ReadFootfallCsv(path);
    const std::vector<FootfallStaircase> found = StairsFromFootfalls(footfalls, settings);
    std::vector<std::string> yamls, written;  // every file made before any is written
    for (std::size_t i = 0; i < found.size() && !stairs_out.empty(); ++i) yamls.push_back(StairsYaml(found[i], path, i, nosing));
    for (std::size_t i = 0; i < yamls.size(); ++i) {
      written.push_back(StairsPath(stairs_out, i));
      WriteFileAtomically(written.back(), yamls[i]);
    }
    const int code = stairs_out.empty() || !found.empty() ? kExitOk : kExitInfeasible;
    if (code != kExitOk) std::cerr << "stairplan footfalls: " << path << ": no staircase found, no stairs YAML written\n";
    if (json) {
      nlohmann::json list = nlohmann::json::array();
      for (const auto& s : found) list.push_back(StaircaseJson(s));
      nlohmann::json out = {{"file", path}, {"footfalls", footfalls.size()}, {"staircases", list}, {"stairs_out", written}};
      std::cout << StampVersion(out).dump(2) << "\n";
      return code;
    }
    std::cout << "stairplan footfalls: " << path << ": " << footfalls.size() << " footfalls, " << found.size() << " staircases\n";
    for (std::size_t i = 0; i < found.size(); ++i) {
      const FootfallStaircase& s = found[i];
      std::cout << "  " << i + 1 << ": " << s.model.steps << " steps walked " << ToString(s.traversal) << ", rise " << s.model.rise
                << " m, run " << s.model.run << " m, nosings within " << s.model.uncertainty * 1000 << " mm, heading "
                << s.model.yaw() * 180.0 / M_PI << " deg, from t = " << s.t_begin
                << " s to " << s.t_end << " s" << (i < written.size() ? "; wrote " + written[i] : "") << "\n";
    }
    return code;
  });
}

const CommandRegistrar kFootfallsRegistrar({"footfalls", "find the staircases walked from a footfall CSV", RunFootfalls});

}  // namespace
}  // namespace stairplan::cli
