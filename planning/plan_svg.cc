#include "planning/plan_svg.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace stairplan {
namespace {

constexpr double kWidthPx = 1100.0;
constexpr double kMarginPx = 60.0;

// World (x, z) in metres to SVG pixels, with equal scales on both axes.
class SideView {
 public:
  SideView(double x0, double x1, double z0, double z1)
      : x0_(x0), z1_(z1), scale_((kWidthPx - 2 * kMarginPx) / (x1 - x0)),
        height_px_(2 * kMarginPx + scale_ * (z1 - z0)) {}
  double X(double x) const { return kMarginPx + (x - x0_) * scale_; }
  double Y(double z) const { return kMarginPx + (z1_ - z) * scale_; }
  double scale() const { return scale_; }
  double height_px() const { return height_px_; }

 private:
  double x0_, z1_, scale_, height_px_;
};

// Each leg's footholds are drawn on their own row above the tread, so legs on the same spot stay visible.
double LegRowPx(const std::string& leg) {
  static const std::map<std::string, double> rows = {{"LF", 7}, {"RF", 15}, {"LH", 23}, {"RH", 31}};
  const auto it = rows.find(leg);
  return it == rows.end() ? 7 : it->second;
}

const char* LegColour(const std::string& leg) {
  static const std::map<std::string, const char*> colours = {
      {"LF", "#1f77b4"}, {"RF", "#ff7f0e"}, {"LH", "#9467bd"}, {"RH", "#8c564b"}};
  const auto it = colours.find(leg);
  return it == colours.end() ? "#333333" : it->second;
}

void DrawBand(std::ostringstream& svg, const SideView& v, const Polygon2& poly, const char* colour, double offset_px) {
  if (poly.empty()) return;
  const auto [lo, hi] = poly.XExtent();
  svg << "<line x1='" << v.X(lo) << "' y1='" << v.Y(poly.z) - offset_px << "' x2='" << v.X(hi) << "' y2='"
      << v.Y(poly.z) - offset_px << "' stroke='" << colour << "' stroke-width='5'/>\n";
}

void DrawAxes(std::ostringstream& svg, const SideView& v, double x0, double x1, double z0, double z1) {
  const double base = v.height_px() - kMarginPx + 20;
  svg << "<g font-family='sans-serif' font-size='12' fill='#222'>\n";
  svg << "<line x1='" << v.X(x0) << "' y1='" << base << "' x2='" << v.X(x1) << "' y2='" << base << "' stroke='#222'/>\n";
  for (double x = std::ceil(x0 * 2) / 2; x <= x1 + 1e-9; x += 0.5) {
    svg << "<line x1='" << v.X(x) << "' y1='" << base << "' x2='" << v.X(x) << "' y2='" << base + 5 << "' stroke='#222'/>";
    svg << "<text x='" << v.X(x) - 10 << "' y='" << base + 18 << "'>" << (std::abs(x) < 1e-9 ? 0.0 : x) << "</text>\n";
  }
  svg << "<text x='" << v.X(x1) - 40 << "' y='" << base + 34 << "'>x [m]</text>\n";
  const double left = kMarginPx - 20;
  svg << "<line x1='" << left << "' y1='" << v.Y(z0) << "' x2='" << left << "' y2='" << v.Y(z1) << "' stroke='#222'/>\n";
  for (double z = std::ceil(z0 * 4) / 4; z <= z1 + 1e-9; z += 0.25) {
    svg << "<line x1='" << left - 5 << "' y1='" << v.Y(z) << "' x2='" << left << "' y2='" << v.Y(z) << "' stroke='#222'/>";
    svg << "<text x='" << 4 << "' y='" << v.Y(z) + 4 << "'>" << (std::abs(z) < 1e-9 ? 0.0 : z) << "</text>\n";
  }
  svg << "<text x='4' y='" << kMarginPx - 30 << "'>z [m]</text>\n</g>\n";
}

void DrawLegend(std::ostringstream& svg, const Plan& plan) {
  svg << "<g font-family='sans-serif' font-size='13'>\n";
  svg << "<text x='" << kMarginPx << "' y='20'>" << plan.robot_name << ", " << plan.gait << ", cadence "
      << plan.cadence_s << " s, status " << ToString(plan.status) << "</text>\n";
  double x = kMarginPx;
  const auto item = [&](const char* colour, const std::string& label) {
    svg << "<rect x='" << x << "' y='30' width='12' height='12' fill='" << colour << "'/>";
    svg << "<text x='" << x + 16 << "' y='41'>" << label << "</text>\n";
    x += 30 + 7.0 * static_cast<double>(label.size());
  };
  item("#2ca02c", "step region");
  item("#d62728", "collision region");
  item("#17becf", "body path");
  for (const std::string& leg : plan.legs) item(LegColour(leg), leg + " footholds");
  svg << "</g>\n";
}

}  // namespace

std::string PlanToSvg(const Plan& plan, const Staircase& stairs, const ConstrainedMap& map) {
  const double x0 = stairs.x_min(), x1 = stairs.x_max();
  double z1 = stairs.total_rise();
  for (const BodyState& b : plan.body) z1 = std::max(z1, b.z);
  const double z0 = -0.1;
  z1 += 0.15;
  const SideView v(x0, x1, z0, z1);
  std::ostringstream svg;
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << kWidthPx << "' height='" << v.height_px() + 50
      << "' viewBox='0 0 " << kWidthPx << " " << v.height_px() + 50 << "'>\n";
  svg << "<rect width='100%' height='100%' fill='white'/>\n";
  for (const Box3& box : stairs.Solids()) {
    svg << "<rect x='" << v.X(box.min.x()) << "' y='" << v.Y(box.max.z()) << "' width='"
        << v.scale() * box.Size().x() << "' height='" << v.scale() * box.Size().z() << "' fill='"
        << (box.kind == SolidKind::kNosing ? "#7f7f7f" : "#c7c7c7") << "' stroke='#555' stroke-width='0.5'/>\n";
  }
  for (const StairRegions& s : map.stairs()) {
    DrawBand(svg, v, s.step_region, "#2ca02c", 3);
    for (const CollisionRegion& c : s.collision_regions) {
      if (c.kind != RegionKind::kSide) DrawBand(svg, v, c.polygon, "#d62728", 3);
    }
  }
  svg << "<polyline fill='none' stroke='#17becf' stroke-width='2' points='";
  for (const BodyState& b : plan.body) svg << v.X(b.x) << "," << v.Y(b.z) << " ";
  svg << "'/>\n";
  for (std::size_t i = 0; i < plan.initial_feet_W.size(); ++i) {
    const auto& p = plan.initial_feet_W[i];
    svg << "<circle cx='" << v.X(p.x()) << "' cy='" << v.Y(p.z()) - LegRowPx(plan.legs[i]) << "' r='4' fill='none' stroke='"
        << LegColour(plan.legs[i]) << "' stroke-width='2'/>\n";
  }
  for (const Footstep& f : plan.footsteps) {
    svg << "<circle cx='" << v.X(f.position_W.x()) << "' cy='" << v.Y(f.position_W.z()) - LegRowPx(f.leg) << "' r='3.5' fill='"
        << LegColour(f.leg) << "'><title>" << f.leg << " t=" << f.t_touchdown << " s</title></circle>\n";
  }
  DrawAxes(svg, v, x0, x1, z0, z1);
  DrawLegend(svg, plan);
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace stairplan
