// `stairplan map --cloud FILE`: perception on a point cloud: the height map with its gaps filled,
// the stairs the tracker fits, and the constrained map built from them (seed 000 [0038]-[0048]).
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "stairplan/perception/stair_perception.h"
#include "stairplan/geometry/stair_spec_yaml.h"
#include "cli/cli_common.h"
#include "stairplan/planning/json_version.h"

namespace stairplan::cli {
namespace {

nlohmann::json MapXy(const Eigen::Vector2d& p) { return {p.x(), p.y()}; }
nlohmann::json MapXyz(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

nlohmann::json StairsJson(const StairFit& fit) {
  if (!fit.found) return nullptr;
  const StairModel& m = fit.model;
  nlohmann::json edges = nlohmann::json::array();
  for (const EdgeLine& e : m.Edges()) edges.push_back({{"a", MapXyz(e.a)}, {"b", MapXyz(e.b)}});
  return {{"steps", m.steps}, {"rise", m.rise}, {"run", m.run}, {"yaw_rad", m.yaw()}, {"width", m.width},
          {"uncertainty", m.uncertainty},
          {"direction", MapXy(m.direction)}, {"center", MapXy(m.center)}, {"levels", m.levels}, {"edges", edges},
          {"residuals", {{"level_rms", fit.level_rms}, {"edge_rms", fit.edge_rms}, {"point_rms", fit.point_rms},
                         {"tread_points", fit.tread_points}, {"levels", fit.level_residuals}, {"edges", fit.edge_residuals}}}};
}

// The constrained map, its polygons placed in the world so they overlay the cloud.
nlohmann::json MapJson(const PerceivedStairs& seen, const StairModel& model, const MapFromHeightMapSettings& s) {
  const auto world = [&](const Polygon2& p) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& v : p.vertices) out.push_back(MapXy(model.StairToWorld(Eigen::Vector3d(v.x(), v.y(), 0.0), s.travel, s.nosing).head<2>()));
    return out;
  };
  nlohmann::json stairs = nlohmann::json::array();
  for (const StairRegions& r : seen.map.stairs()) {
    nlohmann::json regions = nlohmann::json::array();
    for (const CollisionRegion& c : r.collision_regions) regions.push_back({{"kind", ToString(c.kind)}, {"polygon_W", world(c.polygon)}});
    stairs.push_back({{"index", r.index}, {"z_W", r.z + (model.levels.empty() ? 0.0 : model.levels.front())},
                      {"step_region_W", world(r.step_region)}, {"collision_regions", regions}});
  }
  return {{"travel", ToString(s.travel)}, {"facing", ToString(s.facing)}, {"edge_bands", seen.edge_bands},
          {"data_bands", seen.data_bands}, {"stairs", stairs}};
}

// map.svg: the height map from above with the fitted edges and step regions, inside a frame of
// axes in metres under a title and a legend.
std::string Svg(const StairPerception& p, const MapFromHeightMapSettings& s) {
  const HeightMap& m = p.height_map;
  constexpr double kScale = 200.0;  // px per m
  constexpr double kMarginLeft = 60.0, kMarginTop = 70.0, kMarginBottom = 50.0, kMarginRight = 20.0;
  const double w = m.nx() * m.resolution() * kScale, h = m.ny() * m.resolution() * kScale;
  float lo = 1e9f, hi = -1e9f;
  for (int iy = 0; iy < m.ny(); ++iy) {
    for (int ix = 0; ix < m.nx(); ++ix) {
      if (m.state(ix, iy) == CellState::kUnknown) continue;
      lo = std::min(lo, m.height(ix, iy));
      hi = std::max(hi, m.height(ix, iy));
    }
  }
  const auto px = [&](const Eigen::Vector2d& p_W) {
    return Eigen::Vector2d(kMarginLeft + (p_W.x() - m.origin().x()) * kScale, kMarginTop + h - (p_W.y() - m.origin().y()) * kScale);
  };
  std::ostringstream title;
  title << std::setprecision(3) << "stairplan map: " << m.nx() << " x " << m.ny() << " cells of " << m.resolution() * 100
        << " cm, heights " << lo << " to " << hi << " m (dark to light); ";
  if (p.fit.found) {
    title << p.fit.model.steps << " steps fitted, rise " << p.fit.model.rise << " m, run " << p.fit.model.run << " m";
  } else {
    title << "no stairs (" << p.fit.reason << ")";
  }
  std::ostringstream out;
  const double width = std::max({kMarginLeft + w + kMarginRight, 720.0, kMarginLeft + 7.5 * static_cast<double>(title.str().size())});
  const double height = kMarginTop + h + kMarginBottom;
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height << "\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<g font-family=\"sans-serif\" font-size=\"12\">\n";
  out << "<text x=\"" << kMarginLeft << "\" y=\"18\" font-size=\"13\" font-weight=\"bold\">" << title.str() << "</text>\n";
  double x = kMarginLeft;
  const auto item = [&](const std::string& style, const std::string& label) {
    out << "<rect x=\"" << x << "\" y=\"30\" width=\"12\" height=\"12\" " << style << "/><text x=\"" << x + 16
        << "\" y=\"41\">" << label << "</text>\n";
    x += 34 + 6.5 * static_cast<double>(label.size());
  };
  item("fill=\"rgb(140,140,140)\"", "measured");
  item("fill=\"rgb(140,140,200)\"", "filled flat (occluded)");
  item("fill=\"rgb(140,180,140)\"", "filled smoothly");
  item("fill=\"rgb(255,140,140)\"", "poor");
  item("fill=\"black\"", "fitted edges");
  item("fill=\"none\" stroke=\"rgb(0,160,0)\" stroke-width=\"2\"", "step regions");
  // Axes in world metres, ticks every half metre.
  const double x0 = m.origin().x(), x1 = x0 + m.nx() * m.resolution();
  const double y0 = m.origin().y(), y1 = y0 + m.ny() * m.resolution();
  const double base = kMarginTop + h + 6, left = kMarginLeft - 6;
  out << "<line x1=\"" << kMarginLeft << "\" y1=\"" << base << "\" x2=\"" << kMarginLeft + w << "\" y2=\"" << base << "\" stroke=\"#222\"/>\n";
  for (double t = std::ceil(x0 * 2) / 2; t <= x1 + 1e-9; t += 0.5) {
    const double u = px({t, y0}).x();
    out << "<line x1=\"" << u << "\" y1=\"" << base << "\" x2=\"" << u << "\" y2=\"" << base + 5 << "\" stroke=\"#222\"/><text x=\""
        << u - 10 << "\" y=\"" << base + 18 << "\">" << (std::abs(t) < 1e-9 ? 0.0 : t) << "</text>\n";
  }
  out << "<text x=\"" << kMarginLeft + w - 40 << "\" y=\"" << base + 34 << "\">x [m]</text>\n";
  out << "<line x1=\"" << left << "\" y1=\"" << kMarginTop << "\" x2=\"" << left << "\" y2=\"" << kMarginTop + h << "\" stroke=\"#222\"/>\n";
  for (double t = std::ceil(y0 * 2) / 2; t <= y1 + 1e-9; t += 0.5) {
    const double v = px({x0, t}).y();
    out << "<line x1=\"" << left - 5 << "\" y1=\"" << v << "\" x2=\"" << left << "\" y2=\"" << v << "\" stroke=\"#222\"/><text x=\"4\" y=\""
        << v + 4 << "\">" << (std::abs(t) < 1e-9 ? 0.0 : t) << "</text>\n";
  }
  out << "<text x=\"4\" y=\"" << kMarginTop - 8 << "\">y [m]</text>\n</g>\n";
  const double cell = m.resolution() * kScale;
  for (int iy = 0; iy < m.ny(); ++iy) {
    for (int ix = 0; ix < m.nx(); ++ix) {
      const CellState state = m.state(ix, iy);
      if (state == CellState::kUnknown) continue;
      const int g = static_cast<int>(40 + 200 * (m.height(ix, iy) - lo) / std::max(1e-6f, hi - lo));
      const int r = state == CellState::kPoor ? 255 : g, gg = state == CellState::kSmoothed ? std::min(255, g + 40) : g;
      const int b = state == CellState::kOccluded ? std::min(255, g + 60) : g;
      const Eigen::Vector2d c = px(m.CellCenter(ix, iy));
      out << "<rect x=\"" << c.x() - 0.5 * cell << "\" y=\"" << c.y() - 0.5 * cell << "\" width=\"" << cell << "\" height=\"" << cell
          << "\" fill=\"rgb(" << r << "," << gg << "," << b << ")\"/>\n";
    }
  }
  if (p.fit.found) {
    for (const EdgeLine& e : p.fit.model.Edges()) {
      const Eigen::Vector2d a = px(e.a.head<2>()), b = px(e.b.head<2>());
      out << "<line x1=\"" << a.x() << "\" y1=\"" << a.y() << "\" x2=\"" << b.x() << "\" y2=\"" << b.y() << "\" stroke=\"black\" stroke-width=\"2\"/>\n";
    }
  }
  if (p.stairs) {
    for (const StairRegions& r : p.stairs->map.stairs()) {
      if (r.step_region.empty()) continue;
      out << "<polygon fill=\"none\" stroke=\"rgb(0,160,0)\" stroke-width=\"2\" points=\"";
      for (const auto& v : r.step_region.vertices) {
        const Eigen::Vector2d q = px(p.fit.model.StairToWorld(Eigen::Vector3d(v.x(), v.y(), 0.0), s.travel, s.nosing).head<2>());
        out << q.x() << "," << q.y() << " ";
      }
      out << "\"/>\n";
    }
  }
  out << "</svg>\n";
  return out.str();
}

// The perceived stairs for `plan --stairs`; the comment places their frame in the cloud's.
std::string StairsYaml(const PerceivedStairs& seen, const StairModel& model, const MapFromHeightMapSettings& s,
                       const std::string& cloud_path) {
  const Eigen::Vector3d origin = model.StairToWorld(Eigen::Vector3d::Zero(), s.travel, s.nosing);
  std::ostringstream comment;
  comment << "Stairs fitted by stairplan " << kVersion << " map from " << cloud_path << "; plan with: stairplan plan --stairs FILE\n"
          << "In the cloud's frame this staircase's origin is (" << origin.x() << ", " << origin.y() << ", " << origin.z()
          << ") m and its x axis heads " << model.TravelYaw(s.travel) << " rad.";
  return StairSpecToYaml(seen.stairs.spec(), comment.str());
}

Facing ParseFacingFlag(const std::string& text) {
  if (text == "forward") return Facing::kForward;
  if (text == "backward") return Facing::kBackward;
  throw BadInput("--facing: must be 'forward' or 'backward' (got '" + text + "')");
}

int RunMap(const std::vector<std::string>& args) {
  CLI::App app("Map stairs from a point cloud: height map, fitted stairs, constrained map.\n"
               "Exit 0 when stairs were found, 3 when the cloud is not stairs, 2 on bad input.", "map");
  std::string cloud_path, svg_path, stairs_out, direction = "up", facing = "forward";
  double resolution = 0.02;
  bool json = false;
  app.add_option("--cloud", cloud_path,
                 "Point cloud: PLY (ascii or binary little-endian), PCD (ascii, binary or binary_compressed) or x y z "
                 "text, told apart by the content")
      ->required();
  app.add_option("--direction", direction, "How the robot will traverse the stairs: up or down (default up)");
  app.add_option("--facing", facing, "forward or backward (default forward)");
  app.add_option("--resolution", resolution, "Height-map cell size [m] (default 0.02)");
  app.add_option("--svg", svg_path, "Write a top view of the map to this SVG file");
  app.add_option("--stairs-out", stairs_out,
                 "Write the fitted stairs as the YAML that `stairplan plan --stairs` reads (in the stairs' own frame; "
                 "a comment says where that frame lies in the cloud's), with the fit's `uncertainty`, the bound on its "
                 "nosings' error that the planners keep as clearance");
  app.add_flag("--json", json, "Print JSON (keys cloud, height_map, stairs, map) instead of the summary");
  if (const int code = Parse(app, args); code >= 0) return code;
  return Guarded("map", [&] {
    StairPerceptionSettings settings;
    settings.height_map.resolution = resolution;
    settings.regions.travel = ParseDirection(direction, "--direction");
    settings.regions.facing = ParseFacingFlag(facing);
    try {
      settings.height_map.Validate();
    } catch (const std::invalid_argument& e) {
      throw BadInput(std::string("--") + e.what());
    }
    const PointCloud cloud = ReadPointCloud(cloud_path);
    const StairPerception p = PerceiveStairs(cloud, settings);
    const HeightMap& m = p.height_map;
    nlohmann::json out = {
        {"cloud", {{"file", cloud_path}, {"points", cloud.size()}}},
        {"height_map", {{"resolution", m.resolution()}, {"nx", m.nx()}, {"ny", m.ny()}, {"origin", MapXy(m.origin())},
                        {"measured", m.CountState(CellState::kMeasured)}, {"occluded", m.CountState(CellState::kOccluded)},
                        {"smoothed", m.CountState(CellState::kSmoothed)}, {"poor", m.CountState(CellState::kPoor)},
                        {"unknown", m.CountState(CellState::kUnknown)}}},
        {"stairs", StairsJson(p.fit)},
        {"reason", p.fit.reason},
        {"map", p.stairs ? MapJson(*p.stairs, p.fit.model, settings.regions) : nlohmann::json(nullptr)}};
    StampVersion(out);
    if (!svg_path.empty()) WriteFileAtomically(svg_path, Svg(p, settings.regions));
    if (!stairs_out.empty() && p.stairs) WriteFileAtomically(stairs_out, StairsYaml(*p.stairs, p.fit.model, settings.regions, cloud_path));
    if (json) {
      std::cout << out.dump(2) << "\n";
    } else {
      std::cout << "stairplan map: " << cloud_path << ": " << cloud.size() << " points\n"
                << "  height map: " << m.nx() << " x " << m.ny() << " cells of " << m.resolution() << " m; "
                << m.CountState(CellState::kMeasured) << " measured, " << m.CountState(CellState::kOccluded) << " filled flat (occluded), "
                << m.CountState(CellState::kSmoothed) << " filled smoothly, " << m.CountState(CellState::kPoor) << " poor, "
                << m.CountState(CellState::kUnknown) << " unknown\n";
      if (p.fit.found) {
        const StairModel& s = p.fit.model;
        std::cout << "  stairs:     " << s.steps << " steps, rise " << s.rise << " m, run " << s.run << " m, yaw "
                  << s.yaw() * 180.0 / M_PI << " deg, width " << s.width << " m; nosings within " << s.uncertainty * 1000
                  << " mm\n"
                  << "  residuals:  levels " << p.fit.level_rms << " m, edges " << p.fit.edge_rms << " m, tread points "
                  << p.fit.point_rms << " m rms\n"
                  << "  map:        " << p.stairs->map.size() << " surfaces (" << ToString(settings.regions.travel) << ", facing "
                  << ToString(settings.regions.facing) << "), " << p.stairs->edge_bands << " edge and " << p.stairs->data_bands
                  << " data collision bands from the data\n";
      } else {
        std::cout << "  stairs:     none (" << p.fit.reason << ")\n";
      }
      if (!svg_path.empty()) std::cout << "  wrote:      " << svg_path << "\n";
      if (!stairs_out.empty() && p.stairs) std::cout << "  wrote:      " << stairs_out << "\n";
    }
    return p.fit.found ? kExitOk : kExitInfeasible;
  });
}

const CommandRegistrar kMapRegistrar({"map", "map stairs from a point cloud (height map, fitted stairs, constrained map)", RunMap});

}  // namespace
}  // namespace stairplan::cli
