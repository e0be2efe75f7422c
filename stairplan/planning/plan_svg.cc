#include "stairplan/planning/plan_svg.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "stairplan/planning/body_path.h"
#include "stairplan/planning/svg_text.h"

namespace stairplan {
namespace {

constexpr double kWidthPx = 1100.0;
constexpr double kMarginPx = 60.0;
constexpr double kHeaderPx = 64.0;   // title and legend
constexpr double kGapPx = 50.0;      // between the side view's x axis and the top view
constexpr double kLinePx = 16.0;     // one line of the violation list
constexpr int kListedViolations = 6;
constexpr const char* kViolationColour = "#ff00cc";

// World metres to SVG pixels, equal scales on both axes: x to the right; `up` (z in the side view,
// y in the top view) upwards from `top_px`.
class View {
 public:
  View(double x0, double scale, double up_max, double top_px) : x0_(x0), scale_(scale), up_max_(up_max), top_px_(top_px) {}
  double X(double x) const { return kMarginPx + (x - x0_) * scale_; }
  double Y(double up) const { return top_px_ + (up_max_ - up) * scale_; }
  double scale() const { return scale_; }

 private:
  double x0_, scale_, up_max_, top_px_;
};

const char* LegColour(const std::string& leg) {
  static const std::map<std::string, const char*> colours = {
      {"LF", "#1f77b4"}, {"RF", "#ff7f0e"}, {"LH", "#9467bd"}, {"RH", "#8c564b"}};
  const auto it = colours.find(leg);
  return it == colours.end() ? "#333333" : it->second;
}

// Where a violation happened: the footstep that landed outside its region, the leg's foot (both
// feet of a pair), or the body.
Eigen::Vector3d ViolationPlace(const Plan& plan, const Violation& v) {
  if (v.kind == ViolationKind::kFootOutsideStepRegion) {
    for (const Footstep& f : plan.footsteps) {
      if (f.leg == v.leg && std::abs(f.t_touchdown - v.t) < 1e-6) return f.position_W;
    }
  }
  const double t = std::clamp(v.t, 0.0, plan.duration());
  const std::vector<Eigen::Vector3d> feet = FeetAt(plan.legs, plan.initial_feet_W, plan.footsteps, t);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int n = 0;
  for (std::size_t i = 0; i < plan.legs.size() && i < feet.size(); ++i) {
    if (v.leg.find(plan.legs[i]) != std::string::npos) {
      sum += feet[i];
      ++n;
    }
  }
  return n > 0 ? Eigen::Vector3d(sum / n) : BodyPoseAt(plan.body, t).position_W;
}

void DrawXAxis(std::ostringstream& svg, const View& v, double x0, double x1, double base) {
  svg << "<g font-family='sans-serif' font-size='12' fill='#222'>\n";
  svg << "<line x1='" << v.X(x0) << "' y1='" << base << "' x2='" << v.X(x1) << "' y2='" << base << "' stroke='#222'/>\n";
  for (double x = std::ceil(x0 * 2) / 2; x <= x1 + 1e-9; x += 0.5) {
    svg << "<line x1='" << v.X(x) << "' y1='" << base << "' x2='" << v.X(x) << "' y2='" << base + 5 << "' stroke='#222'/>";
    svg << "<text x='" << v.X(x) - 10 << "' y='" << base + 18 << "'>" << (std::abs(x) < 1e-9 ? 0.0 : x) << "</text>\n";
  }
  svg << "<text x='" << v.X(x1) - 40 << "' y='" << base + 32 << "'>x [m]</text>\n</g>\n";
}

void DrawUpAxis(std::ostringstream& svg, const View& v, double lo, double hi, double tick, const char* label) {
  const double left = kMarginPx - 20;
  svg << "<g font-family='sans-serif' font-size='12' fill='#222'>\n";
  svg << "<line x1='" << left << "' y1='" << v.Y(lo) << "' x2='" << left << "' y2='" << v.Y(hi) << "' stroke='#222'/>\n";
  for (double u = std::ceil(lo / tick) * tick; u <= hi + 1e-9; u += tick) {
    svg << "<line x1='" << left - 5 << "' y1='" << v.Y(u) << "' x2='" << left << "' y2='" << v.Y(u) << "' stroke='#222'/>";
    svg << "<text x='4' y='" << v.Y(u) + 4 << "'>" << (std::abs(u) < 1e-9 ? 0.0 : u) << "</text>\n";
  }
  svg << "<text x='4' y='" << v.Y(hi) - 10 << "'>" << label << "</text>\n</g>\n";
}

std::string Title(const Plan& plan, const ValidationReport* validation) {
  std::ostringstream title;
  title << plan.robot_name << ", " << GaitName(plan.gait) << ", cadence " << plan.cadence_s << " s: ";
  if (plan.status != PlanStatus::kOk) {
    title << "INVALID: " << (plan.status_reason.empty() ? ToString(plan.status) : plan.status_reason);
  } else if (validation == nullptr) {
    title << "planned (not validated)";
  } else if (!validation->ok && !validation->violations.empty()) {
    const Violation& v = validation->violations.front();
    title << "INVALID: " << ToString(v.kind) << " (" << v.leg << ") at t = " << v.t << " s, " << v.value
          << (v.detail.empty() ? "" : ", " + v.detail);
  } else if (!validation->ok) {
    title << "INVALID";
  } else {
    title << "valid, min clearance " << validation->min_clearance_m * 1000 << " mm";
  }
  return title.str();
}

void DrawHeader(std::ostringstream& svg, const Plan& plan, const ValidationReport* validation) {
  const bool invalid = plan.status != PlanStatus::kOk || (validation != nullptr && !validation->ok);
  svg << "<g font-family='sans-serif' font-size='13'>\n";
  svg << "<text x='" << kMarginPx << "' y='20' font-weight='bold'" << (invalid ? " fill='#b0006e'" : "") << ">"
      << SvgEscaped(Title(plan, validation)) << "</text>\n";
  double x = kMarginPx;
  const auto item = [&](const char* colour, const std::string& label) {
    svg << "<rect x='" << x << "' y='32' width='12' height='12' fill='" << colour << "'/>";
    svg << "<text x='" << x + 16 << "' y='43'>" << label << "</text>\n";
    x += 30 + 7.0 * static_cast<double>(label.size());
  };
  item("#2ca02c", "step region");
  item("#d62728", "collision region");
  item("#17becf", "body path");
  for (const std::string& leg : plan.legs) item(LegColour(leg), leg + " footholds");
  item(kViolationColour, "violation");
  svg << "</g>\n";
}

void DrawPolygon(std::ostringstream& svg, const View& v, const Polygon2& poly, const char* colour) {
  if (poly.empty()) return;
  svg << "<polygon fill='" << colour << "' fill-opacity='0.45' stroke='none' points='";
  for (const Eigen::Vector2d& p : poly.vertices) svg << v.X(p.x()) << "," << v.Y(p.y()) << " ";
  svg << "'/>\n";
}

void DrawSideView(std::ostringstream& svg, const View& v, const Plan& plan, const Staircase& stairs,
                  const ConstrainedMap& map) {
  for (const Box3& box : stairs.Solids()) {
    svg << "<rect x='" << v.X(box.min.x()) << "' y='" << v.Y(box.max.z()) << "' width='" << v.scale() * box.Size().x()
        << "' height='" << v.scale() * box.Size().z() << "' fill='"
        << (box.kind == SolidKind::kNosing ? "#7f7f7f" : "#c7c7c7") << "' stroke='#555' stroke-width='0.5'/>\n";
  }
  const auto band = [&](const Polygon2& poly, const char* colour) {
    if (poly.empty()) return;
    const auto [lo, hi] = poly.XExtent();
    svg << "<line x1='" << v.X(lo) << "' y1='" << v.Y(poly.z) - 2 << "' x2='" << v.X(hi) << "' y2='" << v.Y(poly.z) - 2
        << "' stroke='" << colour << "' stroke-width='4'/>\n";
  };
  for (const StairRegions& s : map.stairs()) {
    band(s.step_region, "#2ca02c");
    for (const CollisionRegion& c : s.collision_regions) {
      if (c.kind != RegionKind::kSide) band(c.polygon, "#d62728");
    }
  }
  svg << "<polyline fill='none' stroke='#17becf' stroke-width='2' points='";
  for (const BodyState& b : plan.body) svg << v.X(b.x) << "," << v.Y(b.z) << " ";
  svg << "'/>\n";
  // Footholds on their treads: left feet above the tread line, right feet on it.
  for (const Footstep& f : plan.footsteps) {
    const double lift = f.position_W.y() >= 0.0 ? 6.0 : 0.0;
    svg << "<circle cx='" << v.X(f.position_W.x()) << "' cy='" << v.Y(f.position_W.z()) - 3 - lift << "' r='3' fill='"
        << LegColour(f.leg) << "'><title>" << f.leg << " t=" << f.t_touchdown << " s</title></circle>\n";
  }
}

void DrawTopView(std::ostringstream& svg, const View& v, const Plan& plan, const Staircase& stairs,
                 const ConstrainedMap& map) {
  const double w = stairs.half_width();
  for (const StairSurface& s : stairs.surfaces()) {
    svg << "<rect x='" << v.X(s.x_begin) << "' y='" << v.Y(w) << "' width='" << v.scale() * (s.x_end - s.x_begin)
        << "' height='" << v.scale() * 2 * w << "' fill='" << (s.index % 2 == 0 ? "#dcdcdc" : "#c7c7c7")
        << "' stroke='#555' stroke-width='0.5'/>\n";
  }
  for (const StairRegions& s : map.stairs()) {
    DrawPolygon(svg, v, s.step_region, "#2ca02c");
    for (const CollisionRegion& c : s.collision_regions) DrawPolygon(svg, v, c.polygon, "#d62728");
  }
  svg << "<polyline fill='none' stroke='#17becf' stroke-width='2' points='";
  for (const BodyState& b : plan.body) svg << v.X(b.x) << "," << v.Y(b.y) << " ";
  svg << "'/>\n";
  for (std::size_t i = 0; i < plan.initial_feet_W.size() && i < plan.legs.size(); ++i) {
    const Eigen::Vector3d& p = plan.initial_feet_W[i];
    svg << "<circle cx='" << v.X(p.x()) << "' cy='" << v.Y(p.y()) << "' r='4' fill='none' stroke='"
        << LegColour(plan.legs[i]) << "' stroke-width='2'/>\n";
  }
  for (const Footstep& f : plan.footsteps) {
    svg << "<circle cx='" << v.X(f.position_W.x()) << "' cy='" << v.Y(f.position_W.y()) << "' r='3.5' fill='"
        << LegColour(f.leg) << "'><title>" << f.leg << " t=" << f.t_touchdown << " s</title></circle>\n";
  }
}

// A numbered ring at each violation's place in both views, and the first few listed below.
void DrawViolations(std::ostringstream& svg, const View& side, const View& top, const Plan& plan,
                    const ValidationReport& validation, double list_top) {
  svg << "<g font-family='sans-serif' font-size='12' fill='" << kViolationColour << "'>\n";
  for (std::size_t i = 0; i < validation.violations.size(); ++i) {
    const Violation& viol = validation.violations[i];
    const Eigen::Vector3d p = ViolationPlace(plan, viol);
    for (const auto& [cx, cy] : {std::pair{side.X(p.x()), side.Y(p.z())}, std::pair{top.X(p.x()), top.Y(p.y())}}) {
      svg << "<circle cx='" << cx << "' cy='" << cy << "' r='9' fill='none' stroke='" << kViolationColour
          << "' stroke-width='2.5'/><text x='" << cx + 10 << "' y='" << cy - 8 << "'>" << i + 1 << "</text>\n";
    }
    if (static_cast<int>(i) < kListedViolations) {
      svg << "<text x='" << kMarginPx << "' y='" << list_top + kLinePx * static_cast<double>(i) << "'>" << i + 1
          << ": t = " << viol.t << " s, " << ToString(viol.kind) << " (" << viol.leg << "), " << viol.value
          << SvgEscaped(viol.detail.empty() ? "" : ", " + viol.detail) << "</text>\n";
    }
  }
  if (static_cast<int>(validation.violations.size()) > kListedViolations) {
    svg << "<text x='" << kMarginPx << "' y='" << list_top + kLinePx * kListedViolations << "'>... and "
        << validation.violations.size() - kListedViolations << " more</text>\n";
  }
  svg << "</g>\n";
}

}  // namespace

std::string PlanToSvg(const Plan& plan, const Staircase& stairs, const ConstrainedMap& map,
                      const ValidationReport* validation) {
  const double x0 = stairs.x_min(), x1 = stairs.x_max();
  double z1 = stairs.total_rise();
  for (const BodyState& b : plan.body) z1 = std::max(z1, b.z);
  const double z0 = -0.1;
  z1 += 0.15;
  const double scale = (kWidthPx - 2 * kMarginPx) / (x1 - x0);
  const View side(x0, scale, z1, kHeaderPx + 10);
  const double side_bottom = side.Y(z0);
  const double y_max = stairs.half_width() + 0.05;
  const View top(x0, scale, y_max, side_bottom + kGapPx);
  const double top_bottom = top.Y(-y_max);
  const int listed = validation == nullptr ? 0 : std::min<int>(static_cast<int>(validation->violations.size()), kListedViolations + 1);
  const double height = top_bottom + 45 + kLinePx * listed;

  std::ostringstream svg;
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << kWidthPx << "' height='" << height << "' viewBox='0 0 "
      << kWidthPx << " " << height << "'>\n<rect width='100%' height='100%' fill='white'/>\n";
  DrawHeader(svg, plan, validation);
  DrawSideView(svg, side, plan, stairs, map);
  DrawUpAxis(svg, side, z0, z1, 0.25, "z [m]");
  DrawXAxis(svg, side, x0, x1, side_bottom + 8);
  svg << "<text x='" << kMarginPx + 10 << "' y='" << side.Y(z1) + 12
      << "' font-family='sans-serif' font-size='12' fill='#555'>side view (x-z)</text>\n";
  DrawTopView(svg, top, plan, stairs, map);
  DrawUpAxis(svg, top, -y_max, y_max, 0.25, "y [m]");
  svg << "<text x='" << kMarginPx + 10 << "' y='" << top.Y(y_max) - 6
      << "' font-family='sans-serif' font-size='12' fill='#555'>top view (x-y), left is up</text>\n";
  if (validation != nullptr) DrawViolations(svg, side, top, plan, *validation, top_bottom + 30);
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace stairplan
