// Cumulative solved-within-time curves per regime, drawn as plain SVG.
#include "cli/qp_bench_plot.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "stairplan/planning/svg_text.h"

namespace stairplan::cli {
namespace {

constexpr double kPanelW = 420, kPanelH = 300, kLeft = 55, kRight = 15, kTop = 35, kBottom = 45;
const char* const kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b"};

std::string TimeLabel(double decade) {
  const double us = std::pow(10.0, decade);
  std::ostringstream s;
  if (us < 1e3) s << us << " us";
  else if (us < 1e6) s << us / 1e3 << " ms";
  else s << us / 1e6 << " s";
  return s.str();
}

// The decades [lo, hi] that hold every time of the panel (at least one decade wide).
std::pair<int, int> Decades(const QpBenchPanel& panel) {
  double lo = 1e300, hi = 0;
  for (const auto& c : panel.curves) {
    for (double t : c.solved_us) {
      lo = std::min(lo, std::max(t, 0.01));
      hi = std::max(hi, std::max(t, 0.01));
    }
  }
  if (hi == 0) return {0, 1};
  const int a = static_cast<int>(std::floor(std::log10(lo)));
  const int b = static_cast<int>(std::ceil(std::log10(hi)));
  return {a, std::max(b, a + 1)};
}

void DrawPanel(std::ostringstream& svg, const QpBenchPanel& panel, double x0) {
  const std::pair<int, int> decades = Decades(panel);
  const int lo = decades.first, hi = decades.second;  // not a structured binding: the lambdas capture them
  const double w = kPanelW - kLeft - kRight, h = kPanelH - kTop - kBottom;
  const auto X = [&](double us) { return x0 + kLeft + w * (std::log10(std::max(us, 0.01)) - lo) / (hi - lo); };
  const auto Y = [&](double fraction) { return kTop + h * (1.0 - fraction); };
  svg << "<text x='" << x0 + kLeft << "' y='20' font-weight='bold'>" << SvgEscaped(panel.title) << "</text>\n";
  svg << "<rect x='" << x0 + kLeft << "' y='" << kTop << "' width='" << w << "' height='" << h
      << "' fill='none' stroke='#222'/>\n";
  for (int d = lo; d <= hi; ++d) {
    const double x = X(std::pow(10.0, d));
    svg << "<line x1='" << x << "' y1='" << kTop << "' x2='" << x << "' y2='" << kTop + h << "' stroke='#ddd'/>";
    svg << "<text x='" << x - 14 << "' y='" << kTop + h + 16 << "'>" << TimeLabel(d) << "</text>\n";
  }
  for (int k = 0; k <= 4; ++k) {
    const double y = Y(k / 4.0);
    svg << "<line x1='" << x0 + kLeft << "' y1='" << y << "' x2='" << x0 + kLeft + w << "' y2='" << y
        << "' stroke='#ddd'/><text x='" << x0 + 20 << "' y='" << y + 4 << "'>" << k * 25 << "%</text>\n";
  }
  svg << "<text x='" << x0 + kLeft + w / 2 - 60 << "' y='" << kTop + h + 34 << "'>CPU time per solve</text>\n";
  for (std::size_t c = 0; c < panel.curves.size(); ++c) {
    std::vector<double> t = panel.curves[c].solved_us;
    std::sort(t.begin(), t.end());
    const char* colour = kColours[c % (sizeof(kColours) / sizeof(kColours[0]))];
    svg << "<polyline fill='none' stroke='" << colour << "' stroke-width='2' points='" << X(std::pow(10.0, lo)) << ","
        << Y(0);
    for (std::size_t i = 0; i < t.size(); ++i) {
      const double fraction = static_cast<double>(i + 1) / std::max(1, panel.problems);
      svg << " " << X(t[i]) << "," << Y(static_cast<double>(i) / std::max(1, panel.problems)) << " " << X(t[i]) << ","
          << Y(fraction);
    }
    if (!t.empty()) svg << " " << X(std::pow(10.0, hi)) << "," << Y(static_cast<double>(t.size()) / std::max(1, panel.problems));
    svg << "'/>\n";
    const double ly = kTop + 16 + 16 * static_cast<double>(c);
    svg << "<line x1='" << x0 + kLeft + 8 << "' y1='" << ly - 4 << "' x2='" << x0 + kLeft + 28 << "' y2='" << ly - 4
        << "' stroke='" << colour << "' stroke-width='2'/><text x='" << x0 + kLeft + 32 << "' y='" << ly << "'>"
        << SvgEscaped(panel.curves[c].solver) << " (" << t.size() << "/" << panel.problems << ")</text>\n";
  }
}

}  // namespace

std::string QpBenchPlotSvg(const std::vector<QpBenchPanel>& panels, const std::string& caption) {
  const double width = kPanelW * static_cast<double>(std::max<std::size_t>(1, panels.size()));
  std::ostringstream svg;
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << width << "' height='" << kPanelH + 30
      << "' font-family='sans-serif' font-size='11'>\n<rect width='100%' height='100%' fill='white'/>\n";
  for (std::size_t p = 0; p < panels.size(); ++p) DrawPanel(svg, panels[p], kPanelW * static_cast<double>(p));
  svg << "<text x='10' y='" << kPanelH + 18 << "'>" << SvgEscaped(caption) << "</text>\n</svg>\n";
  return svg.str();
}

}  // namespace stairplan::cli
