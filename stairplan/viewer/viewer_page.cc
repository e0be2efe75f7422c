#include "stairplan/viewer/viewer_page.h"

#include <iomanip>
#include <sstream>

namespace stairplan {
namespace {

std::string Escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// JSON inside a <script> element: "</" would end the element early; "<\/" is the same JSON string.
std::string ScriptSafe(std::string text) {
  for (std::size_t at = text.find("</"); at != std::string::npos; at = text.find("</", at + 3)) {
    text.replace(at, 2, "<\\/");
  }
  return text;
}

constexpr const char* kStyle = R"css(
html, body { margin: 0; height: 100%; font: 13px/1.35 system-ui, sans-serif; color: #222; background: #f4f6f8; }
#page { display: grid; grid-template-rows: auto 1fr; grid-template-columns: 1fr 230px; height: 100%; }
#bar { grid-column: 1 / 3; display: flex; flex-wrap: wrap; align-items: center; gap: 8px; padding: 6px 10px;
       background: #fff; border-bottom: 1px solid #ccd; }
#bar h1 { font-size: 14px; margin: 0 12px 0 0; font-weight: 600; }
#bar h1.invalid { color: #b0006e; }
#time { flex: 1; min-width: 160px; accent-color: #666; }
#view { width: 100%; height: 100%; display: block; min-height: 0; }
#side { padding: 8px 10px; overflow: auto; background: #fff; border-left: 1px solid #ccd; }
#side h2 { font-size: 13px; margin: 8px 0 4px; }
.swatch { display: inline-block; width: 12px; height: 12px; margin-right: 6px; vertical-align: -2px; border: 1px solid #0003; }
.violation { cursor: pointer; padding: 2px 0; }
.violation:hover { text-decoration: underline; }
)css";

std::string Legend(const nlohmann::json& scene) {
  std::ostringstream out;
  const auto item = [&](const char* color, const std::string& label, double opacity = 1.0) {
    out << "<div><span class=\"swatch\" style=\"background:" << color << ";opacity:" << opacity << "\"></span>"
        << Escaped(label) << "</div>\n";
  };
  out << "<h2>Legend</h2>\n";
  item("#1f5fd0", "robot (plan, collision geometry)");
  if (!scene["sim"].is_null()) item("#ff8c1a", "robot (MuJoCo run)", 0.6);
  item("#2ca02c", "step region", 0.5);
  item("#d62728", "collision region", 0.5);
  item("#c8c8c8", "stairs");
  item("#202020", "body path");
  item("#e6ab02", "footstep LF");
  item("#a6761d", "footstep RF");
  item("#1b9e77", "footstep LH");
  item("#555555", "footstep RH");
  item("#ff00cc", "violation");
  if (!scene["sim"].is_null()) item("#00b8d9", "impact and response (MuJoCo run); dots: touchdowns");
  return out.str();
}

// The run's impacts other than touchdowns, each with its response; touchdowns only counted.
std::string ImpactList(const nlohmann::json& sim) {
  if (!sim.contains("impacts")) return "";
  std::ostringstream out;
  std::size_t touchdowns = 0;
  std::ostringstream lines;
  for (const nlohmann::json& e : sim["impacts"]) {
    if (e["kind"] == "touchdown") {
      ++touchdowns;
      continue;
    }
    std::ostringstream line;
    line << "t = " << std::fixed << std::setprecision(3) << e["t"].get<double>() << " s: " << e["leg"].get<std::string>()
         << " " << e["kind"].get<std::string>() << " -> " << e["response"].get<std::string>()
         << (e["executed"].get<bool>() || e["response"] == "proceed" ? "" : " (recorded only)");
    lines << "<div class=\"violation\" data-t=\"" << e["t"].get<double>() << "\" title=\""
          << Escaped(e["reason"].get<std::string>()) << "\">" << Escaped(line.str()) << "</div>\n";
  }
  out << "<h2>Impacts (" << sim["impacts"].size() - touchdowns << ", and " << touchdowns << " touchdowns)</h2>\n"
      << lines.str();
  return out.str();
}

std::string ViolationList(const nlohmann::json& scene) {
  std::ostringstream out;
  const nlohmann::json& list = scene["violations"];
  out << "<h2>Violations (" << list.size() << ")</h2>\n";
  if (list.empty()) out << "<div>none</div>\n";
  for (const nlohmann::json& v : list) {
    std::ostringstream line;
    line << "t = " << std::fixed << std::setprecision(2) << v["t"].get<double>() << " s: "
         << v["kind"].get<std::string>() << " (" << v["leg"].get<std::string>() << ") "
         << std::setprecision(4) << v["value"].get<double>()
         << (v["detail"].get<std::string>().empty() ? "" : ", " + v["detail"].get<std::string>());
    out << "<div class=\"violation\" data-t=\"" << v["t"].get<double>() << "\">" << Escaped(line.str()) << "</div>\n";
  }
  if (!scene["sim"].is_null()) {
    const std::string status = scene["sim"]["status"].get<std::string>();
    const std::string cause = scene["sim"]["cause"].get<std::string>();
    out << "<h2>MuJoCo run</h2>\n<div>" << Escaped(status + (cause.empty() ? "" : ": " + cause)) << "</div>\n";
    out << ImpactList(scene["sim"]);
  }
  return out.str();
}

}  // namespace

std::string ViewerPageHtml(const nlohmann::json& scene, const std::string& script) {
  const std::string title = scene["title"].get<std::string>();
  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>stairplan: "
       << Escaped(title) << "</title>\n<style>" << kStyle << "</style>\n</head>\n<body>\n<div id=\"page\">\n"
       << "<div id=\"bar\"><h1" << (scene["valid"].get<bool>() ? "" : " class=\"invalid\"") << ">" << Escaped(title)
       << "</h1>\n<button id=\"play\">pause</button>\n<input id=\"time\" type=\"range\">\n<span id=\"time-label\"></span>\n"
       << "<label>speed <select id=\"speed\"><option>0.25</option><option>0.5</option><option selected>1</option>"
       << "<option>2</option><option>4</option></select></label></div>\n"
       << "<canvas id=\"view\"></canvas>\n<div id=\"side\">\n" << Legend(scene) << ViolationList(scene)
       << "<h2>Camera</h2><div>drag: orbit, right-drag: pan, wheel: zoom</div>\n</div>\n</div>\n"
       << "<script id=\"scene-data\" type=\"application/json\">" << ScriptSafe(scene.dump()) << "</script>\n"
       << "<script>" << script << "</script>\n</body>\n</html>\n";
  return html.str();
}

}  // namespace stairplan
