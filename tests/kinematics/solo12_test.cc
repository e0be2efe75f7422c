// Solo 12 (../shared/data/robots/solo12): a real quadruped whose collision geometry is STL meshes
// named by package:// URIs. It loads with the package path, its legs are found and named, its
// kinematics match the URDF's joint origins, and its mesh feet get their contact points.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <optional>
#include <random>

#include "stairplan/kinematics/robot_kinematics.h"
#include "stairplan/kinematics/robot_model.h"
#include "test_paths.h"

using stairplan::FootContact;
using stairplan::MeshSettings;
using stairplan::PackagePath;
using stairplan::RobotModel;
using stairplan::testing::SharedPath;

namespace {

struct Solo {
  std::string urdf, packages;
};

// Empty when ../shared is absent (the caller skips).
Solo SoloFiles() {
  const std::string folder = SharedPath("data/robots/solo12");
  return folder.empty() ? Solo{} : Solo{folder + "/solo12.urdf", folder};
}

MeshSettings WithPackages(const std::string& packages) {
  MeshSettings settings;
  settings.package_path = PackagePath::FromString(packages);
  settings.use_ros_package_path = false;
  return settings;
}

// Solo 12 loaded with its package path; empty (with a WARN) when ../shared is absent.
std::optional<RobotModel> LoadSolo() {
  const Solo solo = SoloFiles();
  if (solo.urdf.empty()) {
    WARN("Solo 12 skipped: ../shared not found");
    return std::nullopt;
  }
  return RobotModel::FromUrdfFile(solo.urdf, {}, WithPackages(solo.packages));
}

}  // namespace

TEST_CASE("Solo 12 loads with its package path: legs found and named", "[solo12]") {
  const std::optional<RobotModel> solo = LoadSolo();
  if (!solo) return;
  const RobotModel& robot = *solo;
  CHECK(robot.meshes().size() == 17);  // base, and per leg shoulder, upper leg, lower leg, foot
  REQUIRE(robot.legs().size() == 4);
  const char* feet[4][2] = {{"LF", "FL_FOOT"}, {"RF", "FR_FOOT"}, {"LH", "HL_FOOT"}, {"RH", "HR_FOOT"}};
  for (int l = 0; l < 4; ++l) {
    const auto& leg = robot.legs()[static_cast<std::size_t>(l)];
    INFO(leg.name);
    CHECK(leg.name == feet[l][0]);
    CHECK(leg.foot_link == feet[l][1]);
    CHECK(leg.joint_names.size() == 3);
    // The HAA joint origins of the URDF, and the foot at zero angles: the hip plus the y offsets of
    // HFE (0.014), KFE (0.03745) and the ankle (0.008), thigh and shank 0.16 m each straight down.
    const double sx = leg.name[1] == 'F' ? 1.0 : -1.0, sy = leg.name[0] == 'L' ? 1.0 : -1.0;
    CHECK(leg.hip_B.isApprox(Eigen::Vector3d(sx * 0.1946, sy * 0.0875, 0.0), 1e-12));
    CHECK(leg.foot_zero_B.isApprox(Eigen::Vector3d(sx * 0.1946, sy * 0.14695, -0.32), 1e-12));
  }
  CHECK(robot.hip_length() == Approx(0.3892));
  CHECK(robot.hip_width() == Approx(0.175));
}

TEST_CASE("Solo 12's forward kinematics match its joint origins and axes", "[solo12]") {
  const std::optional<RobotModel> solo = LoadSolo();
  if (!solo) return;
  const RobotModel& robot = *solo;
  const stairplan::RobotKinematics kinematics(robot);
  stairplan::RobotWorkspace ws(kinematics);
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> angle(-1.5, 1.5);
  for (int l = 0; l < 4; ++l) {
    const auto& leg = kinematics.leg(l);
    const double sy = leg.name()[0] == 'L' ? 1.0 : -1.0;
    for (int trial = 0; trial < 50; ++trial) {
      const Eigen::Vector3d q(angle(rng), angle(rng), angle(rng));
      // HAA about x at the hip; HFE and KFE about y; thigh and shank 0.16 m.
      const double x = -0.16 * std::sin(q(1)) - 0.16 * std::sin(q(1) + q(2));
      const double z = -0.16 * std::cos(q(1)) - 0.16 * std::cos(q(1) + q(2));
      const Eigen::Vector3d in_hip(x, sy * (0.014 + 0.03745 + 0.008), z);
      const Eigen::Vector3d expected = leg.model().hip_B + Eigen::AngleAxisd(q(0), Eigen::Vector3d::UnitX()) * in_hip;
      INFO(leg.name() << " q " << q.transpose());
      CHECK((leg.FootPosition(q, ws.leg(l)) - expected).norm() < 1e-12);
    }
  }
}

TEST_CASE("Solo 12's mesh feet touch down at their lowest point along the leg", "[solo12]") {
  const std::optional<RobotModel> solo = LoadSolo();
  if (!solo) return;
  const RobotModel& robot = *solo;
  const stairplan::RobotKinematics kinematics(robot);
  stairplan::RobotWorkspace ws(kinematics);
  for (int l = 0; l < 4; ++l) {
    const auto& leg = kinematics.leg(l);
    const auto& model = leg.model();
    INFO(model.name);
    CHECK(model.foot_contact == FootContact::kMeshLowestPoint);
    // The foot mesh is a wheel of radius 16 mm about the foot origin, 16.5 mm thick along y: its
    // lowest point along any direction in its x-z plane is on the rim, across its thickness.
    const Eigen::Vector3d& contact = model.foot_contact_point;
    CHECK(Eigen::Vector2d(contact.x(), contact.z()).norm() == Approx(0.016).margin(2e-4));
    CHECK(std::abs(contact.y()) < 0.00825);
    // ... and it is the point furthest along the leg (hip to foot) in the nominal stance.
    const Eigen::Isometry3d foot = leg.FootPose(leg.nominal(), ws.leg(l));
    const Eigen::Vector3d along = (foot.translation() - model.hip_B).normalized();
    CHECK((foot.linear() * contact).normalized().dot(along) > 0.99);
    // The wheel rolls about the knee axis: it is the sphere of its rim, centred on the foot origin
    // (its middle plane), whose bottom along the leg is that contact point.
    CHECK(model.foot_radius == Approx(0.016).margin(5e-4));
    CHECK(model.foot_sphere_center.norm() < 1e-4);
    const Eigen::Vector3d along_F = foot.linear().transpose() * along;
    CHECK(model.foot_sphere_center.dot(along_F) + model.foot_radius == Approx(contact.dot(along_F)).margin(3e-4));
  }
}

TEST_CASE("Solo 12 without its package path names the URI, the link and the folders searched", "[solo12]") {
  const Solo solo = SoloFiles();
  if (solo.urdf.empty()) {
    WARN("Solo 12 skipped: ../shared not found");
    return;
  }
  std::string error;
  try {
    RobotModel::FromUrdfFile(solo.urdf, {}, WithPackages("/nonexistent/one:/nonexistent/two"));
  } catch (const std::invalid_argument& e) {
    error = e.what();
  }
  CHECK_THAT(error, Catch::StartsWith(solo.urdf + ": <link name=\""));
  CHECK_THAT(error, Catch::Contains("package://example-robot-data/robots/solo_description/meshes/stl/"));
  CHECK_THAT(error, Catch::Contains("/nonexistent/one, /nonexistent/two"));
}

TEST_CASE("Solo 12 loads through ROS_PACKAGE_PATH, and its meshes are read once per process", "[solo12]") {
  const Solo solo = SoloFiles();
  if (solo.urdf.empty()) {
    WARN("Solo 12 skipped: ../shared not found");
    return;
  }
  const char* saved = std::getenv("ROS_PACKAGE_PATH");
  const std::string restore = saved ? saved : "";
  setenv("ROS_PACKAGE_PATH", solo.packages.c_str(), 1);
  const RobotModel first = RobotModel::FromUrdfFile(solo.urdf);
  const std::size_t read = stairplan::MeshFilesRead();
  const RobotModel second = RobotModel::FromUrdfFile(solo.urdf);
  if (saved) {
    setenv("ROS_PACKAGE_PATH", restore.c_str(), 1);
  } else {
    unsetenv("ROS_PACKAGE_PATH");
  }
  CHECK(stairplan::MeshFilesRead() == read);
  CHECK(second.meshes().Find("FL_FOOT", 0) == first.meshes().Find("FL_FOOT", 0));
  // The four feet share one file: one mesh in memory.
  CHECK(first.meshes().Find("FL_FOOT", 0) == first.meshes().Find("HR_FOOT", 0));
}
