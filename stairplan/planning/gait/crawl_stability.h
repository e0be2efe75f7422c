// Quasi-static stability of the paper's crawl (Chen, Ko, Li, Lin 2012, "Stair Climbing in a
// Quadruped Robot", "Stability Analysis"): over one cycle of hip travel (one CL), the fraction
// during which the centre of mass, projected on the ground, lies outside the support polygon of the
// feet on the stairs (the triangle of the three stance feet while one leg swings).
//
// The model is the paper's: hips travel along a line parallel to the edge line at clearance d, the
// body is inclined with the stairs, the COM is midway between the hips, each leg lifts off when its
// hip passes the point where its contact offset puts it (eq. (3)) and swings for D_i.
#pragma once

#include <array>

#include "stairplan/planning/gait/gait_design.h"

namespace stairplan {

/// The two arrangements of contact offsets in the paper: case 1, right legs at a_min and left
/// legs at a_max; case 2, the front pair switched.
enum class CrawlCase { kRightFirst = 1, kFrontSwitched = 2 };

/// The stability estimate for one arrangement.
struct CrawlStability {
  CrawlCase arrangement = CrawlCase::kRightFirst;  ///< case 1 or case 2
  /// Legs in the order they swing within one cycle, starting with the right hind leg (names as
  /// everywhere in stairplan: LF, RF, LH, RH).
  std::array<const char*, 4> swing_sequence{};
  /// Fraction of a cycle with the COM outside the support polygon (two legs in the air counts
  /// as outside) [0, 1].
  double fraction_outside = 0.0;
  /// The same as a share of the time some leg is in the air (4 D_i of each CL) [0, 1].
  double fraction_of_swing_time = 0.0;
  /// The same split by the swinging leg, in the order RH, LH, RF, LF.
  std::array<double, 4> fraction_outside_by_leg{};
  /// The smallest stability margin over the cycle: the COM's distance to the nearest edge line of
  /// the support polygon, negative when outside [m]. Unlike the fraction, it scales with the body
  /// width (with the COM on the mid-line, the inside/outside verdict does not).
  double min_margin = 0.0;
};

/// The support at one instant of the crawl: which legs swing and where the COM stands in the
/// polygon of the others.
struct CrawlInstant {
  int legs_in_air = 0;  ///< how many legs swing (the design keeps it at most 1; more is a fault)
  /// The swinging leg, in the order RH, LH, RF, LF (0-3); -1 when all four stand. With several in
  /// the air, the last of them in that order.
  int swing_leg = -1;
  /// The stability margin: the COM's distance to the nearest edge line of the stance feet's
  /// polygon, negative when outside [m]; -infinity with two legs in the air.
  double margin = 0.0;
};

/// The instant of the paper's crawl when the hind hips are `hind_hip` along the hip line from the
/// point d above a nose [m] (the pattern repeats every CL): one sample of EvaluateCrawlStability,
/// for checks of a single swing or of the margin's course through a cycle.
CrawlInstant CrawlStabilityAt(const GaitDesignInput& input, const GaitDesign& design, CrawlCase arrangement,
                              double hind_hip);

/// Evaluates one arrangement by sampling `samples` hip positions evenly over one CL. Needs a
/// design with D_s > 0 (condition (10)); throws std::invalid_argument otherwise.
CrawlStability EvaluateCrawlStability(const GaitDesignInput& input, const GaitDesign& design, CrawlCase arrangement,
                                      int samples = 7200);

/// The share of a cycle that a hind leg is in the air, 2 D_i / CL: the most time the COM can
/// spend outside the support triangle when, as the paper finds for both cases, the front swings
/// keep it inside. The paper's 27.3 % and 30 % exceed it for its own parameters (20.9 %):
/// third_party_notes/chen2012_stair_climbing.md.
double HindSwingShare(const GaitDesign& design);

}  // namespace stairplan
