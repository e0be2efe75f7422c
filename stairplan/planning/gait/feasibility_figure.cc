#include "stairplan/planning/gait/feasibility_figure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "stairplan/planning/gait/feasibility_volume.h"

namespace stairplan {
namespace {

// The chart's window in (W/BL, H/BL) and its place on the page [px].
constexpr double kWLo = 0.2, kWHi = 1.0, kHLo = 0.1, kHHi = 0.6;
constexpr double kLeft = 70.0, kRight = 610.0, kTop = 40.0, kBottom = 440.0;
constexpr int kFigureColumns = 200, kFigureRows = 250;

// Building-code bounds on real stairs (DESIGN.md, domain notes) [m]; a missing bound is open.
struct CodeRange {
  const char* label;
  double run_lo, run_hi, rise_lo, rise_hi;
};
constexpr double kOpen = -1.0;
constexpr CodeRange kCodeRanges[] = {
    {"US residential", 0.254, kOpen, kOpen, 0.196},
    {"US commercial", 0.279, kOpen, 0.102, 0.178},
    {"UK private", 0.220, 0.300, 0.150, 0.220},
};

double Px(double w) { return kLeft + (w - kWLo) / (kWHi - kWLo) * (kRight - kLeft); }
double Py(double h) { return kBottom - (h - kHLo) / (kHHi - kHLo) * (kBottom - kTop); }

std::string Format(const char* fmt, double a, double b = 0.0, double c = 0.0, double d = 0.0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, fmt, a, b, c, d);
  return buf;
}

DimensionlessVerdict At(double w, double h, double l, double p) { return EvaluateDimensionless({w, h, l, p}); }

// The feasible region, one rectangle per column and run of feasible rows.
std::string FeasibleCells(double l, double p) {
  std::string out = "<g fill=\"#b7e4b0\" stroke=\"none\">\n";
  const double dw = (kWHi - kWLo) / kFigureColumns, dh = (kHHi - kHLo) / kFigureRows;
  for (int i = 0; i < kFigureColumns; ++i) {
    const double w = kWLo + (i + 0.5) * dw;
    int start = -1;
    for (int j = 0; j <= kFigureRows; ++j) {
      const bool in = j < kFigureRows && At(w, kHLo + (j + 0.5) * dh, l, p).feasible();
      if (in && start < 0) start = j;
      if (!in && start >= 0) {
        const double x = Px(w - 0.5 * dw), y = Py(kHLo + j * dh);
        out += Format("<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\"/>\n", x, y, Px(w + 0.5 * dw) - x,
                      Py(kHLo + start * dh) - y);
        start = -1;
      }
    }
  }
  return out + "</g>\n";
}

// Each condition's boundary: where it changes verdict between vertically adjacent samples.
std::string Boundaries(double l, double p) {
  struct Curve {
    const char* colour;
    bool DimensionlessVerdict::*holds;
  };
  const Curve curves[] = {{"#c0392b", &DimensionlessVerdict::c14},
                          {"#2e6fd1", &DimensionlessVerdict::c15},
                          {"#e08a00", &DimensionlessVerdict::c16}};
  std::string out;
  const int columns = 4 * kFigureColumns, rows = 4 * kFigureRows;
  const double dw = (kWHi - kWLo) / columns, dh = (kHHi - kHLo) / rows;
  for (const Curve& c : curves) {
    out += std::string("<g fill=\"") + c.colour + "\">\n";
    for (int i = 0; i <= columns; ++i) {
      const double w = kWLo + i * dw;
      bool below = At(w, kHLo, l, p).*c.holds;
      for (int j = 1; j <= rows; ++j) {
        const double h = kHLo + j * dh;
        const bool here = At(w, h, l, p).*c.holds;
        if (here != below) out += Format("<circle cx=\"%.2f\" cy=\"%.2f\" r=\"0.9\"/>\n", Px(w), Py(h - 0.5 * dh));
        below = here;
      }
    }
    out += "</g>\n";
  }
  // CL = BL and CL = BL / 2: outside that band (11)-(13) no longer stand for (8)-(10).
  for (double radius : {0.5, 1.0}) {
    out += "<path fill=\"none\" stroke=\"#555\" stroke-dasharray=\"2,3\" d=\"";
    bool first = true;
    for (int k = 0; k <= 180; ++k) {
      const double a = k * M_PI / 360.0;
      const double w = radius * std::cos(a), h = radius * std::sin(a);
      if (w < kWLo || w > kWHi || h < kHLo || h > kHHi) continue;
      out += Format(first ? "M%.2f,%.2f " : "L%.2f,%.2f ", Px(w), Py(h));
      first = false;
    }
    out += "\"/>\n";
  }
  return out;
}

std::string Axes() {
  std::string out = Format("<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"none\" stroke=\"#000\"/>\n",
                           kLeft, kTop, kRight - kLeft, kBottom - kTop);
  for (int k = 2; k <= 10; ++k) {
    const double w = 0.1 * k;
    out += Format("<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#000\"/>\n", Px(w), kBottom, Px(w), kBottom + 5);
    out += Format("<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">%.1f</text>\n", Px(w), kBottom + 18, w);
  }
  for (int k = 1; k <= 6; ++k) {
    const double h = 0.1 * k;
    out += Format("<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#000\"/>\n", kLeft - 5, Py(h), kLeft, Py(h));
    out += Format("<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">%.1f</text>\n", kLeft - 8, Py(h) + 4, h);
  }
  out += Format("<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">W / BL</text>\n", 0.5 * (kLeft + kRight), kBottom + 36);
  out += Format("<text x=\"18\" y=\"%.1f\" transform=\"rotate(-90 18 %.1f)\" text-anchor=\"middle\">H / BL</text>\n",
                0.5 * (kTop + kBottom), 0.5 * (kTop + kBottom));
  return out;
}

std::string CodeRanges(double bl) {
  std::string out = "<g fill=\"none\" stroke=\"#7a4fa0\" stroke-dasharray=\"6,3\">\n";
  std::string labels = "<g fill=\"#7a4fa0\" font-size=\"11\">\n";
  int k = 0;
  for (const CodeRange& r : kCodeRanges) {
    const double w0 = std::max(kWLo, r.run_lo / bl), w1 = r.run_hi < 0 ? kWHi : std::min(kWHi, r.run_hi / bl);
    const double h0 = r.rise_lo < 0 ? kHLo : std::max(kHLo, r.rise_lo / bl), h1 = std::min(kHHi, r.rise_hi / bl);
    if (w1 <= w0 || h1 <= h0) continue;
    const double inset = 1.5 * k;  // ranges that share an open edge stay distinguishable
    out += Format("<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\"/>\n", Px(w0) + inset, Py(h1) + inset,
                  Px(w1) - Px(w0) - 2 * inset, Py(h0) - Py(h1) - 2 * inset);
    labels += Format("<text x=\"%.2f\" y=\"%.2f\">", Px(w0) + 4, Py(h0) - 5 - inset) + r.label + "</text>\n";
    ++k;
  }
  return out + "</g>\n" + labels + "</g>\n";
}

std::string Stairs(const std::vector<MarkedStair>& stairs, double bl) {
  std::string out = "<g font-size=\"11\">\n";
  for (const MarkedStair& s : stairs) {
    const double x = Px(s.run / bl), y = Py(s.rise / bl);
    out += Format("<circle cx=\"%.2f\" cy=\"%.2f\" r=\"4\" fill=\"#000\"/>\n", x, y);
    out += Format("<text x=\"%.2f\" y=\"%.2f\">", x + 6, y - 6) + s.label + "</text>\n";
  }
  return out + "</g>\n";
}

std::string Legend(double l, double p) {
  std::string out = Format("<text x=\"%.1f\" y=\"24\" font-size=\"14\">Feasible W/BL, H/BL for l_max/BL = %.3f, p = %.2f "
                           "(eqs. (14)-(16))</text>\n",
                           kLeft, l, p);
  const char* entries[][2] = {{"#b7e4b0", "feasible"},
                              {"#c0392b", "(14): hind-right vs front-left swing"},
                              {"#2e6fd1", "(15): front-right vs hind-left swing"},
                              {"#e08a00", "(16): l_max >= l_min"},
                              {"#555", "CL = BL and CL = BL / 2 (dotted): the assumption CL &lt; BL &lt; 2 CL"}};
  double y = kBottom + 60;
  for (const auto& e : entries) {
    out += Format("<rect x=\"%.1f\" y=\"%.1f\" width=\"10\" height=\"10\" fill=\"", kLeft, y - 9) + e[0] + "\"/>";
    out += Format("<text x=\"%.1f\" y=\"%.1f\" font-size=\"12\">", kLeft + 16, y) + e[1] + "</text>\n";
    y += 16;
  }
  return out;
}

}  // namespace

std::vector<MarkedStair> PaperStairs() {
  return {{0.27, 0.17, "27 x 17"}, {0.31, 0.175, "31 x 17.5"}, {0.28, 0.16, "28 x 16"}};
}

std::string FeasibilityFigureSvg(double max_leg_length, double body_length, double buffer,
                                 const std::vector<MarkedStair>& stairs) {
  if (!std::isfinite(max_leg_length) || max_leg_length <= 0.0 || !std::isfinite(body_length) || body_length <= 0.0) {
    throw std::invalid_argument("FeasibilityFigureSvg: leg and body lengths must be finite numbers > 0");
  }
  if (!std::isfinite(buffer) || buffer < 0.0 || buffer >= 1.0) {
    throw std::invalid_argument("FeasibilityFigureSvg: buffer must be in [0, 1)");
  }
  const double l = max_leg_length / body_length;
  std::string svg =
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"640\" height=\"590\" font-family=\"sans-serif\" font-size=\"12\">\n"
      "<rect width=\"640\" height=\"590\" fill=\"#fff\"/>\n";
  svg += FeasibleCells(l, buffer);
  svg += Boundaries(l, buffer);
  svg += CodeRanges(body_length);
  svg += Stairs(stairs, body_length);
  svg += Axes();
  svg += Legend(l, buffer);
  return svg + "</svg>\n";
}

}  // namespace stairplan
