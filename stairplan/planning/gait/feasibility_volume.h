// The paper's design chart (Chen, Ko, Li, Lin 2012, "Stair Climbing in a Quadruped Robot", eqs.
// (14)-(16) and Figure 4): the interference conditions (11)-(13) divided through by the body length
// BL, so that the feasible designs form a volume in (W/BL, H/BL, l_max/BL) for a given buffer
// fraction p.
//
// The seed's text of (14)-(16) lost its exponents in extraction; these are the forms that follow
// from (11)-(13) by squaring (each side is non-negative for CL < BL < 2CL, the paper's assumption):
//   (14) (l/BL)^2 <= (CL/2BL)^2 + [(3 - p/2) CL/BL - 1]^2 / [(2 - p) W/H]^2
//   (15) (l/BL)^2 <= (CL/2BL)^2 + [(p/2) CL/BL - 1]^2 / [(2 - p) W/H]^2
//   (16) l/BL >= (1/2) (CL/BL)^2 / (W/BL)
// Outside that assumption a right side that is negative before squaring makes the condition fail.
#pragma once

namespace stairplan {

/// A design in dimensionless form: every length divided by BL.
struct DimensionlessDesign {
  double run = 0.0;         ///< W / BL
  double rise = 0.0;        ///< H / BL
  double max_leg = 0.0;     ///< l_max / BL
  double buffer = 0.42;     ///< p
};

/// Which of (14)-(16) hold.
struct DimensionlessVerdict {
  bool c14 = false;  ///< front-left swing not overlapping the hind-right one, from (11)
  bool c15 = false;  ///< front-right swing not overlapping the hind-left one, from (12)
  bool c16 = false;  ///< l_max >= l_min, from (13)
  /// CL < BL < 2CL, the assumption under which (11)-(13) replace (8)-(10).
  bool in_body_range = false;
  /// True when (14), (15) and (16) all hold.
  bool feasible() const { return c14 && c15 && c16; }
};

/// Evaluates (14)-(16). Non-positive or non-finite sizes give a verdict with nothing holding.
DimensionlessVerdict EvaluateDimensionless(const DimensionlessDesign& design);

}  // namespace stairplan
