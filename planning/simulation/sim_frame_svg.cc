#include "planning/simulation/sim_frame_svg.h"

#include <algorithm>
#include <sstream>

namespace stairplan {

std::string SimFrameSvg(const SimFrame& frame, const Staircase& stairs, const Plan& plan) {
  constexpr double kWidthPx = 1000.0, kMarginPx = 40.0;
  double z_lo = 0.0, z_hi = 0.0;
  for (const StairSurface& s : stairs.surfaces()) {
    z_lo = std::min(z_lo, s.z);
    z_hi = std::max(z_hi, s.z);
  }
  z_hi += 0.8;  // room for the robot above the highest surface
  const double x0 = stairs.x_min(), x1 = stairs.x_max();
  const double scale = (kWidthPx - 2 * kMarginPx) / (x1 - x0);
  const double height_px = 2 * kMarginPx + scale * (z_hi - z_lo + 0.1);
  const auto X = [&](double x) { return kMarginPx + (x - x0) * scale; };
  const auto Y = [&](double z) { return kMarginPx + (z_hi - z) * scale; };
  std::ostringstream svg;
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << kWidthPx << "' height='" << height_px << "'>\n"
      << "<rect width='100%' height='100%' fill='white'/>\n";
  for (const Box3& box : stairs.Solids()) {
    svg << "<rect x='" << X(box.min.x()) << "' y='" << Y(box.max.z()) << "' width='" << (box.max.x() - box.min.x()) * scale
        << "' height='" << (box.max.z() - box.min.z()) * scale << "' fill='#bbbbbb' stroke='#888888'/>\n";
  }
  for (const Footstep& f : plan.footsteps) {
    svg << "<circle cx='" << X(f.position_W.x()) << "' cy='" << Y(f.position_W.z()) << "' r='3' fill='#2ca02c'/>\n";
  }
  for (std::size_t b = 0; b < frame.bodies.size(); ++b) {
    const int parent = frame.parents[b];
    if (parent < 0) continue;
    const Eigen::Vector3d& p = frame.bodies[static_cast<std::size_t>(parent)];
    const Eigen::Vector3d& c = frame.bodies[b];
    svg << "<line x1='" << X(p.x()) << "' y1='" << Y(p.z()) << "' x2='" << X(c.x()) << "' y2='" << Y(c.z())
        << "' stroke='#1f3f7f' stroke-width='3' stroke-linecap='round'/>\n";
  }
  if (!frame.bodies.empty()) {
    svg << "<circle cx='" << X(frame.bodies[0].x()) << "' cy='" << Y(frame.bodies[0].z()) << "' r='6' fill='#d62728'/>\n";
  }
  for (std::size_t f = 0; f < frame.feet.size(); ++f) {
    svg << "<circle cx='" << X(frame.feet[f].x()) << "' cy='" << Y(frame.feet[f].z()) << "' r='"
        << std::max(2.0, frame.foot_radii[f] * scale) << "' fill='none' stroke='#ff7f0e' stroke-width='2'/>\n";
  }
  svg << "<text x='10' y='20' font-family='sans-serif' font-size='14'>t = " << frame.t << " s</text>\n</svg>\n";
  return svg.str();
}

}  // namespace stairplan
