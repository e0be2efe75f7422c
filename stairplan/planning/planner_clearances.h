// The clearances a plan's planners kept: their margins raised by the uncertainty of the stairs
// planned on (WithStairUncertainty, stairplan/pipeline/plan_pipeline.h), as plan.json's `clearance` reports them.
#pragma once

namespace stairplan {

/// The clearances the planners kept on the stairs planned on [m]: each planner's own margin raised
/// by the stairs' uncertainty (WithStairUncertainty). plan.json's `clearance` reports them.
struct PlannerClearances {
  double stairs_uncertainty = 0.0;   ///< StairSpec::uncertainty of the stairs planned on
  double body_qp = 0.0;              ///< BodyPlannerSettings::clearance_margin (the body optimisation's rows keep theirs on top)
  double touchdown = 0.0;            ///< BodyPathSettings::touchdown_clearance (the quasi-static path's posture fit; not raised)
  double swing = 0.0;                ///< SwingSettings::clearance (swing feet over the stairs)
  double edge_margin = 0.0;          ///< ConstrainedMapSettings::edge_margin (footholds off the walking edges; not raised)
  double riser_margin = 0.0;         ///< ConstrainedMapSettings::riser_margin (footholds off the risers above; not raised)
  double validator = 0.0;            ///< ValidationSettings::min_clearance: the judge's, on the stairs it is given (not raised)
};

}  // namespace stairplan
