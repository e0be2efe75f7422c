// The SVG of `stairplan qp bench --plot`: one panel per regime, in each the fraction of problems
// every solver solved at qpbenchmark's 1e-6 within a CPU time (log scale): higher and further
// left is better; a curve that stops below 1 is the solver's failures.
#pragma once

#include <string>
#include <vector>

namespace stairplan::cli {

/// One solver's curve in one panel.
struct QpBenchCurve {
  std::string solver;
  std::vector<double> solved_us;  ///< CPU times of the problems it solved (any order)
};

/// One regime's panel.
struct QpBenchPanel {
  std::string title;  ///< e.g. "cold, 34 problems"
  int problems = 0;
  std::vector<QpBenchCurve> curves;
};

/// The whole SVG document; `caption` goes under the panels (machine, tolerance, time measure).
std::string QpBenchPlotSvg(const std::vector<QpBenchPanel>& panels, const std::string& caption);

}  // namespace stairplan::cli
