// Our own URDF-to-KDL converter. ROS's kdl_parser would do the same job but links ROS 1 (roscpp,
// rosconsole, log4cxx) and warns about a root link with inertia; this one needs only urdfdom and KDL.
#pragma once

#include <kdl/tree.hpp>

namespace urdf {
class ModelInterface;
}

namespace stairplan {

/// A KDL tree with one segment per URDF joint, named after the joint's child link, rooted at the
/// URDF's root link. Revolute and continuous joints become rotational KDL joints about their axis,
/// prismatic joints translational ones, everything else (fixed, floating, planar) a fixed joint.
/// The root link has no segment, so its inertia (often absent, e.g. Unitree's `base`) is not
/// carried; the inertias of all other links are, expressed at their link origin.
/// Throws std::invalid_argument naming the joint when KDL refuses a segment.
KDL::Tree UrdfToKdlTree(const urdf::ModelInterface& model);

}  // namespace stairplan
