// The paper's Figure 4(b) (Chen, Ko, Li, Lin 2012, "Stair Climbing in a Quadruped Robot"): the
// cross-section of the feasible volume of (14)-(16) at a given l_max/BL and p, in the plane of W/BL
// and H/BL, with the paper's three stairs and the building-code ranges of real stairs marked.
// Returned as SVG text; the caller writes it.
#pragma once

#include <string>
#include <vector>

namespace stairplan {

/// A stair to mark on the chart [m].
struct MarkedStair {
  double run = 0.0;  ///< tread depth W [m]
  double rise = 0.0;  ///< riser height H [m]
  std::string label;  ///< its label on the chart
};

/// The paper's stairs: nominal 27 x 17 cm, and the two it climbed, 31 x 17.5 and 28 x 16 cm.
std::vector<MarkedStair> PaperStairs();

/// Draws Figure 4(b) for a robot with `max_leg_length` and `body_length` [m] and buffer p.
/// Throws std::invalid_argument when a size is not a finite positive number or p is outside [0, 1).
std::string FeasibilityFigureSvg(double max_leg_length, double body_length, double buffer,
                                 const std::vector<MarkedStair>& stairs);

}  // namespace stairplan
