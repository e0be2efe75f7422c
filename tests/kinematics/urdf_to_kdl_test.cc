// Our URDF-to-KDL converter: one segment per joint, fixed joints kept, masses carried.
#include <catch2/catch.hpp>

#include <kdl/tree.hpp>
#include <urdf_model/model.h>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/kinematics/robot_model.h"
#include "stairplan/kinematics/urdf_to_kdl.h"
#include "robot_files.h"

TEST_CASE("the KDL tree has one segment per joint and the URDF's masses", "[urdf_to_kdl]") {
  for (const auto& file : stairplan::testing::TestRobots()) {
    INFO(file.label);
    const stairplan::RobotModel robot =
        file.path.empty() ? stairplan::BuiltinRobot() : stairplan::RobotModel::FromUrdfFile(file.path);
    const KDL::Tree tree = stairplan::UrdfToKdlTree(robot.urdf());
    CHECK(tree.getNrOfSegments() == robot.urdf().joints_.size());
    int movable = 0;
    double mass = 0.0;
    for (const auto& [name, joint] : robot.urdf().joints_) {
      movable += (joint->type == urdf::Joint::REVOLUTE || joint->type == urdf::Joint::CONTINUOUS ||
                  joint->type == urdf::Joint::PRISMATIC);
    }
    CHECK(static_cast<int>(tree.getNrOfJoints()) == movable);
    for (const auto& [name, element] : tree.getSegments()) mass += element.segment.getInertia().getMass();
    const auto root = robot.urdf().getRoot();
    const double root_mass = root->inertial ? root->inertial->mass : 0.0;
    // The root link has no segment; every other link's mass is carried.
    CHECK(mass == Approx(robot.total_mass() - root_mass).epsilon(1e-12));
    CHECK(tree.getRootSegment()->first == root->name);
  }
}
