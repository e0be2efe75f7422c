// The first planner: a quasi-static crawl that puts every foot at the centre of a step region,
// one stair per cycle, with four-feet phases between swings in which the centre of mass moves
// over the next support triangle, and the body carried above the feet at a fixed hip height. Later planners
// (step planner, body planner) replace its parts; it stays as a simple, predictable baseline.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "stairplan/geometry/constrained_map.h"
#include "stairplan/geometry/staircase.h"
#include "stairplan/kinematics/robot_model.h"
#include "stairplan/planning/body_path.h"
#include "stairplan/planning/plan.h"
#include "stairplan/planning/swing_trajectory.h"

namespace stairplan {

/// The order in which the crawl swings its legs, one at a time, within a cycle, along the travel:
/// the trailing legs are the hind legs facing forward and the front legs facing backward.
enum class CrawlSequence {
  /// The trailing pair, then the leading pair (the 2012 paper's crawl: facing forward right hind,
  /// left hind, right front, left front). Between the pairs the stance is a stride shorter: a short robot's
  /// trailing feet land just behind its leading feet, and the next support triangle is a sliver
  /// the COM must cross the body to reach.
  kPairs,
  /// Each side's trailing leg, then its leading leg, right side first (the lateral-sequence crawl
  /// of McGhee and Frank, 1968, the most stable order of a crawl). The stance keeps its length,
  /// and the COM moves across once a cycle.
  kLateral,
  /// Each side's leading leg, then its trailing leg, right side first. The COM gives up some of
  /// its lead before each leading swing, but the stance stretches where kLateral's shortens: a
  /// trailing leg swings toward a neighbour that has already stepped on (Unitree A1, its front
  /// knees pointing back, climbs the low stairs backward only in this order).
  kLateralLeadingFirst,
};

/// The other order of the same kind, tried where no body is found on the first: kLateral and
/// kLateralLeadingFirst each other's; kPairs none (itself).
CrawlSequence OtherLateralOrder(CrawlSequence sequence);

/// "pairs", "lateral" or "leading-first"; throws std::invalid_argument otherwise.
CrawlSequence ParseCrawlSequence(const std::string& text);

/// The crawl planner's timing, foothold layout and search.
struct CrawlSettings {
  CrawlSequence sequence = CrawlSequence::kLateral;  ///< the order of the swings
  double swing_duration = 0.40;       ///< one leg's swing [s]
  double shift_duration = 0.60;       ///< four feet down between swings, moving the COM [s]
  /// The diagonal pairs swing together (the trot): the same footholds and cycles, two swing slots
  /// a cycle instead of four, each preceded by shift_duration with four feet down.
  bool diagonal_pairs = false;
  double start_gap = 0.10;            ///< front feet this far before the first step region [m]
  /// Move the trailing feet inside their step regions to one stance length (hip spacing along the
  /// pitched body) behind the leading feet, instead of the step-region centres. Off by default:
  /// the body QP's reach bounds do not yet hold on those footholds (its NLP test plan turns
  /// infeasible), although the quasi-static path validates on them.
  bool keep_stance_length = false;
  /// Trailing feet stay this far inside their step region when they move to keep the stance length [m].
  double trailing_margin = 0.01;
  /// Treads from the trailing to the leading feet at the start (0: each foot starts at the
  /// foothold nearest under its hip).
  int stance_treads = 0;
  /// Leading and trailing feet this far forward (along travel) of their step region's centre,
  /// kept trailing_margin inside the region [m].
  double lead_offset = 0.0;
  double trail_offset = 0.0;  ///< trailing feet's offset, as lead_offset [m]
  /// The leading and trailing legs' first stride as a share of the others: they start that far
  /// behind their first touchdown (1: on the lattice).
  double lead_first_stride = 1.0;
  double trail_first_stride = 1.0;  ///< the trailing legs' first stride, as lead_first_stride
  /// When a touchdown of the plan fails the stance check (a leg out of reach, beyond its limits or
  /// against the stairs), other foothold layouts fitted to the robot's hip spacing are screened
  /// (stance checks at their touchdowns) and up to this many of them planned in full; the first
  /// whose every touchdown passes is returned, else the layout given, or, when a foot of that one
  /// lands where another still stands, the least unstandable layout whose feet keep apart.
  /// 0: no search.
  int fit_footholds = 1;
  /// Every swing's support triangle (the other three feet, seen from above) holds a circle this
  /// large, so that the centre of mass can stand inside it with the validator's stability margin
  /// (1 cm) to spare. A layout that breaks it (a trailing foot landing on or just beside a leading
  /// foot that has not lifted yet) fails as a touchdown the stance check refuses [m].
  double min_support_inradius = 0.02;
  /// When positive, a plan whose body accelerates faster than this between its samples [m/s^2]
  /// also fails (the posture fit found no smooth correction for some swing: it jumps there), so
  /// the layout search runs for it and a layout replacing it must not jump either. 0: off.
  double refit_body_acceleration = 0.0;
  /// Where the feet start, one contact point per leg in the robot's order (the alignment pose's
  /// stance, stairplan/planning/stair_alignment.h): each leg's footholds are laid from the one nearest its
  /// start as usual, and its first swing leaves from the start. Empty: each foot starts on the
  /// foothold nearest under its hip with the body start_gap before the flight.
  std::vector<Eigen::Vector3d> start_feet;
  BodyPathSettings body;              ///< how the body follows the feet
  SwingSettings swing;                ///< how high the feet swing over the stairs

  /// Throws std::invalid_argument naming the field.
  void Validate() const;
};

/// The foothold layouts fitted to the robot's hip spacing that the crawl's foothold search tries
/// (see fit_footholds), as `settings` that plan each of them with no search of their own, the
/// most promising first. The number of treads between the leading and the trailing feet: the
/// one nearest the hip spacing along the pitched body, one fewer and one more; the pairs' offsets
/// in their step regions for each: the one that fits it best, the most the regions allow the
/// other way, and none; the trailing legs' first stride whole or halved. The best-fitting offsets
/// of all three tread counts come first, then the others in that order, each with the whole first
/// strides before the halved ones.
std::vector<CrawlSettings> FittedLayouts(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map,
                                         const CrawlSettings& settings);

/// Touchdowns of a plan on a foothold another foot still stands on (CrowdedTouchdowns()).
struct TouchdownCrowding {
  int touchdowns = 0;  ///< how many
  ///@{
  /// The first of them: when, the leg landing and the leg it lands on.
  double first_t = 0.0;
  std::string leg, onto;
  ///@}
};

/// Touchdowns of `plan` on a foothold another foot still stands on (their feet overlap seen from
/// above; radii from `robot`'s legs, which name the plan's): a short robot's hind foot landing
/// where its front foot has not lifted from yet. No body makes such a plan valid: the feet would
/// stand in each other.
TouchdownCrowding CrowdedTouchdowns(const RobotModel& robot, const Plan& plan);

/// The crawl's footsteps on the layout `settings` give, for a body planner to carry the body
/// over: no posture fit and no foothold search (those judge footholds by the quasi-static path),
/// and no body. Never throws for geometry it cannot handle.
Plan PlanCrawlFootholds(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map,
                        const CrawlSettings& settings = {});

/// Plans a crawl over `stairs` for `robot` on `map`. Never throws for geometry it cannot
/// handle: the plan's status says infeasible and why.
Plan PlanCrawl(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map,
               const CrawlSettings& settings = {});

}  // namespace stairplan
