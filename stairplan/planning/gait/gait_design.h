// The gait design of "Stair Climbing in a Quadruped Robot" (Chen, Ko, Li, Lin, 2012): minimum leg
// length, contact offsets, swing separations and the four-leg interference conditions for a
// quasi-static crawl whose hips travel parallel to the stairs' edge line. Pure geometry.
//
// Symbols follow the paper: W tread depth (run), H rise, CL = sqrt(W^2 + H^2), phi = atan(H / W),
// d hip clearance (hip path to edge line), l leg length (hip to foot), BL body length (hip to hip),
// p buffer fraction. Distances D_* are hip travel along the slope. SI units (m, rad).
#pragma once

#include <array>
#include <optional>
#include <string>

namespace stairplan {

/// What the design needs: the stairs, the robot's leg and body sizes and two design choices.
struct GaitDesignInput {
  double rise = 0.17;         ///< H [m]
  double run = 0.27;          ///< W, tread depth [m]
  double max_leg_length = 0.21;  ///< l_max, hip to foot [m]
  double body_length = 0.444;    ///< BL, front hip to hind hip [m]
  double body_width = 0.36;      ///< BW, left to right foot, for the stability estimate [m]
  double buffer = 0.42;          ///< p: fraction of D_s kept between the right and left swings
  /// d: hip path above the edge line [m]. Unset means H / 2, the paper's simulation choice
  /// (d = 8.5 cm for H = 17 cm).
  std::optional<double> hip_clearance;

  /// d: hip_clearance when set, else H / 2 [m].
  double HipClearance() const { return hip_clearance ? *hip_clearance : 0.5 * rise; }
  /// Throws std::invalid_argument naming the field (non-finite, non-positive, p outside [0, 1)).
  void Validate() const;
};

/// One of the paper's inequalities, with how much room it leaves (negative when violated).
struct GaitCondition {
  const char* name = "";   ///< "(8)", "(9)", "(10)", ...
  const char* text = "";   ///< the inequality in words
  bool holds = false;  ///< true when the inequality holds
  double slack = 0.0;      ///< [m]; >= 0 when it holds
};

/// The design's numbers. NaN where a quantity does not exist (e.g. D_s when l_max < CL / 2).
struct GaitDesign {
  double cl = 0.0;         ///< characteristic length CL [m]
  double phi = 0.0;        ///< stair slope [rad]
  double l_min = 0.0;      ///< eq. (1) [m]
  double d = 0.0;          ///< hip clearance used [m]
  double a_min = 0.0;      ///< contact offset at l = l_min, eq. (4) (right legs) [m]
  double a_max = 0.0;      ///< contact offset at l = l_max, eq. (3) (left legs) [m]
  double d_s = 0.0;        ///< D_s, eq. (5): separation of the right and left swing starts [m]
  double d_i = 0.0;        ///< D_i, eq. (6): one leg's swing [m]
  double d_o = 0.0;        ///< D_o, eq. (7): one leg pair's swings with the buffer [m]
  double rem = 0.0;        ///< rem(BL, CL) [m]
  /// In checking order: (10) l_max > l_min, (8) rem + D_o <= CL, (9) rem >= D_o, then that both
  /// contact offsets lie on the tread: "(4)" a_min >= 0 (d not too large), "(3)" a_max <= W.
  std::array<GaitCondition, 5> conditions{};
  bool feasible = false;  ///< every condition holds
  /// The violated condition checked first when infeasible; the tightest one when feasible.
  std::string binding;
};

/// l_min = (W^2 + H^2) / (2 W), eq. (1).
double MinLegLength(double run, double rise);
/// a(l, d) = (sqrt(l^2 - CL^2 / 4) - d) csc(phi), eq. (3); NaN when l < CL / 2.
double ContactOffset(double leg_length, double hip_clearance, double run, double rise);
/// D_s = (W / H) sqrt(l_max^2 - CL^2 / 4) - CL / 2, eq. (5); NaN when l_max < CL / 2.
double SwingStartSeparation(double max_leg_length, double run, double rise);
/// The remainder of x / y for y > 0, in [0, y) (rem in the paper's eqs. (8) and (9)).
double Remainder(double x, double y);

/// Evaluates the whole design. Throws std::invalid_argument on bad input; an infeasible design is
/// a result (feasible = false, binding names the condition), not an exception.
GaitDesign DesignGait(const GaitDesignInput& input);

}  // namespace stairplan
