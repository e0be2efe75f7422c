// Leg forward kinematics against positions composed independently from the URDF text, the
// Jacobian against finite differences, knee and link frames, reach.
#include <catch2/catch.hpp>

#include <map>
#include <random>
#include <sstream>

#include <tinyxml.h>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/kinematics/robot_kinematics.h"
#include "robot_files.h"

using stairplan::LegKinematics;
using stairplan::LegWorkspace;
using stairplan::RobotKinematics;
using stairplan::RobotModel;

namespace {

struct JointOrigin {
  std::string parent;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
};

Eigen::Vector3d Triple(const char* text) {
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  if (!text) return v;
  std::istringstream in(text);
  in >> v.x() >> v.y() >> v.z();
  return v;
}

// child link -> (parent link, joint origin), read straight from the XML (no urdfdom, no KDL).
std::map<std::string, JointOrigin> ReadJointOrigins(const std::string& xml) {
  TiXmlDocument doc;
  doc.Parse(xml.c_str());
  REQUIRE_FALSE(doc.Error());
  std::map<std::string, JointOrigin> joints;
  for (const TiXmlElement* j = doc.FirstChildElement("robot")->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
    JointOrigin jo;
    jo.parent = j->FirstChildElement("parent")->Attribute("link");
    if (const TiXmlElement* o = j->FirstChildElement("origin")) {
      const Eigen::Vector3d rpy = Triple(o->Attribute("rpy"));
      jo.origin.linear() = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                            Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                            Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX())).toRotationMatrix();
      jo.origin.translation() = Triple(o->Attribute("xyz"));
    }
    joints[j->FirstChildElement("child")->Attribute("link")] = jo;
  }
  return joints;
}

std::string ReadUrdf(const stairplan::testing::RobotFile& file) {
  return file.path.empty() ? stairplan::BuiltinRobotUrdf() : stairplan::testing::ReadFile(file.path);
}

}  // namespace

TEST_CASE("foot FK at zero matches the URDF's composed joint origins to 1e-9", "[leg_kinematics]") {
  for (const auto& file : stairplan::testing::TestRobots()) {
    INFO(file.label);
    const std::string xml = ReadUrdf(file);
    const RobotModel robot = RobotModel::FromUrdfString(xml, file.label);
    const RobotKinematics kinematics(robot);
    const auto joints = ReadJointOrigins(xml);
    for (const LegKinematics& leg : kinematics.legs()) {
      INFO(leg.name());
      Eigen::Isometry3d expected = Eigen::Isometry3d::Identity();
      for (std::string link = leg.model().foot_link; link != robot.base_link(); link = joints.at(link).parent) {
        expected = joints.at(link).origin * expected;
      }
      LegWorkspace ws(leg);
      const Eigen::Isometry3d foot = leg.FootPose(Eigen::Vector3d::Zero(), ws);
      CHECK((foot.translation() - expected.translation()).norm() < 1e-9);
      CHECK((foot.linear() - expected.linear()).norm() < 1e-9);
      CHECK((leg.FootPosition(Eigen::Vector3d::Zero(), ws) - leg.model().foot_zero_B).norm() < 1e-9);
    }
  }
}

TEST_CASE("link frames end at the foot and the knee frame is the last movable joint's", "[leg_kinematics]") {
  const RobotKinematics kinematics(stairplan::BuiltinRobot());
  const LegKinematics& leg = kinematics.leg("LF");
  LegWorkspace ws(leg);
  REQUIRE(leg.segment_count() == 4);  // HAA, HFE, KFE, fixed foot
  CHECK(leg.segment_link(3) == "LF_foot");
  CHECK(leg.segment_link(leg.knee_segment()) == "LF_shank");
  const Eigen::Vector3d q(0.2, 0.7, -1.4);
  const auto& frames = leg.LinkFrames(q, ws);
  CHECK((frames.back().translation() - leg.FootPosition(q, ws)).norm() < 1e-12);
  CHECK((frames[2].translation() - leg.KneePosition(q, ws)).norm() < 1e-12);
  // stairbot by hand: hip at (0.30, 0.10, 0), thigh 0.30 and shank 0.30 in the plane rotated by HAA.
  const double haa = q(0), hfe = q(1), kfe = q(2);
  const Eigen::Vector3d knee_in_plane(-0.30 * std::sin(hfe), 0.08, -0.30 * std::cos(hfe));
  const Eigen::Vector3d foot_in_plane = knee_in_plane + Eigen::Vector3d(-0.30 * std::sin(hfe + kfe), 0.0, -0.30 * std::cos(hfe + kfe));
  const Eigen::Matrix3d rx = Eigen::AngleAxisd(haa, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::Vector3d hip(0.30, 0.10, 0.0);
  CHECK((leg.KneePosition(q, ws) - (hip + rx * knee_in_plane)).norm() < 1e-12);
  CHECK((leg.FootPosition(q, ws) - (hip + rx * foot_in_plane)).norm() < 1e-12);
}

TEST_CASE("the foot Jacobian matches central finite differences", "[leg_kinematics]") {
  std::mt19937 rng(7);
  for (const auto& file : stairplan::testing::TestRobots()) {
    INFO(file.label);
    const RobotKinematics kinematics(RobotModel::FromUrdfString(ReadUrdf(file), file.label));
    for (const LegKinematics& leg : kinematics.legs()) {
      LegWorkspace ws(leg);
      for (int trial = 0; trial < 20; ++trial) {
        Eigen::Vector3d q;
        for (int j = 0; j < 3; ++j) {
          q(j) = std::uniform_real_distribution<double>(std::max(leg.lower()(j), -3.0), std::min(leg.upper()(j), 3.0))(rng);
        }
        const Eigen::Matrix3d J = leg.FootJacobian(q, ws);
        Eigen::Matrix3d fd;
        const double h = 1e-6;
        for (int j = 0; j < 3; ++j) {
          Eigen::Vector3d dq = Eigen::Vector3d::Zero();
          dq(j) = h;
          fd.col(j) = (leg.FootPosition(q + dq, ws) - leg.FootPosition(q - dq, ws)) / (2 * h);
        }
        CHECK((J - fd).norm() < 1e-7);
      }
    }
  }
}

TEST_CASE("reach bounds hold for random configurations and the nominal pose stands", "[leg_kinematics]") {
  std::mt19937 rng(11);
  for (const auto& file : stairplan::testing::TestRobots()) {
    INFO(file.label);
    const RobotKinematics kinematics(RobotModel::FromUrdfString(ReadUrdf(file), file.label));
    for (const LegKinematics& leg : kinematics.legs()) {
      INFO(leg.name());
      LegWorkspace ws(leg);
      CHECK(leg.reach().lo >= 0.0);
      CHECK(leg.reach().hi <= leg.model().max_reach + 1e-9);  // the sum of offsets bounds it
      CHECK(leg.reach().hi > 0.7 * leg.model().max_reach);  // knee limits keep Unitree legs from straightening
      // Sampled bounds: allow a little slack for configurations between grid points.
      for (int trial = 0; trial < 200; ++trial) {
        Eigen::Vector3d q;
        for (int j = 0; j < 3; ++j) q(j) = std::uniform_real_distribution<double>(leg.lower()(j), leg.upper()(j))(rng);
        const double d = (leg.FootPosition(q, ws) - leg.hip_B()).norm();
        CHECK(d <= leg.reach().hi + 0.01);
        CHECK(d >= leg.reach().lo - 0.01);
      }
      CHECK(leg.WithinLimits(leg.nominal()));
      const Eigen::Vector3d foot = leg.FootPosition(leg.nominal(), ws);
      CHECK(foot.z() < leg.hip_B().z() - 0.5 * leg.model().max_reach);  // standing: foot well below the hip
      // Knee towards the body centre when the limits allow it (ANYmal, stairbot's front legs).
      const Eigen::Vector3d knee = leg.KneePosition(leg.nominal(), ws);
      if (file.label.rfind("anymal", 0) == 0) {
        CHECK((knee.x() - 0.5 * (foot.x() + leg.hip_B().x())) * leg.hip_B().x() < 0.0);
      }
    }
  }
}
