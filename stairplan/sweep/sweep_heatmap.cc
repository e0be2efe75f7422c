// The sweep heatmap: one panel per direction, run along x and rise along y, a cell per point
// coloured by outcome, with the building-code boxes of DESIGN.md's domain notes drawn on top.
#include <algorithm>
#include <map>
#include <sstream>

#include "stairplan/sweep/sweep_runner.h"

namespace stairplan {
namespace {

constexpr double kPanel = 420.0;  // panel size [px]
constexpr double kMargin = 70.0;

struct CodeBox {
  const char* name;
  double rise_lo, rise_hi, run_lo, run_hi;
  const char* colour;
};

// Building codes (DESIGN.md): US residential riser <= 196 mm and tread >= 254 mm; US commercial
// riser 102-178 mm and tread >= 279 mm; UK private rise 150-220 mm and going 220-300 mm.
const CodeBox kCodes[] = {
    {"US residential", 0.0, 0.196, 0.254, 10.0, "#1f77b4"},
    {"US commercial", 0.102, 0.178, 0.279, 10.0, "#9467bd"},
    {"UK private", 0.150, 0.220, 0.220, 0.300, "#ff7f0e"},
};

const char* StatusColour(const std::string& status) {
  if (status == "valid") return "#2ca02c";
  if (status == "invalid") return "#d62728";
  if (status == "infeasible") return "#7f7f7f";
  if (status == "failed") return "#000000";
  return "#ffffff";
}

class Panel {
 public:
  Panel(const SweepGrid& grid, double left) : grid_(grid), left_(left) {}
  double X(double run) const { return left_ + (run - lo(grid_.run)) / span(grid_.run) * kPanel; }
  double Y(double rise) const { return kMargin + kPanel - (rise - lo(grid_.rise)) / span(grid_.rise) * kPanel; }
  double cell_w() const { return kPanel / grid_.run.count; }
  double cell_h() const { return kPanel / grid_.rise.count; }

 private:
  // Cells are centred on the grid values, so the panel reaches half a cell beyond each end.
  static double step(const SweepAxis& a) { return a.count > 1 ? (a.hi - a.lo) / (a.count - 1) : 0.01; }
  static double lo(const SweepAxis& a) { return a.lo - 0.5 * step(a); }
  static double span(const SweepAxis& a) { return a.hi - a.lo + step(a); }
  const SweepGrid& grid_;
  double left_;
};

void DrawPanel(std::ostringstream& svg, const std::vector<SweepRow>& rows, const SweepGrid& grid, TravelDirection dir,
               double left) {
  const Panel p(grid, left);
  // With several step counts or nosings, the panel shows the first of each.
  const int steps = static_cast<int>(grid.steps.lo);
  for (const SweepRow& r : rows) {
    if (r.point.direction != dir || r.point.steps != steps || r.point.nosing != grid.nosing.lo) continue;
    svg << "<rect x='" << p.X(r.point.run) - p.cell_w() / 2 << "' y='" << p.Y(r.point.rise) - p.cell_h() / 2
        << "' width='" << p.cell_w() << "' height='" << p.cell_h() << "' fill='" << StatusColour(r.status)
        << "' stroke='white' stroke-width='0.5'><title>rise " << r.point.rise << " run " << r.point.run << ": "
        << r.status << (r.reason.empty() ? "" : " (" + r.reason + ")") << "</title></rect>\n";
  }
  svg << "<g fill='none' stroke-width='2'>\n";
  for (const CodeBox& c : kCodes) {
    const double x0 = std::max(p.X(c.run_lo), left), x1 = std::min(p.X(c.run_hi), left + kPanel);
    const double y0 = std::max(p.Y(c.rise_hi), kMargin), y1 = std::min(p.Y(c.rise_lo), kMargin + kPanel);
    if (x1 <= x0 || y1 <= y0) continue;
    svg << "<rect x='" << x0 << "' y='" << y0 << "' width='" << x1 - x0 << "' height='" << y1 - y0 << "' stroke='"
        << c.colour << "'><title>" << c.name << "</title></rect>\n";
  }
  svg << "</g>\n<g font-family='sans-serif' font-size='12'>\n";
  svg << "<text x='" << left << "' y='" << kMargin - 10 << "'>" << ToString(dir) << ", " << steps
      << " steps, nosing " << grid.nosing.lo << " m</text>\n";
  for (double run : {grid.run.lo, 0.5 * (grid.run.lo + grid.run.hi), grid.run.hi}) {
    svg << "<text x='" << p.X(run) - 12 << "' y='" << kMargin + kPanel + 18 << "'>" << run << "</text>\n";
  }
  svg << "<text x='" << left + kPanel / 2 - 20 << "' y='" << kMargin + kPanel + 36 << "'>run [m]</text>\n";
  for (double rise : {grid.rise.lo, 0.5 * (grid.rise.lo + grid.rise.hi), grid.rise.hi}) {
    svg << "<text x='" << left - 40 << "' y='" << p.Y(rise) + 4 << "'>" << rise << "</text>\n";
  }
  svg << "<text x='" << left - 60 << "' y='" << kMargin - 24 << "'>rise [m]</text>\n</g>\n";
}

// The legend's items laid out in rows that fit `width`; returns the rows' total height.
struct LegendItem {
  const char* colour;
  std::string label;
  bool outline;
};
double HeatmapLegendHeight(const std::vector<LegendItem>& items, double width, std::ostringstream* svg, double top) {
  constexpr double kRow = 20.0;
  double x = kMargin, y = top;
  for (const LegendItem& item : items) {
    const double item_width = 40 + 7.0 * static_cast<double>(item.label.size());
    if (x > kMargin && x + item_width > width - 10) {
      x = kMargin;
      y += kRow;
    }
    if (svg != nullptr) {
      *svg << "<rect x='" << x << "' y='" << y << "' width='12' height='12' "
           << (item.outline ? "fill='none' stroke-width='2' stroke='" : "fill='") << item.colour << "'/>";
      *svg << "<text x='" << x + 16 << "' y='" << y + 11 << "'>" << item.label << "</text>\n";
    }
    x += item_width;
  }
  return y - top + kRow;
}

}  // namespace

std::string SweepHeatmapSvg(const std::vector<SweepRow>& rows, const SweepGrid& grid) {
  const double width = kMargin + static_cast<double>(grid.directions.size()) * (kPanel + kMargin);
  std::vector<LegendItem> legend = {{StatusColour("valid"), "valid", false},
                                    {StatusColour("invalid"), "invalid", false},
                                    {StatusColour("infeasible"), "infeasible", false}};
  for (const CodeBox& c : kCodes) legend.push_back({c.colour, c.name, true});
  const double legend_top = kPanel + 2 * kMargin + 20;
  const double height = legend_top + HeatmapLegendHeight(legend, width, nullptr, legend_top) + 10;
  std::ostringstream svg;
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << width << "' height='" << height << "'>\n"
      << "<rect width='100%' height='100%' fill='white'/>\n";
  double left = kMargin;
  for (TravelDirection dir : grid.directions) {
    DrawPanel(svg, rows, grid, dir, left);
    left += kPanel + kMargin;
  }
  svg << "<g font-family='sans-serif' font-size='12'>\n";
  HeatmapLegendHeight(legend, width, &svg, legend_top);
  svg << "</g>\n</svg>\n";
  return svg.str();
}

}  // namespace stairplan
